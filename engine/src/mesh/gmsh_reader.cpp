// Gmsh .msh readers: v1 ($NOD/$ELM), v2.2 ASCII ($Nodes/$Elements with tags) and v4.1 ASCII
// (entity blocks). Format facts from the Gmsh reference manual, section "MSH file format".
#include <algorithm>
#include <cstdint>
#include <string>
#include <unordered_map>
#include <vector>

#include "mesh/volume_readers.hpp"
#include "mesh/text_reader.hpp"

namespace tacta::mesh_detail {

namespace {

// Nodes per element for Gmsh element types 1..31 (0 = unknown type).
int gmsh_nodes_per_element(int64_t type) {
  static constexpr int kNodes[] = {0, 2,  3,  4,  4, 8,  6,  5,  3,  6,  9, 10, 27, 18, 14, 1,
                                   8, 20, 15, 13, 9, 10, 12, 15, 15, 21, 4, 5,  6,  20, 35, 56};
  if (type < 1 || type > 31) return 0;
  return kNodes[type];
}

// Linear tet (4) and the higher-order ones whose first four nodes are the corners.
bool gmsh_is_tet(int64_t type) {
  return type == 4 || type == 11 || type == 29 || type == 30 || type == 31;
}

constexpr int64_t kMaxCount = 2'000'000'000;  // more than any mesh a haptic loop can step

struct GmshMesh {
  std::vector<double> positions;
  std::unordered_map<int64_t, uint32_t> node_index;  // file tag -> position index
  std::vector<int64_t> tet_tags;                     // 4 per tet, node tags as in the file
  std::vector<int> tet_lines;                        // file line of each tet, for messages
  std::vector<int64_t> tet_ids;                      // element tag of each tet
  std::unordered_map<int64_t, int>
      element_lines;  // element tag -> its line, to refuse a tag given twice
  size_t skipped = 0;
  bool has_nodes = false, has_elements = false;
};

void add_node(TextReader& in, GmshMesh& mesh, int64_t tag, const double xyz[3]) {
  if (!mesh.node_index.emplace(tag, static_cast<uint32_t>(mesh.positions.size() / 3)).second) {
    in.fail("node " + std::to_string(tag) + " is defined twice");
  }
  mesh.positions.insert(mesh.positions.end(), xyz, xyz + 3);
}

void read_node_line(TextReader& in, GmshMesh& mesh) {
  int64_t tag = in.next_int("a node number");
  double xyz[3];
  for (double& c : xyz) c = in.next_double("a node coordinate");
  add_node(in, mesh, tag, xyz);
}

// Reads the node tags of one element, all on the element's own line.
void read_element_nodes(TextReader& in, GmshMesh& mesh, int64_t element, int64_t type, int count,
                        int line) {
  auto [first, inserted] = mesh.element_lines.emplace(element, line);
  if (!inserted) {
    in.fail_at(line, "element " + std::to_string(element) + " is defined twice (first on line " +
                         std::to_string(first->second) + ")");
  }
  int64_t tags[4] = {0, 0, 0, 0};
  for (int i = 0; i < count; ++i) {
    int64_t tag = in.next_int("an element node number");
    if (in.line() != line) {
      in.fail_at(line, "element " + std::to_string(element) +
                           " has fewer node numbers on its line than its type " +
                           std::to_string(type) + " needs (" + std::to_string(count) + ")");
    }
    if (i < 4) tags[i] = tag;
  }
  if (!in.next_on_new_line()) {
    in.fail_at(line, "element " + std::to_string(element) +
                         " has more numbers on its line than its type " + std::to_string(type) +
                         " takes (" + std::to_string(count) + " nodes)");
  }
  if (!gmsh_is_tet(type)) {
    ++mesh.skipped;
    return;
  }
  mesh.tet_tags.insert(mesh.tet_tags.end(), tags, tags + 4);
  mesh.tet_lines.push_back(line);
  mesh.tet_ids.push_back(element);
}

void read_v1_v2_nodes(TextReader& in, GmshMesh& mesh, const char* end_keyword) {
  int64_t count = in.next_int_in("the node count", 0, kMaxCount);
  for (int64_t i = 0; i < count; ++i) {
    if (in.peek() == end_keyword) {
      in.next("");
      in.fail("the node count says " + std::to_string(count) + " but only " + std::to_string(i) +
              " nodes are given");
    }
    read_node_line(in, mesh);
  }
  in.expect(end_keyword);
  mesh.has_nodes = true;
}

void read_v1_v2_elements(TextReader& in, GmshMesh& mesh, bool version1, const char* end_keyword) {
  int64_t count = in.next_int_in("the element count", 0, kMaxCount);
  for (int64_t i = 0; i < count; ++i) {
    if (in.peek() == end_keyword) {
      in.next("");
      in.fail("the element count says " + std::to_string(count) + " but only " + std::to_string(i) +
              " elements are given");
    }
    int64_t element = in.next_int("an element number");
    int line = in.line();
    int64_t type = in.next_int("an element type");
    int expected = gmsh_nodes_per_element(type);
    if (expected == 0)
      in.fail("element " + std::to_string(element) + " has unknown type " + std::to_string(type));
    int count_nodes = expected;
    if (version1) {
      in.next_int("the physical region");
      in.next_int("the elementary region");
      int64_t given = in.next_int_in("the element's node count", 1, 64);
      if (given != expected) {
        in.fail("element " + std::to_string(element) + " of type " + std::to_string(type) +
                " must have " + std::to_string(expected) + " nodes, the file says " +
                std::to_string(given));
      }
    } else {
      int64_t tags = in.next_int_in("the element's tag count", 0, 64);
      for (int64_t t = 0; t < tags; ++t) in.next_int("an element tag");
    }
    if (in.line() != line)
      in.fail_at(line, "element " + std::to_string(element) + " is cut across lines");
    read_element_nodes(in, mesh, element, type, count_nodes, line);
  }
  in.expect(end_keyword);
  mesh.has_elements = true;
}

void read_v4_nodes(TextReader& in, GmshMesh& mesh) {
  int64_t blocks = in.next_int_in("the node block count", 0, kMaxCount);
  int64_t total = in.next_int_in("the node count", 0, kMaxCount);
  in.next_int("the smallest node tag");
  in.next_int("the largest node tag");
  int64_t seen = 0;
  std::vector<int64_t> tags;
  for (int64_t b = 0; b < blocks; ++b) {
    int64_t dim = in.next_int_in("the block's entity dimension", 0, 3);
    in.next_int("the block's entity tag");
    int64_t parametric = in.next_int_in("the block's parametric flag", 0, 1);
    int64_t count = in.next_int_in("the block's node count", 0, kMaxCount);
    if (seen + count > total)
      in.fail("the node blocks hold more nodes than the $Nodes header's " + std::to_string(total));
    tags.clear();
    for (int64_t i = 0; i < count; ++i) tags.push_back(in.next_int("a node tag"));
    for (int64_t i = 0; i < count; ++i) {
      double xyz[3];
      for (double& c : xyz) c = in.next_double("a node coordinate");
      for (int64_t p = 0; p < parametric * dim; ++p) in.next_double("a parametric coordinate");
      add_node(in, mesh, tags[static_cast<size_t>(i)], xyz);
    }
    seen += count;
  }
  if (seen != total)
    in.fail("the $Nodes header says " + std::to_string(total) + " nodes, the blocks hold " +
            std::to_string(seen));
  in.expect("$EndNodes");
  mesh.has_nodes = true;
}

void read_v4_elements(TextReader& in, GmshMesh& mesh) {
  int64_t blocks = in.next_int_in("the element block count", 0, kMaxCount);
  int64_t total = in.next_int_in("the element count", 0, kMaxCount);
  in.next_int("the smallest element tag");
  in.next_int("the largest element tag");
  int64_t seen = 0;
  for (int64_t b = 0; b < blocks; ++b) {
    in.next_int_in("the block's entity dimension", 0, 3);
    in.next_int("the block's entity tag");
    int64_t type = in.next_int("the block's element type");
    int nodes = gmsh_nodes_per_element(type);
    if (nodes == 0) in.fail("unknown element type " + std::to_string(type));
    int64_t count = in.next_int_in("the block's element count", 0, kMaxCount);
    if (seen + count > total)
      in.fail("the element blocks hold more elements than the header's " + std::to_string(total));
    for (int64_t i = 0; i < count; ++i) {
      int64_t element = in.next_int("an element tag");
      read_element_nodes(in, mesh, element, type, nodes, in.line());
    }
    seen += count;
  }
  if (seen != total)
    in.fail("the $Elements header says " + std::to_string(total) + " elements, the blocks hold " +
            std::to_string(seen));
  in.expect("$EndElements");
  mesh.has_elements = true;
}

// Skips a section we do not use ($PhysicalNames, $Entities, $NodeData...) up to its end marker.
void skip_section(TextReader& in, std::string_view name) {
  std::string end = "$End" + std::string(name.substr(1));
  std::string end_v1 = end;
  std::transform(end_v1.begin(), end_v1.end(), end_v1.begin(),
                 [](unsigned char c) { return std::toupper(c); });
  for (;;) {
    std::string_view token = in.next(("'" + end + "'").c_str());
    std::string upper(token);
    std::transform(upper.begin(), upper.end(), upper.begin(),
                   [](unsigned char c) { return std::toupper(c); });
    if (upper == end_v1) return;
  }
}

}  // namespace

VolumeMesh read_gmsh(const std::string& path, std::string_view text, LoadReport& report) {
  TextReader in(path, text);
  GmshMesh mesh;
  int version = 1;
  report.format = "gmsh-1";
  while (!in.at_end()) {
    std::string_view section = in.next("a section such as $Nodes");
    if (section == "$MeshFormat") {
      std::string_view v = in.next("the format version");
      if (v == "2" || v == "2.0" || v == "2.1" || v == "2.2") {
        version = 2;
        report.format = "gmsh-2.2";
      } else if (v == "4.1") {
        version = 4;
        report.format = "gmsh-4.1";
      } else {
        in.fail("Gmsh format version " + std::string(v) + " is not supported (1, 2.2 and 4.1 are)");
      }
      if (in.next_int("the file type (0 ASCII, 1 binary)") != 0)
        in.fail("binary .msh files are not supported; save as ASCII");
      in.next_int("the data size");
      in.expect("$EndMeshFormat");
    } else if (section == "$NOD" && version == 1) {
      read_v1_v2_nodes(in, mesh, "$ENDNOD");
    } else if (section == "$ELM" && version == 1) {
      read_v1_v2_elements(in, mesh, true, "$ENDELM");
    } else if (section == "$Nodes" && version == 2) {
      read_v1_v2_nodes(in, mesh, "$EndNodes");
    } else if (section == "$Elements" && version == 2) {
      read_v1_v2_elements(in, mesh, false, "$EndElements");
    } else if (section == "$Nodes" && version == 4) {
      read_v4_nodes(in, mesh);
    } else if (section == "$Elements" && version == 4) {
      read_v4_elements(in, mesh);
    } else if (section.size() > 1 && section[0] == '$') {
      skip_section(in, section);
    } else {
      in.fail("expected a section such as $Nodes, found '" + std::string(section.substr(0, 40)) +
              "'");
    }
  }
  if (!mesh.has_nodes) in.fail("the file has no node section");
  if (!mesh.has_elements) in.fail("the file has no element section");

  VolumeMesh out;
  out.source = path;
  out.positions = std::move(mesh.positions);
  out.tets.reserve(mesh.tet_tags.size());
  for (size_t i = 0; i < mesh.tet_tags.size(); ++i) {
    auto it = mesh.node_index.find(mesh.tet_tags[i]);
    if (it == mesh.node_index.end()) {
      in.fail_at(mesh.tet_lines[i / 4], "element " + std::to_string(mesh.tet_ids[i / 4]) +
                                            " refers to node " + std::to_string(mesh.tet_tags[i]) +
                                            ", which the file does not define");
    }
    out.tets.push_back(it->second);
  }
  report.skipped_elements += mesh.skipped;
  return out;
}

}  // namespace tacta::mesh_detail
