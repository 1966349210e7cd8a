#include "mesh/vtk_xml_data.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <zlib.h>

#include "mesh/text_reader.hpp"

namespace tacta::mesh_detail {

namespace {

using tinyxml2::XMLElement;

constexpr double kMaxIndex = 4e9;  // beyond any uint32 index a mesh can hold
// Deflate's largest ratio: a 258-byte match coded in 2 bits. A header that promises more bytes
// than its compressed blocks can give is refused before anything is allocated for them.
constexpr uint64_t kMaxInflation = 1032;

int base64_value(char c) {
  if (c >= 'A' && c <= 'Z') return c - 'A';
  if (c >= 'a' && c <= 'z') return c - 'a' + 26;
  if (c >= '0' && c <= '9') return c - '0' + 52;
  if (c == '+') return 62;
  if (c == '/') return 63;
  return -1;
}

// The bytes of one array's binary data, read in order: raw bytes, or base64 decoded group by
// group, so that separately padded streams (header, then data, as VTK writes them) read as their
// concatenation.
class ByteStream {
 public:
  ByteStream(const XmlContext& ctx, const XMLElement* where, std::string_view data, bool base64)
      : ctx_(ctx), where_(where), data_(data), base64_(base64) {}

  // The bytes left, at most (base64: what the characters left can decode to).
  uint64_t most_left() const {
    const size_t rest = data_.size() - pos_;
    return base64_ ? (rest / 4 + 1) * 3 + (buffered_ - used_) : rest;
  }

  void read(unsigned char* out, size_t n, const char* what) {
    if (!base64_) {
      if (n > data_.size() - pos_) truncated(what);
      if (n > 0) std::memcpy(out, data_.data() + pos_, n);
      pos_ += n;
      return;
    }
    for (size_t i = 0; i < n; ++i) {
      if (used_ == buffered_ && !next_group()) truncated(what);
      out[i] = buffer_[used_++];
    }
  }

  uint64_t word(const char* what) {
    unsigned char b[8];
    const int size = ctx_.header_bytes;
    read(b, static_cast<size_t>(size), what);
    uint64_t value = 0;
    for (int i = 0; i < size; ++i) value = (value << 8) | b[ctx_.big_endian ? i : size - 1 - i];
    return value;
  }

 private:
  [[noreturn]] void truncated(const char* what) const {
    ctx_.fail(where_, std::string("binary data ends inside ") + what + " (truncated?)");
  }
  bool next_group() {
    int v[4];
    int pad = 0;
    for (int k = 0; k < 4; ++k) {
      while (pos_ < data_.size() && std::isspace(static_cast<unsigned char>(data_[pos_]))) ++pos_;
      if (pos_ == data_.size()) {
        if (k == 0) return false;
        ctx_.fail(where_, "base64 data length is not a multiple of 4 (truncated?)");
      }
      const char c = data_[pos_++];
      if (c == '=' && k >= 2) {
        v[k] = 0;
        ++pad;
      } else {
        v[k] = base64_value(c);
        if (v[k] < 0 || pad > 0) ctx_.fail(where_, "invalid base64 character in binary data");
      }
    }
    const uint32_t triple = (static_cast<uint32_t>(v[0]) << 18) |
                            (static_cast<uint32_t>(v[1]) << 12) |
                            (static_cast<uint32_t>(v[2]) << 6) | static_cast<uint32_t>(v[3]);
    buffer_[0] = static_cast<unsigned char>(triple >> 16);
    buffer_[1] = static_cast<unsigned char>(triple >> 8);
    buffer_[2] = static_cast<unsigned char>(triple);
    buffered_ = 3 - pad;
    used_ = 0;
    return true;
  }

