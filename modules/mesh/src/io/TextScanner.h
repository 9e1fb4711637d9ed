#pragma once
// Line- and token-oriented scanner over an in-memory text file, tracking 1-based line numbers.
// Every number is parsed with std::from_chars over the whole token, so "1.5abc" or "0x10" is an error
// (unlike iostream >>, which stops silently at the first bad character).
#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace reamsim::io {

class TextScanner {
 public:
  // commentChar: everything from this character to the end of the line is ignored ('\0' = no comments).
  TextScanner(std::string_view text, std::string file, char commentChar = '\0');

  // Lines that are only a comment are also appended to `out` (the text after the comment character,
  // trimmed): OBJ and OFF files written by ReamSim keep the bone's patient frame in one.
  void collectCommentLines(std::vector<std::string>* out) { commentLines_ = out; }

  // Advances to the next line (the first call moves to line 1). Returns false at the end of the text.
  bool nextLine();
  // Advances to the next line that has at least one token. Returns false at the end of the text.
  bool nextNonEmptyLine();
  long lineNumber() const { return line_; }
  // The current line without its terminator and comment.
  std::string_view line() const { return lineText_; }
  // Byte offset just past the current line's terminator (where the next line starts).
  std::size_t offsetAfterLine() const { return next_; }

  // Next whitespace-separated token on the current line; false when the line is exhausted.
  bool token(std::string_view& tok);
  // Next token, moving to following lines when needed; false at the end of the text.
  bool tokenAcrossLines(std::string_view& tok);
  // Next token on the current line, or an InputError mentioning `what` if the line ends first.
  std::string_view requireToken(const char* what);
  bool atLineEnd();
  // Throws "unexpected extra token 'X' after <what>" if the current line has anything left.
  void expectLineEnd(const char* what);
  // The rest of the current line (trimmed), consuming it.
  std::string_view restOfLine();

  // Full-token number parsing; errors name `what` and the current line.
  double parseDouble(std::string_view tok, const std::string& what) const;
  std::int64_t parseInt(std::string_view tok, const std::string& what) const;
  double readDouble(const std::string& what) { return parseDouble(requireToken(what.c_str()), what); }
  std::int64_t readInt(const std::string& what) { return parseInt(requireToken(what.c_str()), what); }

  [[noreturn]] void fail(const std::string& problem) const;
  const std::string& file() const { return file_; }

 private:
  std::string_view text_;
  std::string file_;
  char comment_;
  std::vector<std::string>* commentLines_ = nullptr;
  std::size_t next_ = 0;  // start of the next line
  std::string_view lineText_;
  std::size_t pos_ = 0;  // cursor within lineText_
  long line_ = 0;
};

// Shared helpers for callers that parse numbers outside a scanner (e.g. OBJ "v/vt/vn" parts).
bool parseDoubleToken(std::string_view tok, double& out);  // false if not a complete number
bool parseIntToken(std::string_view tok, std::int64_t& out);
std::string quoteToken(std::string_view tok);  // 'tok' shortened and with unprintable bytes escaped

}  // namespace reamsim::io
