// SPDX-License-Identifier: MIT
// text_scanner: the hand-written, line-counting tokenizer behind the text readers (OFF, OBJ, ASCII PLY/STL).
#pragma once

#include <charconv>
#include <cmath>
#include <cstdint>
#include <string>
#include <string_view>
#include <system_error>

#include "shapestruct/core/errors.hpp"

namespace shapestruct::io_detail {

/// Walks a text buffer token by token, counting lines so that every error names "path:line". Numbers are
/// parsed with std::from_chars (locale-independent, no allocation, the fastest conversion the standard
/// library offers). `comment` starts a comment running to the end of the line ('\0' for none).
/// Every function is O(characters consumed); nothing allocates except error messages.
class text_scanner {
 public:
  text_scanner(std::string_view text, std::string name, char comment)
      : p_(text.data()), end_(text.data() + text.size()), name_(std::move(name)), comment_(comment) {}

  [[nodiscard]] std::int64_t line() const noexcept { return line_; }
  [[nodiscard]] const std::string& name() const noexcept { return name_; }
  [[nodiscard]] std::size_t remaining() const noexcept { return static_cast<std::size_t>(end_ - p_); }
  [[nodiscard]] const char* position() const noexcept { return p_; }

  [[noreturn]] void fail(file_error reason, const std::string& problem) const {
    throw io_error(reason, name_, line_, 0, problem);
  }

  /// Skips spaces, tabs, carriage returns (CRLF files) and form feeds on the current line.
  void skip_inline_space() noexcept {
    while (p_ != end_ && (*p_ == ' ' || *p_ == '\t' || *p_ == '\r' || *p_ == '\f' || *p_ == '\v')) ++p_;
  }

  /// True when only space or a comment is left on the current line.
  [[nodiscard]] bool at_line_end() noexcept {
    skip_inline_space();
    return p_ == end_ || *p_ == '\n' || (comment_ != '\0' && *p_ == comment_);
  }

  /// Moves past the end of the current line (ignoring whatever is left on it).
  void skip_rest_of_line() noexcept {
    while (p_ != end_ && *p_ != '\n') ++p_;
    if (p_ != end_) {
      ++p_;
      ++line_;
    }
  }

  /// Moves to the first token of the next line holding one (skipping blank and comment-only lines,
  /// starting with the current line). Returns false at end of input.
  bool next_content_line() noexcept {
    for (;;) {
      skip_inline_space();
      if (p_ == end_) return false;
      if (*p_ == '\n' || (comment_ != '\0' && *p_ == comment_)) {
        skip_rest_of_line();
        continue;
      }
      return true;
    }
  }

  /// The next whitespace-delimited token on the current line, empty if the line has no more.
  [[nodiscard]] std::string_view token() noexcept {
    if (at_line_end()) return {};
    const char* b = p_;
    while (p_ != end_ && !is_space(*p_) && !(comment_ != '\0' && *p_ == comment_)) ++p_;
    return {b, static_cast<std::size_t>(p_ - b)};
  }

  /// The rest of the current line (trimmed, comment removed), without consuming the newline.
  [[nodiscard]] std::string_view rest_of_line() noexcept {
    skip_inline_space();
    const char* b = p_;
    while (p_ != end_ && *p_ != '\n' && !(comment_ != '\0' && *p_ == comment_)) ++p_;
    const char* e = p_;
    while (e != b && is_space(e[-1])) --e;
    return {b, static_cast<std::size_t>(e - b)};
  }

  /// Reads a finite floating-point number on the current line.
  /// \throws io_error syntax (missing or not a number) or bad_value (non-finite or out of range).
  double read_double(const char* what) {
    const std::string_view t = token();
    if (t.empty()) fail(file_error::syntax, std::string("expected ") + what + ", found the end of the line");
    return parse_double(t, what);
  }

  /// Reads a decimal integer on the current line.
  /// \throws io_error syntax (missing or not an integer) or bad_value (out of the 64-bit range).
  std::int64_t read_int(const char* what) {
    const std::string_view t = token();
    if (t.empty()) fail(file_error::syntax, std::string("expected ") + what + ", found the end of the line");
    return parse_int(t, what);
  }

  /// Parses a whole token as a finite double ('+' signs accepted; nan/inf rejected as bad_value).
  double parse_double(std::string_view t, const char* what) const {
    std::string_view s = t;
    if (!s.empty() && s[0] == '+') s.remove_prefix(1);
    double v = 0;
    const auto [ptr, ec] = std::from_chars(s.data(), s.data() + s.size(), v);
    if (ec == std::errc::result_out_of_range)
      fail(file_error::bad_value, std::string(what) + " '" + clip(t) + "' is out of the double range");
    if (ec != std::errc() || ptr != s.data() + s.size() || s.empty())
      fail(file_error::syntax, std::string("expected ") + what + ", found '" + clip(t) + "'");
    if (!std::isfinite(v)) fail(file_error::bad_value, std::string(what) + " '" + clip(t) + "' is not finite");
    return v;
  }

  /// Parses a whole token as a 64-bit integer ('+' accepted).
  std::int64_t parse_int(std::string_view t, const char* what) const {
    std::string_view s = t;
    if (!s.empty() && s[0] == '+') s.remove_prefix(1);
    std::int64_t v = 0;
    const auto [ptr, ec] = std::from_chars(s.data(), s.data() + s.size(), v);
    if (ec == std::errc::result_out_of_range)
      fail(file_error::bad_value, std::string(what) + " '" + clip(t) + "' is out of the 64-bit integer range");
    if (ec != std::errc() || ptr != s.data() + s.size() || s.empty())
      fail(file_error::syntax, std::string("expected ") + what + " (an integer), found '" + clip(t) + "'");
    return v;
  }

  /// A token shortened for messages: hostile files can hold megabyte-long tokens.
  [[nodiscard]] static std::string clip(std::string_view t) {
    std::string out;
    const std::size_t n = t.size() < 40 ? t.size() : 40;
    for (std::size_t i = 0; i < n; ++i) {
      const unsigned char c = static_cast<unsigned char>(t[i]);
      out += (c >= 32 && c < 127) ? static_cast<char>(c) : '?';
    }
    if (t.size() > 40) out += "...";
    return out;
  }

  [[nodiscard]] static bool is_space(char c) noexcept {
    return c == ' ' || c == '\t' || c == '\r' || c == '\n' || c == '\f' || c == '\v';
  }

 private:
  const char* p_;
  const char* end_;
  std::string name_;
  char comment_;
  std::int64_t line_ = 1;
};

/// ASCII case-insensitive equality.
[[nodiscard]] inline bool iequals(std::string_view a, std::string_view b) noexcept {
  if (a.size() != b.size()) return false;
  for (std::size_t i = 0; i < a.size(); ++i) {
    char x = a[i], y = b[i];
    if (x >= 'A' && x <= 'Z') x = static_cast<char>(x - 'A' + 'a');
    if (y >= 'A' && y <= 'Z') y = static_cast<char>(y - 'A' + 'a');
    if (x != y) return false;
  }
  return true;
}

}  // namespace shapestruct::io_detail
