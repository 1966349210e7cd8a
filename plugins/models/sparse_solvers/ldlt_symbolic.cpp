#include "ldlt_symbolic.hpp"

#include <vector>

namespace tacta::models::sparse {

namespace {

// The elimination tree: column k's entries above the diagonal climb to the roots of the forest
// built so far, which k adopts; the climbed paths are shortened to point at k.
void elimination_tree(int n, const int* outer, const int* inner, std::span<int> parent) {
  std::vector<int> ancestor(n, -1);
  for (int k = 0; k < n; ++k) {
    parent[k] = -1;
    for (int p = outer[k]; p < outer[k + 1]; ++p)
      for (int i = inner[p]; i != -1 && i < k;) {
        const int up = ancestor[i];
        ancestor[i] = k;
        if (up == -1) parent[i] = k;
        i = up;
      }
  }
}

// The nodes in an order where every subtree is contiguous and ends at its root.
std::vector<int> postorder(int n, std::span<const int> parent) {
  std::vector<int> first_child(n, -1), next_sibling(n, -1), order, stack;
  order.reserve(n);
  for (int j = n - 1; j >= 0; --j)
    if (parent[j] != -1) {
      next_sibling[j] = first_child[parent[j]];
      first_child[parent[j]] = j;
    }
  for (int root = 0; root < n; ++root) {
    if (parent[root] != -1) continue;
    stack.push_back(root);
    while (!stack.empty()) {
      const int j = stack.back();
      const int child = first_child[j];
      if (child == -1) {
        order.push_back(j);
        stack.pop_back();
      } else {
        first_child[j] = next_sibling[child];
        stack.push_back(child);
      }
    }
  }
  return order;
}

}  // namespace

// Row i of L holds the nodes of its row subtree: the tree paths from each k < i with A(i, k) != 0
// up to i. Column j's count is the number of row subtrees holding j, summed over j's subtree as
// differences: +1 at each leaf of a row subtree, -1 where two of its leaves' paths meet (their
// least common ancestor, found with the tree so far as a disjoint set), -1 at each parent for the
// child below it. Nodes are taken in postorder, so j is a leaf of row i's subtree exactly when
// none of j's descendants was (first[j], the first descendant's rank, passes i's last leaf's).
void ldlt_symbolic(int n, const int* outer, const int* inner, std::span<int> parent,
                   std::span<int> below) {
  elimination_tree(n, outer, inner, parent);
  const std::vector<int> order = postorder(n, parent);
  std::vector<int> first(n, -1), delta(n, 0);
  for (int k = 0; k < n; ++k) {
    int j = order[k];
    delta[j] = first[j] == -1 ? 1 : 0;  // a leaf of the tree: its own diagonal
    for (; j != -1 && first[j] == -1; j = parent[j]) first[j] = k;
  }
  // The entries right of the diagonal in each row of the upper triangle (A(i, j), i > j, by j).
  std::vector<int> row_start(n + 1, 0), row_entries(outer[n]);
  for (int k = 0; k < n; ++k)
    for (int p = outer[k]; p < outer[k + 1]; ++p)
      if (inner[p] < k) ++row_start[inner[p] + 1];
  for (int j = 0; j < n; ++j) row_start[j + 1] += row_start[j];
  {
    std::vector<int> fill(row_start.begin(), row_start.end() - 1);
    for (int k = 0; k < n; ++k)
      for (int p = outer[k]; p < outer[k + 1]; ++p)
        if (inner[p] < k) row_entries[fill[inner[p]]++] = k;
  }
  std::vector<int> last_first(n, -1), last_leaf(n, -1), joined(n);
  for (int j = 0; j < n; ++j) joined[j] = j;
  for (int k = 0; k < n; ++k) {
    const int j = order[k];
    if (parent[j] != -1) --delta[parent[j]];
    for (int p = row_start[j]; p < row_start[j + 1]; ++p) {
      const int i = row_entries[p];
      if (first[j] <= last_first[i]) continue;  // not a leaf of row i's subtree
      last_first[i] = first[j];
      const int previous = last_leaf[i];
      last_leaf[i] = j;
      ++delta[j];
      if (previous == -1) continue;
      int meet = previous;
      while (meet != joined[meet]) meet = joined[meet];
      for (int s = previous; s != meet;) {
        const int up = joined[s];
        joined[s] = meet;
        s = up;
      }
      --delta[meet];
    }
    if (parent[j] != -1) joined[j] = parent[j];
  }
  for (int j = 0; j < n; ++j)  // a parent's index is above its children's
    if (parent[j] != -1) delta[parent[j]] += delta[j];
  for (int j = 0; j < n; ++j) below[j] = delta[j] - 1;
}

}  // namespace tacta::models::sparse
