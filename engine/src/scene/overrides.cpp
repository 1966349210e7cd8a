// Applying --set key.path=value overrides to a YAML tree.
#include "scene/overrides.hpp"

#include <charconv>

#include "scene/did_you_mean.hpp"
#include "tacta/error.hpp"

namespace tacta::scene_detail {

namespace {

struct Override {
  std::string text;                   // the whole "key.path=value", for messages
  std::vector<std::string> segments;  // "bodies", "*", "model"
  YAML::Node value;
  std::vector<OverrideOrigin>* origins;

  [[noreturn]] void fail(const std::string& key_path, const std::string& message) const {
    throw InputError(SourceLocation{"--set " + text, 0, 0, key_path}, message);
  }
};

std::optional<size_t> parse_index(const std::string& segment) {
  size_t value = 0;
  auto [end, error] = std::from_chars(segment.data(), segment.data() + segment.size(), value);
  if (error != std::errc() || end != segment.data() + segment.size()) return std::nullopt;
  return value;
}

// Writes the override into `node` from segment `depth` on. `node` is a handle into the tree:
// assigning through it (node[key] = ...) edits the tree; it is never rebound.
void apply_at(YAML::Node node, const Override& o, size_t depth, const std::string& path) {
  const std::string& segment = o.segments[depth];
  const bool last = depth + 1 == o.segments.size();
  auto descend = [&](YAML::Node child, const std::string& child_key_path) {
    if (last) {
      child = o.value;  // child is a handle into the tree: this writes the tree
      o.origins->push_back(OverrideOrigin{child_key_path, o.text});
    } else {
      apply_at(child, o, depth + 1, child_key_path);
    }
  };

  if (node.IsSequence()) {
    if (segment == "*") {
      if (node.size() == 0) o.fail(path, "'*' selects nothing: the list is empty");
      for (size_t i = 0; i < node.size(); ++i) descend(node[i], item_path(path, i));
      return;
    }
    if (auto index = parse_index(segment)) {
      if (*index >= node.size())
        o.fail(item_path(path, *index), "index " + segment + " is out of range: the list has " +
                                            std::to_string(node.size()) + " items");
      descend(node[*index], item_path(path, *index));
      return;
    }
    std::vector<std::string> names;
    for (size_t i = 0; i < node.size(); ++i) {
      const YAML::Node element = node[i];
      if (!element.IsMap()) continue;
      const YAML::Node name = element["name"];
      if (!name.IsDefined() || !name.IsScalar()) continue;
      if (name.Scalar() == segment) {
        descend(node[i], item_path(path, i));
        return;
      }
      names.push_back(name.Scalar());
    }
    o.fail(path, "no element named '" + segment + "' (use an index, '*' or a name); " +
                     unknown_name_message("name", segment, names));
  }

  if (node.IsScalar())
    o.fail(path, "'" + path + "' holds a value, not a map or list, so '" + segment +
                     "' cannot select inside it");
  if (!node.IsMap() && parse_index(segment))
    o.fail(child_path(path, segment), "'" + (path.empty() ? std::string("<scene>") : path) +
                                          "' is not a list, so index " + segment +
                                          " selects nothing");
  if (segment == "*") {
    if (!node.IsMap() || node.size() == 0) o.fail(path, "'*' selects nothing here");
    for (auto entry : node) descend(entry.second, child_path(path, entry.first.Scalar()));
    return;
  }
  const bool existed = node.IsMap() && static_cast<const YAML::Node&>(node)[segment].IsDefined();
  if (!existed)  // a key the override creates: errors about it belong to the override
    o.origins->push_back(OverrideOrigin{child_path(path, segment), o.text});
  descend(node[segment], child_path(path, segment));  // creates a missing key
}

Override parse(const std::string& text, std::vector<OverrideOrigin>& origins) {
  Override o{text, {}, {}, &origins};
  const size_t equals = text.find('=');
  if (equals == std::string::npos || equals == 0 || equals + 1 == text.size())
    o.fail("", "expected key.path=value, found '" + text + "'");
  const std::string key = text.substr(0, equals);
  for (size_t start = 0;;) {
    const size_t dot = key.find('.', start);
    const std::string segment = key.substr(start, dot == std::string::npos ? dot : dot - start);
    if (segment.empty()) o.fail("", "empty segment in key path '" + key + "'");
    o.segments.push_back(segment);
    if (dot == std::string::npos) break;
    start = dot + 1;
  }
  try {
    o.value = YAML::Load(text.substr(equals + 1));
  } catch (const YAML::Exception& e) {
    o.fail("", "the value is not valid YAML: " + e.msg);
  }
  return o;
}

}  // namespace

void apply_overrides(YAML::Node& root, const std::vector<std::string>& overrides,
                     std::vector<OverrideOrigin>& origins) {
  for (const std::string& text : overrides) {
    const Override o = parse(text, origins);
    if (!root.IsMap() && !root.IsNull()) o.fail("", "the scene is not a map of keys");
    apply_at(root, o, 0, "");
  }
}

}  // namespace tacta::scene_detail
