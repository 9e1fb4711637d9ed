#include "TextScanner.h"

#include <charconv>
#include <cstdio>
#include <system_error>

#include "reamsim/mesh/MeshError.h"

namespace reamsim::io {
namespace {

bool isSpace(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\v' || c == '\f'; }

// from_chars rejects a leading '+', which some exporters write.
std::string_view stripPlus(std::string_view tok) {
  if (tok.size() > 1 && tok[0] == '+' && tok[1] != '-' && tok[1] != '+') tok.remove_prefix(1);
  return tok;
}

// A line's text without the spaces around it (lines hold no '\n').
std::string_view trimmed(std::string_view t) {
  while (!t.empty() && isSpace(t.front())) t.remove_prefix(1);
  while (!t.empty() && isSpace(t.back())) t.remove_suffix(1);
  return t;
}

}  // namespace

bool parseDoubleToken(std::string_view tok, double& out) {
  tok = stripPlus(tok);
  if (tok.empty()) return false;
  const auto [ptr, ec] = std::from_chars(tok.data(), tok.data() + tok.size(), out, std::chars_format::general);
  return ec == std::errc() && ptr == tok.data() + tok.size();
}

bool parseIntToken(std::string_view tok, std::int64_t& out) {
  tok = stripPlus(tok);
  if (tok.empty()) return false;
  const auto [ptr, ec] = std::from_chars(tok.data(), tok.data() + tok.size(), out, 10);
  return ec == std::errc() && ptr == tok.data() + tok.size();
}

std::string quoteToken(std::string_view tok) {
  constexpr std::size_t kMax = 40;
  std::string out = "'";
  for (std::size_t i = 0; i < tok.size() && i < kMax; ++i) {
    const auto c = static_cast<unsigned char>(tok[i]);
    if (c >= 0x20 && c < 0x7f) {
      out += static_cast<char>(c);
    } else {
      char buf[8];
      std::snprintf(buf, sizeof buf, "\\x%02x", c);
      out += buf;
    }
  }
  if (tok.size() > kMax) out += "...";
  return out + "'";
}

TextScanner::TextScanner(std::string_view text, std::string file, char commentChar)
    : text_(text), file_(std::move(file)), comment_(commentChar) {}

bool TextScanner::nextLine() {
  if (next_ >= text_.size()) {
    lineText_ = {};
    pos_ = 0;
    return false;
  }
  const std::size_t start = next_;
  std::size_t end = text_.find('\n', start);
  if (end == std::string_view::npos) {
    end = text_.size();
    next_ = end;
  } else {
    next_ = end + 1;
  }
  lineText_ = text_.substr(start, end - start);
  if (comment_ != '\0') {
    const std::size_t c = lineText_.find(comment_);
    if (c != std::string_view::npos) {
      if (commentLines_ && trimmed(lineText_).front() == comment_)  // the line is only a comment
        commentLines_->emplace_back(trimmed(lineText_.substr(c + 1)));
      lineText_ = lineText_.substr(0, c);
    }
  }
  pos_ = 0;
  ++line_;
  return true;
}

bool TextScanner::nextNonEmptyLine() {
  while (nextLine())
    if (!atLineEnd()) return true;
  return false;
}

bool TextScanner::atLineEnd() {
  while (pos_ < lineText_.size() && isSpace(lineText_[pos_])) ++pos_;
  return pos_ >= lineText_.size();
}

bool TextScanner::token(std::string_view& tok) {
  if (atLineEnd()) return false;
  const std::size_t start = pos_;
  while (pos_ < lineText_.size() && !isSpace(lineText_[pos_])) ++pos_;
  tok = lineText_.substr(start, pos_ - start);
  return true;
}

bool TextScanner::tokenAcrossLines(std::string_view& tok) {
  while (!token(tok))
    if (!nextLine()) return false;
  return true;
}

std::string_view TextScanner::requireToken(const char* what) {
  std::string_view tok;
  if (!token(tok)) fail(std::string("line ends before ") + what);
  return tok;
}

void TextScanner::expectLineEnd(const char* what) {
  std::string_view tok;
  if (token(tok)) fail("unexpected extra token " + quoteToken(tok) + " after " + what);
}

std::string_view TextScanner::restOfLine() {
  const std::string_view rest = trimmed(lineText_.substr(pos_));
  pos_ = lineText_.size();
  return rest;
}

double TextScanner::parseDouble(std::string_view tok, const std::string& what) const {
  double v = 0;
  if (!parseDoubleToken(tok, v)) fail("cannot parse " + what + " from " + quoteToken(tok) + " (not a number or out of range)");
  return v;
}

std::int64_t TextScanner::parseInt(std::string_view tok, const std::string& what) const {
  std::int64_t v = 0;
  if (!parseIntToken(tok, v)) fail("cannot parse " + what + " from " + quoteToken(tok) + " (not an integer)");
  return v;
}

void TextScanner::fail(const std::string& problem) const { throw InputError(file_, line_, problem); }

}  // namespace reamsim::io