  const XmlContext& ctx_;
  const XMLElement* where_;
  std::string_view data_;
  bool base64_;
  size_t pos_ = 0;
  unsigned char buffer_[3] = {0, 0, 0};
  int buffered_ = 0, used_ = 0;
};

// The data of one array: a byte-count header then the bytes, or (zlib) a header of block count,
// block size, last block size and each block's compressed size, then the blocks.
std::vector<unsigned char> binary_payload(const XmlContext& ctx, const XMLElement* array,
                                          ByteStream& in, size_t expected_bytes) {
  if (!ctx.zlib) {
    const uint64_t size = in.word("its header");
    if (size != expected_bytes) {
      ctx.fail(array, "binary header says " + std::to_string(size) + " bytes, the array needs " +
                          std::to_string(expected_bytes));
    }
    if (size > in.most_left())
      ctx.fail(array, "binary data is shorter than its header says (truncated?)");
    std::vector<unsigned char> out(expected_bytes);
    in.read(out.data(), expected_bytes, "the array");
    return out;
  }
  const uint64_t blocks = in.word("its header"), block_size = in.word("its header"),
                 last_size = in.word("its header");
  const uint64_t h = static_cast<uint64_t>(ctx.header_bytes);
  if (blocks > in.most_left() / h)
    ctx.fail(array, "compressed header gives an impossible block count");
  std::vector<uint64_t> compressed(blocks);
  uint64_t compressed_total = 0;
  for (uint64_t& c : compressed) {
    c = in.word("its header");
    if (c > in.most_left()) ctx.fail(array, "a compressed block is cut short (truncated?)");
    compressed_total += c;
  }
  if (compressed_total > in.most_left())
    ctx.fail(array, "the compressed blocks are cut short (truncated?)");
  const bool sizes_fit =
      blocks == 0 ||
      (last_size <= block_size && (blocks == 1 || block_size <= expected_bytes / (blocks - 1)));
  const uint64_t total = !sizes_fit || blocks == 0 ? 0
                                                   : (blocks - 1) * block_size +
                                                         (last_size == 0 ? block_size : last_size);
  if (!sizes_fit || total != expected_bytes) {
    ctx.fail(array, "compressed header says " +
                        (sizes_fit ? std::to_string(total) : std::string("other")) +
                        " bytes, the array needs " + std::to_string(expected_bytes));
  }
  if (expected_bytes / kMaxInflation > compressed_total) {
    ctx.fail(array, "compressed blocks of " + std::to_string(compressed_total) +
                        " bytes cannot inflate to the " + std::to_string(expected_bytes) +
                        " bytes the header says (corrupt header)");
  }
  std::vector<unsigned char> out(expected_bytes), block;
  size_t dst = 0;
  for (uint64_t b = 0; b < blocks; ++b) {
    block.resize(compressed[b]);
    in.read(block.data(), block.size(), "a compressed block");
    const uint64_t want = b + 1 == blocks && last_size != 0 ? last_size : block_size;
    uLongf produced = static_cast<uLongf>(want);
    if (uncompress(out.data() + dst, &produced, block.data(), static_cast<uLong>(block.size())) !=
            Z_OK ||
        produced != want) {
      ctx.fail(array,
               "compressed block " + std::to_string(b) + " does not inflate (corrupt zlib data)");
    }
    dst += produced;
  }
  return out;
}

struct ScalarType {
  int size = 0;
  bool is_float = false, is_signed = false;
};

ScalarType scalar_type(const XmlContext& ctx, const XMLElement* array) {
  const char* name = array->Attribute("type");
  std::string t = name ? name : "";
  if (t == "Float32") return {4, true, true};
  if (t == "Float64") return {8, true, true};
  if (t == "Int8" || t == "Char") return {1, false, true};
  if (t == "UInt8") return {1, false, false};
  if (t == "Int16") return {2, false, true};
  if (t == "UInt16") return {2, false, false};
  if (t == "Int32") return {4, false, true};
  if (t == "UInt32") return {4, false, false};
  if (t == "Int64") return {8, false, true};
  if (t == "UInt64") return {8, false, false};
  ctx.fail(array, "DataArray type '" + t + "' is not a VTK scalar type");
}

double to_double(const unsigned char* p, ScalarType type, bool big_endian) {
  uint64_t raw = 0;
  for (int i = 0; i < type.size; ++i) raw = (raw << 8) | p[big_endian ? i : type.size - 1 - i];
  if (type.is_float) {
    if (type.size == 4) {
      uint32_t bits = static_cast<uint32_t>(raw);
      float f;
      std::memcpy(&f, &bits, 4);
      return static_cast<double>(f);
    }
    double d;
    std::memcpy(&d, &raw, 8);
    return d;
  }
  if (type.is_signed && type.size < 8 && (raw >> (8 * type.size - 1)) != 0) {
    raw |= ~uint64_t{0} << (8 * type.size);  // sign-extend
  }
  return type.is_signed ? static_cast<double>(static_cast<int64_t>(raw)) : static_cast<double>(raw);
}

// Where an array's binary data starts: its text (inline), or its offset into the appended data.
ByteStream binary_source(const XmlContext& ctx, const XMLElement* array, bool appended) {
  if (!appended) {
    const char* text = array->GetText();
    return ByteStream(ctx, array, text ? text : "", true);
  }
  if (ctx.appended.data() == nullptr)
    ctx.fail(array, "DataArray format=\"appended\" but the file has no <AppendedData>");
  uint64_t offset = 0;
  if (array->QueryUnsigned64Attribute("offset", &offset) != tinyxml2::XML_SUCCESS ||
      offset > ctx.appended.size()) {
    ctx.fail(array, "an appended DataArray needs an offset inside the appended data (0 to " +
                        std::to_string(ctx.appended.size()) + ")");
  }
  return ByteStream(ctx, array, ctx.appended.substr(offset), ctx.appended_base64);
}

}  // namespace

std::vector<double> read_array(const XmlContext& ctx, const XMLElement* array, size_t count) {
  ScalarType type = scalar_type(ctx, array);
  const char* format_attr = array->Attribute("format");
  std::string format = format_attr ? format_attr : "ascii";
  std::vector<double> values;
  if (format == "ascii") {
    const char* text = array->GetText();
    TextReader in(ctx.path, text ? text : "");
    while (!in.at_end()) {
      values.push_back(in.next_double("a DataArray value"));
      if (values.size() > count) break;
    }
  } else if (format == "binary" || format == "appended") {
    ByteStream in = binary_source(ctx, array, format == "appended");
    std::vector<unsigned char> bytes =
        binary_payload(ctx, array, in, count * static_cast<size_t>(type.size));
    values.resize(count);
    for (size_t i = 0; i < count; ++i)
      values[i] =
          to_double(bytes.data() + i * static_cast<size_t>(type.size), type, ctx.big_endian);
  } else {
    ctx.fail(array, "DataArray format '" + format + "' is not ascii, binary or appended");
  }
  if (values.size() != count) {
    const char* name = array->Attribute("Name");
    ctx.fail(array, std::string("DataArray ") + (name ? name : "") + " must hold " +
                        std::to_string(count) + " values, it holds " +
                        (values.size() > count ? "more" : std::to_string(values.size())));
  }
  for (double v : values) {
    if (!std::isfinite(v)) ctx.fail(array, "DataArray holds a NaN or infinite value");
    if (!type.is_float && v != std::floor(v)) ctx.fail(array, "integer DataArray holds a fraction");
  }
  return values;
}

const XMLElement* child(const XmlContext& ctx, const XMLElement* parent, const char* name) {
  const XMLElement* c = parent->FirstChildElement(name);
  if (!c) ctx.fail(parent, std::string("<") + parent->Name() + "> has no <" + name + "> element");
  return c;
}

int64_t count_attribute(const XmlContext& ctx, const XMLElement* e, const char* name,
                        bool optional) {
  if (optional && e->Attribute(name) == nullptr) return 0;
  int64_t value = -1;
  if (e->QueryInt64Attribute(name, &value) != tinyxml2::XML_SUCCESS || value < 0 ||
      value > 2'000'000'000) {
    ctx.fail(e, std::string("<") + e->Name() + "> needs a non-negative integer attribute " + name);
  }
  return value;
}

XmlCells read_cells(const XmlContext& ctx, const XMLElement* parent, size_t count) {
  auto named = [&](const char* name) {
    for (const XMLElement* a = parent->FirstChildElement("DataArray"); a;
         a = a->NextSiblingElement("DataArray")) {
      const char* n = a->Attribute("Name");
      if (n && std::strcmp(n, name) == 0) return a;
    }
    ctx.fail(parent, std::string("<") + parent->Name() + "> has no DataArray named '" + name + "'");
  };
  const XMLElement* offsets_array = named("offsets");
  std::vector<double> offsets = read_array(ctx, offsets_array, count);
  XmlCells cells;
  cells.offsets.reserve(count + 1);
  cells.offsets.push_back(0);
  for (double o : offsets) {
    if (o < static_cast<double>(cells.offsets.back()))
      ctx.fail(offsets_array, "cell offsets must not decrease");
    if (o > kMaxIndex)
      ctx.fail(offsets_array, "cell offset " + std::to_string(o) + " is too large");
    cells.offsets.push_back(static_cast<int64_t>(o));
  }
  const XMLElement* connectivity_array = named("connectivity");
  cells.line = connectivity_array->GetLineNum();
  const std::vector<double> connectivity =
      read_array(ctx, connectivity_array, static_cast<size_t>(cells.offsets.back()));
  cells.connectivity.reserve(connectivity.size());
  for (double v : connectivity)
    cells.connectivity.push_back(v >= 0 && v <= kMaxIndex ? static_cast<int64_t>(v) : -1);
  return cells;
}

const XMLElement* parse_vtk_xml(const std::string& path, const std::string& text, const char* type,
                                const char* what_type_holds, tinyxml2::XMLDocument& doc,
                                XmlContext& ctx) {
  ctx.path = path;
  // Raw appended data is not XML: the parser sees the file up to its '_' marker and from
  // </AppendedData> on, so that every line number stays the file's.
  std::string xml;
  const std::string* parsed = &text;
  const size_t tag = text.find("<AppendedData");
  if (tag != std::string::npos) {
    const int tag_line =
        1 + static_cast<int>(
                std::count(text.begin(), text.begin() + static_cast<std::ptrdiff_t>(tag), '\n'));
    const size_t close = text.find('>', tag);
    const size_t marker =
        close == std::string::npos ? close : text.find_first_not_of(" \t\r\n", close + 1);
    if (marker == std::string::npos || text[marker] != '_')
      throw InputError({path, tag_line, 0, ""}, "<AppendedData> must start with '_'");
    const size_t end = text.rfind("</AppendedData>");
    if (end == std::string::npos || end < marker)
      throw InputError({path, tag_line, 0, ""}, "<AppendedData> has no end (truncated?)");
    ctx.appended = std::string_view(text).substr(marker + 1, end - marker - 1);
    xml = text.substr(0, marker + 1) + text.substr(end);
    parsed = &xml;
  }
  if (doc.Parse(parsed->data(), parsed->size()) != tinyxml2::XML_SUCCESS) {
    const char* message = doc.ErrorStr();
    throw InputError({path, doc.ErrorLineNum(), 0, ""},
                     std::string("malformed XML (truncated?): ") + (message ? message : ""));
  }
  const XMLElement* root = doc.FirstChildElement("VTKFile");
  if (!root) ctx.fail(nullptr, "no <VTKFile> element");
  const char* file_type = root->Attribute("type");
  if (!file_type || std::strcmp(file_type, type) != 0) {
    ctx.fail(root, std::string("VTKFile type '") + (file_type ? file_type : "") + "' is not " +
                       type + ", which holds " + what_type_holds);
  }
  const char* order = root->Attribute("byte_order");
  ctx.big_endian = order && std::strcmp(order, "BigEndian") == 0;
  const char* header = root->Attribute("header_type");
  if (header && std::strcmp(header, "UInt64") == 0) {
    ctx.header_bytes = 8;
  } else if (header && std::strcmp(header, "UInt32") != 0) {
    ctx.fail(root, std::string("header_type '") + header + "' is not UInt32 or UInt64");
  }
  const char* compressor = root->Attribute("compressor");
  if (compressor && std::strcmp(compressor, "vtkZLibDataCompressor") == 0) {
    ctx.zlib = true;
  } else if (compressor && *compressor) {
    ctx.fail(root, std::string("compressor '") + compressor +
                       "' is not supported (vtkZLibDataCompressor is)");
  }
  if (const XMLElement* appended = root->FirstChildElement("AppendedData")) {
    const char* encoding = appended->Attribute("encoding");
    if (ctx.appended.data() == nullptr) ctx.fail(appended, "<AppendedData> must start with '_'");
    if (encoding && std::strcmp(encoding, "base64") == 0) {
      ctx.appended_base64 = true;
    } else if (!encoding || std::strcmp(encoding, "raw") != 0) {
      ctx.fail(appended, "<AppendedData> needs encoding=\"raw\" or \"base64\"");
    }
  }
  return root;
}

}  // namespace tacta::mesh_detail
