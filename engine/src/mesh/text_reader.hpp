// Whitespace-separated tokens of a text mesh file with their line numbers, and number parsing that
// rejects what a mesh cannot hold (NaN, infinities, trailing garbage, out-of-range integers).
// Every failure is an InputError naming the file and line.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "tacta/error.hpp"

namespace tacta::mesh_detail {

// Whole file as bytes; throws InputError when it cannot be read.
std::string read_file_bytes(const std::string& path);

class TextReader {
 public:
  TextReader(std::string path, std::string_view text) : path_(std::move(path)), text_(text) {}

  // Next token; throws "unexpected end of file, expected <what>" at the end.
  std::string_view next(const char* what);
  // Next token without consuming it; empty at the end of the file.
  std::string_view peek();
  bool at_end();
  // Line of the token returned last (1-based).
  int line() const { return token_line_; }
  // True when the next token starts a new line (or the file ends).
  bool next_on_new_line();
  // Skips what is left of the current line, its line break included.
  void skip_line();
  // Byte offset of the next unread character, and the whole text (binary data inside a text
  // file, as in BINARY legacy VTK, is read from there).
  size_t position() const { return pos_; }
  std::string_view text() const { return text_; }
  // Moves n bytes on (at most to the end), counting the line breaks passed so that later lines
  // keep the numbers an editor shows.
  void skip_bytes(size_t n);

  int64_t next_int(const char* what);
  // An integer in [min, max], else an error naming what and the range.
  int64_t next_int_in(const char* what, int64_t min, int64_t max);
  double next_double(const char* what);
  void expect(std::string_view keyword);

  [[noreturn]] void fail(const std::string& message) const;
  [[noreturn]] void fail_at(int line, const std::string& message) const;
  const std::string& path() const { return path_; }

 private:
  void skip_space();
  std::string path_;
  std::string_view text_;
  size_t pos_ = 0;
  int line_ = 1;        // line of pos_
  int token_line_ = 1;  // line of the last token returned
};

// A line-oriented text file (OBJ, ASCII STL): each next() moves to the following line and splits
// it into whitespace-separated words; fail() names the file and that line.
class LineWords {
 public:
  LineWords(const std::string& path, const std::string& bytes) : path_(path), bytes_(bytes) {}
  bool next();
  const std::vector<std::string_view>& words() const { return words_; }
  int line() const { return number_; }
  [[noreturn]] void fail(const std::string& message) const;
  // Words [first, last) must be finite numbers; returns them in out when it is given.
  void expect_numbers(size_t first, size_t last, const char* what, double* out = nullptr) const;

 private:
  const std::string& path_;
  const std::string& bytes_;
  size_t pos_ = 0;
  int number_ = 0;
  std::vector<std::string_view> words_;
};

// Parsing of one token, for callers that hold their own tokens (XML arrays); the error says what.
bool parse_int(std::string_view token, int64_t& out);
bool parse_double(std::string_view token, double& out);

}  // namespace tacta::mesh_detail
