#include "mesh/text_reader.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <fstream>
#include <sstream>

namespace tacta::mesh_detail {

namespace {
bool is_space(char c) {
  return c == ' ' || c == '\t' || c == '\n' || c == '\r' || c == '\f' || c == '\v';
}

std::string quoted(std::string_view token) {
  constexpr size_t kShown = 40;  // long garbage is cut so that a message stays one line
  std::string s(token.substr(0, kShown));
  if (token.size() > kShown) s += "...";
  return "'" + s + "'";
}
}  // namespace

std::string read_file_bytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError({path, 0, 0, ""}, "cannot open the file");
  std::ostringstream buffer;
  buffer << in.rdbuf();
  if (in.bad()) throw InputError({path, 0, 0, ""}, "cannot read the file");
  return std::move(buffer).str();
}

bool parse_int(std::string_view token, int64_t& out) {
  if (!token.empty() && token.front() == '+') token.remove_prefix(1);
  const char* end = token.data() + token.size();
  auto [ptr, ec] = std::from_chars(token.data(), end, out);
  return ec == std::errc() && ptr == end && !token.empty();
}

bool parse_double(std::string_view token, double& out) {
  if (!token.empty() && token.front() == '+') token.remove_prefix(1);
  const char* end = token.data() + token.size();
  auto [ptr, ec] = std::from_chars(token.data(), end, out, std::chars_format::general);
  return ec == std::errc() && ptr == end && !token.empty();
}

void TextReader::skip_space() {
  while (pos_ < text_.size() && is_space(text_[pos_])) {
    if (text_[pos_] == '\n') ++line_;
    ++pos_;
  }
}

bool TextReader::at_end() {
  skip_space();
  return pos_ >= text_.size();
}

std::string_view TextReader::peek() {
  skip_space();
  size_t end = pos_;
  while (end < text_.size() && !is_space(text_[end])) ++end;
  return text_.substr(pos_, end - pos_);
}

bool TextReader::next_on_new_line() {
  size_t p = pos_;
  while (p < text_.size() && is_space(text_[p])) {
    if (text_[p] == '\n') return true;
    ++p;
  }
  return p >= text_.size() || pos_ == 0;
}

void TextReader::skip_line() {
  while (pos_ < text_.size() && text_[pos_] != '\n') ++pos_;
  if (pos_ < text_.size()) {
    ++pos_;
    ++line_;
  }
}

void TextReader::skip_bytes(size_t n) {
  const size_t end = std::min(text_.size(), pos_ + std::min(n, text_.size()));
  line_ += static_cast<int>(std::count(text_.begin() + static_cast<std::ptrdiff_t>(pos_),
                                       text_.begin() + static_cast<std::ptrdiff_t>(end), '\n'));
  pos_ = end;
}

std::string_view TextReader::next(const char* what) {
  skip_space();
  if (pos_ >= text_.size())
    fail_at(line_, std::string("unexpected end of file (truncated?), expected ") + what);
  size_t start = pos_;
  while (pos_ < text_.size() && !is_space(text_[pos_])) ++pos_;
  token_line_ = line_;
  return text_.substr(start, pos_ - start);
}

int64_t TextReader::next_int(const char* what) {
  std::string_view token = next(what);
  int64_t value = 0;
  if (!parse_int(token, value))
    fail(std::string("expected ") + what + " (an integer), found " + quoted(token));
  return value;
}

int64_t TextReader::next_int_in(const char* what, int64_t min, int64_t max) {
  int64_t value = next_int(what);
  if (value < min || value > max) {
    fail(std::string("expected ") + what + " in [" + std::to_string(min) + ", " +
         std::to_string(max) + "], found " + std::to_string(value));
  }
  return value;
}

double TextReader::next_double(const char* what) {
  std::string_view token = next(what);
  double value = 0;
  if (!parse_double(token, value))
    fail(std::string("expected ") + what + " (a number), found " + quoted(token));
  if (!std::isfinite(value))
    fail(std::string("expected ") + what + " to be finite, found " + quoted(token));
  return value;
}

void TextReader::expect(std::string_view keyword) {
  std::string what = "'" + std::string(keyword) + "'";
  std::string_view token = next(what.c_str());
  if (token != keyword) fail("expected " + what + ", found " + quoted(token));
}

void TextReader::fail(const std::string& message) const { fail_at(token_line_, message); }

void TextReader::fail_at(int line, const std::string& message) const {
  throw InputError({path_, line, 0, ""}, message);
}

bool LineWords::next() {
  if (pos_ >= bytes_.size()) return false;
  size_t end = bytes_.find('\n', pos_);
  if (end == std::string::npos) end = bytes_.size();
  std::string_view line(bytes_.data() + pos_, end - pos_);
  pos_ = end + 1;
  ++number_;
  words_.clear();
  size_t p = 0;
  while ((p = line.find_first_not_of(" \t\r\f\v", p)) != std::string_view::npos) {
    const size_t stop = std::min(line.find_first_of(" \t\r\f\v", p), line.size());
    words_.push_back(line.substr(p, stop - p));
    p = stop;
  }
  return true;
}

void LineWords::fail(const std::string& message) const {
  throw InputError({path_, number_, 0, ""}, message);
}

void LineWords::expect_numbers(size_t first, size_t last, const char* what, double* out) const {
  for (size_t i = first; i < last; ++i) {
    double value = 0;
    if (!parse_double(words_[i], value) || !std::isfinite(value)) {
      fail(std::string("expected ") + what + " (a finite number), found " + quoted(words_[i]));
    }
    if (out != nullptr) out[i - first] = value;
  }
}

}  // namespace tacta::mesh_detail
