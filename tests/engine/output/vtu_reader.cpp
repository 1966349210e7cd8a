#include "vtu_reader.hpp"

#include <cstring>
#include <fstream>
#include <sstream>
#include <stdexcept>

namespace tacta::output::testing {

namespace {

std::string attribute(const std::string& tag, const std::string& name) {
  const std::string key = " " + name + "=\"";
  const size_t at = tag.find(key);
  if (at == std::string::npos) return "";
  const size_t start = at + key.size();
  return tag.substr(start, tag.find('"', start) - start);
}

template <typename T>
void append_raw(const std::vector<uint8_t>& bytes, std::vector<double>& out) {
  uint64_t byte_count = 0;
  std::memcpy(&byte_count, bytes.data(), sizeof byte_count);
  if (bytes.size() < sizeof byte_count + byte_count) throw std::runtime_error("short binary block");
  for (size_t i = 0; i < byte_count / sizeof(T); ++i) {
    T v;
    std::memcpy(&v, bytes.data() + sizeof byte_count + i * sizeof(T), sizeof(T));
    out.push_back(static_cast<double>(v));
  }
}

}  // namespace

std::vector<uint8_t> decode_base64(const std::string& text) {
  std::vector<uint8_t> out;
  uint32_t buffer = 0;
  int bits = 0;
  for (char c : text) {
    int v;
    if (c >= 'A' && c <= 'Z')
      v = c - 'A';
    else if (c >= 'a' && c <= 'z')
      v = c - 'a' + 26;
    else if (c >= '0' && c <= '9')
      v = c - '0' + 52;
    else if (c == '+')
      v = 62;
    else if (c == '/')
      v = 63;
    else
      continue;  // padding and white space
    buffer = (buffer << 6) | static_cast<uint32_t>(v);
    bits += 6;
    if (bits >= 8) {
      bits -= 8;
      out.push_back(static_cast<uint8_t>((buffer >> bits) & 0xFF));
    }
  }
  return out;
}

VtuFile read_vtu(const std::filesystem::path& file) {
  std::ifstream in(file, std::ios::binary);
  if (!in) throw std::runtime_error("cannot open " + file.string());
  VtuFile vtu;
  vtu.text.assign(std::istreambuf_iterator<char>(in), {});
  const size_t piece = vtu.text.find("<Piece ");
  if (piece == std::string::npos) throw std::runtime_error("no Piece in " + file.string());
  const std::string piece_tag = vtu.text.substr(piece, vtu.text.find('>', piece) - piece);
  vtu.point_count = std::stoul(attribute(piece_tag, "NumberOfPoints"));
  vtu.cell_count = std::stoul(attribute(piece_tag, "NumberOfCells"));
  for (size_t at = vtu.text.find("<DataArray"); at != std::string::npos;
       at = vtu.text.find("<DataArray", at + 1)) {
    const size_t tag_end = vtu.text.find('>', at);
    const std::string tag = vtu.text.substr(at, tag_end - at);
    const size_t body_end = vtu.text.find("</DataArray>", tag_end);
    const std::string body = vtu.text.substr(tag_end + 1, body_end - tag_end - 1);
    VtuArray array;
    array.type = attribute(tag, "type");
    const std::string components = attribute(tag, "NumberOfComponents");
    array.components = components.empty() ? 1 : std::stoi(components);
    if (attribute(tag, "format") == "ascii") {
      std::istringstream values(body);
      for (double v; values >> v;) array.values.push_back(v);
    } else {
      const std::vector<uint8_t> bytes = decode_base64(body);
      if (array.type == "Float64")
        append_raw<double>(bytes, array.values);
      else if (array.type == "Int64")
        append_raw<int64_t>(bytes, array.values);
      else if (array.type == "UInt8")
        append_raw<uint8_t>(bytes, array.values);
      else
        throw std::runtime_error("unexpected type " + array.type);
    }
    vtu.arrays[attribute(tag, "Name")] = std::move(array);
  }
  return vtu;
}

}  // namespace tacta::output::testing
