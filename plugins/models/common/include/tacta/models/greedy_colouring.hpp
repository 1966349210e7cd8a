// Greedy graph colouring for the models' parallel passes (vbd's vertices, the corotational
// pass's tiles of element batches): items taken in index order, each given the lowest colour
// no earlier-coloured item it conflicts with holds, then listed colour by colour.
#pragma once

#include <cstdint>
#include <vector>

namespace tacta::models {

// Colour c's items are members[starts[c], starts[c + 1]), in index order.
struct ColourGroups {
  std::vector<uint32_t> starts, members;
};

// for_each_conflict(i, visit) calls visit(j) for the items j item i must not share a colour with
// (in any order, repeats allowed; j == i and items not coloured yet are ignored). Items with
// skip(i) get no colour and are in no group.
template <class ForEachConflict, class Skip>
ColourGroups greedy_colouring(uint32_t count, ForEachConflict&& for_each_conflict, Skip&& skip) {
  constexpr uint32_t kNone = UINT32_MAX;
  std::vector<uint32_t> colour(count, kNone), taken_by;  // taken_by[c] = i + 1: i conflicts on c
  for (uint32_t i = 0; i < count; ++i) {
    if (skip(i)) continue;
    for_each_conflict(i, [&](uint32_t j) {
      if (j != i && colour[j] != kNone) taken_by[colour[j]] = i + 1;
    });
    uint32_t c = 0;
    while (c < taken_by.size() && taken_by[c] == i + 1) ++c;
    if (c == taken_by.size()) taken_by.push_back(0);
    colour[i] = c;
  }
  ColourGroups groups;
  groups.starts.assign(taken_by.size() + 1, 0);
  for (uint32_t i = 0; i < count; ++i)
    if (colour[i] != kNone) ++groups.starts[colour[i] + 1];
  for (size_t c = 0; c < taken_by.size(); ++c) groups.starts[c + 1] += groups.starts[c];
  groups.members.resize(groups.starts.back());
  std::vector<uint32_t> fill(groups.starts.begin(), groups.starts.end() - 1);
  for (uint32_t i = 0; i < count; ++i)
    if (colour[i] != kNone) groups.members[fill[colour[i]]++] = i;
  return groups;
}

}  // namespace tacta::models
