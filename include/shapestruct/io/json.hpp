// SPDX-License-Identifier: MIT
// json_value: a small JSON document model with a reader that reports line:column and a deterministic writer.
#pragma once

#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <fstream>
#include <map>
#include <memory>
#include <sstream>
#include <string>
#include <utility>
#include <variant>
#include <vector>

#include "shapestruct/core/errors.hpp"

// GCC 12 issues false -Warray-bounds / -Wstringop-overflow reports for std::variant members of recursive types
// constructed inline (GCC bug 105746 family); the warnings point into this header, so they are silenced here only.
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Warray-bounds"
#pragma GCC diagnostic ignored "-Wstringop-overflow"
#endif

namespace shapestruct {

/// A JSON value: null, boolean, number (double), string, array or object. Objects keep their keys in insertion
/// order (so a hand-written file round-trips in the order its author chose) and reject duplicate keys on read.
/// Written to serve template files (templates/part_template.hpp) without a non-Debian dependency.
class json_value {
 public:
  using array = std::vector<json_value>;
  using object = std::vector<std::pair<std::string, json_value>>;
  enum class kind { null, boolean, number, string, array, object };

  json_value() = default;
  json_value(std::nullptr_t) {}
  json_value(bool b) : v_(b) {}
  json_value(double x) : v_(x) {}
  json_value(int x) : v_(static_cast<double>(x)) {}
  json_value(long x) : v_(static_cast<double>(x)) {}
  json_value(long long x) : v_(static_cast<double>(x)) {}
  json_value(const char* s) : v_(std::string(s)) {}
  json_value(std::string s) : v_(std::move(s)) {}
  json_value(array a) : v_(std::make_shared<array>(std::move(a))) {}
  json_value(object o) : v_(std::make_shared<object>(std::move(o))) {}

  [[nodiscard]] kind type() const noexcept { return static_cast<kind>(v_.index()); }
  [[nodiscard]] bool is_null() const noexcept { return type() == kind::null; }
  [[nodiscard]] bool is_number() const noexcept { return type() == kind::number; }
  [[nodiscard]] bool is_string() const noexcept { return type() == kind::string; }
  [[nodiscard]] bool is_bool() const noexcept { return type() == kind::boolean; }
  [[nodiscard]] bool is_array() const noexcept { return type() == kind::array; }
  [[nodiscard]] bool is_object() const noexcept { return type() == kind::object; }

  /// Accessors throw std::invalid_argument naming the expected kind when the value has another kind; the
  /// template reader turns that into an io_error naming the file and the key.
  [[nodiscard]] bool as_bool() const { return get<bool>("a boolean"); }
  [[nodiscard]] double as_number() const { return get<double>("a number"); }
  [[nodiscard]] const std::string& as_string() const { return get<std::string>("a string"); }
  [[nodiscard]] const array& as_array() const { return *get<std::shared_ptr<array>>("an array"); }
  [[nodiscard]] const object& as_object() const { return *get<std::shared_ptr<object>>("an object"); }
  [[nodiscard]] array& as_array() { return *get_mut<std::shared_ptr<array>>("an array"); }
  [[nodiscard]] object& as_object() { return *get_mut<std::shared_ptr<object>>("an object"); }

  /// The member named key of an object, or nullptr when absent. O(#members).
  [[nodiscard]] const json_value* find(const std::string& key) const {
    for (const auto& [k, v] : as_object())
      if (k == key) return &v;
    return nullptr;
  }
  /// Appends (or replaces) a member of an object.
  void set(const std::string& key, json_value v) {
    for (auto& [k, old] : as_object())
      if (k == key) {
        old = std::move(v);
        return;
      }
    as_object().emplace_back(key, std::move(v));
  }

  static const char* kind_name(kind k) noexcept {
    switch (k) {
      case kind::null: return "null";
      case kind::boolean: return "a boolean";
      case kind::number: return "a number";
      case kind::string: return "a string";
      case kind::array: return "an array";
      case kind::object: return "an object";
    }
    return "?";
  }

 private:
  template <class T>
  const T& get(const char* what) const {
    if (const T* p = std::get_if<T>(&v_)) return *p;
    throw std::invalid_argument(std::string("expected ") + what + ", found " + kind_name(type()));
  }
  template <class T>
  T& get_mut(const char* what) {
    if (T* p = std::get_if<T>(&v_)) {
      // Copy-on-write: values share containers after a copy, so detach before mutating.
      if (p->use_count() > 1) *p = std::make_shared<typename T::element_type>(**p);
      return *p;
    }
    throw std::invalid_argument(std::string("expected ") + what + ", found " + kind_name(type()));
  }
  std::variant<std::monostate, bool, double, std::string, std::shared_ptr<array>, std::shared_ptr<object>> v_;
};

namespace detail {

class json_parser {
 public:
  json_parser(const std::string& text, const std::string& path) : s_(text), path_(path) {}

  json_value parse_document() {
    skip_ws();
    json_value v = parse_value(0);
    skip_ws();
    if (i_ != s_.size()) fail("unexpected text after the JSON value");
    return v;
  }

 private:
  // Nesting deeper than this is certainly not a template file; the cap keeps recursion off the stack limit.
  static constexpr int max_depth = 256;

  [[noreturn]] void fail(const std::string& what) const {
    std::int64_t line = 1, col = 1;
    for (std::size_t k = 0; k < i_ && k < s_.size(); ++k) {
      if (s_[k] == '\n') {
        ++line;
        col = 1;
      } else {
        ++col;
      }
    }
    throw io_error(i_ >= s_.size() ? file_error::truncated : file_error::syntax, path_, line, 0,
                   "column " + std::to_string(col) + ": " + what);
  }
  void skip_ws() {
    while (i_ < s_.size() && (s_[i_] == ' ' || s_[i_] == '\t' || s_[i_] == '\n' || s_[i_] == '\r')) ++i_;
  }
  char peek() const { return i_ < s_.size() ? s_[i_] : '\0'; }
  void expect(char c) {
    if (peek() != c) fail(std::string("expected '") + c + "'");
    ++i_;
  }
  void literal(const char* word) {
    for (const char* p = word; *p; ++p) {
      if (peek() != *p) fail(std::string("invalid literal, expected '") + word + "'");
      ++i_;
    }
  }

  json_value parse_value(int depth) {
    if (depth > max_depth) fail("nesting deeper than 256 levels");
    if (i_ >= s_.size()) fail("unexpected end of input");
    const char c = s_[i_];
    if (c == '{') return parse_object(depth);
    if (c == '[') return parse_array(depth);
    if (c == '"') return json_value(parse_string());
    if (c == 't') {
      literal("true");
      return json_value(true);
    }
    if (c == 'f') {
      literal("false");
      return json_value(false);
    }
    if (c == 'n') {
      literal("null");
      return json_value(nullptr);
    }
    if (c == '-' || (c >= '0' && c <= '9')) return json_value(parse_number());
    fail(std::string("unexpected character '") + c + "'");
  }

  json_value parse_object(int depth) {
    expect('{');
    json_value::object members;
    skip_ws();
    if (peek() == '}') {
      ++i_;
      return json_value(std::move(members));
    }
    for (;;) {
      skip_ws();
      if (peek() != '"') fail("expected a string key");
      std::string key = parse_string();
      for (const auto& m : members)
        if (m.first == key) fail("duplicate key \"" + key + "\"");
      skip_ws();
      expect(':');
      skip_ws();
      members.emplace_back(std::move(key), parse_value(depth + 1));
      skip_ws();
      if (peek() == ',') {
        ++i_;
        continue;
      }
      if (peek() == '}') {
        ++i_;
        return json_value(std::move(members));
      }
      fail("expected ',' or '}' in an object");
    }
  }

  json_value parse_array(int depth) {
    expect('[');
    json_value::array items;
    skip_ws();
    if (peek() == ']') {
      ++i_;
      return json_value(std::move(items));
    }
    for (;;) {
      skip_ws();
      items.push_back(parse_value(depth + 1));
      skip_ws();
      if (peek() == ',') {
        ++i_;
        continue;
      }
      if (peek() == ']') {
        ++i_;
        return json_value(std::move(items));
      }
      fail("expected ',' or ']' in an array");
    }
  }

  static void put_utf8(std::string& out, std::uint32_t cp) {
    if (cp < 0x80) {
      out += static_cast<char>(cp);
    } else if (cp < 0x800) {
      out += static_cast<char>(0xC0 | (cp >> 6));
      out += static_cast<char>(0x80 | (cp & 0x3F));
    } else if (cp < 0x10000) {
      out += static_cast<char>(0xE0 | (cp >> 12));
      out += static_cast<char>(0x80 | ((cp >> 6) & 0x3F));
      out += static_cast<char>(0x80 | (cp & 0x3F));
    } else {
      out += static_cast<char>(0xF0 | (cp >> 18));
      out += static_cast<char>(0x80 | ((cp >> 12) & 0x3F));
      out += static_cast<char>(0x80 | ((cp >> 6) & 0x3F));
      out += static_cast<char>(0x80 | (cp & 0x3F));
    }
  }
  std::uint32_t hex4() {
    std::uint32_t v = 0;
    for (int k = 0; k < 4; ++k) {
      const char c = peek();
      v <<= 4;
      if (c >= '0' && c <= '9') v |= static_cast<std::uint32_t>(c - '0');
      else if (c >= 'a' && c <= 'f') v |= static_cast<std::uint32_t>(c - 'a' + 10);
      else if (c >= 'A' && c <= 'F') v |= static_cast<std::uint32_t>(c - 'A' + 10);
      else fail("bad \\u escape");
      ++i_;
    }
    return v;
  }

  std::string parse_string() {
    expect('"');
    std::string out;
    for (;;) {
      if (i_ >= s_.size()) fail("unterminated string");
      const char c = s_[i_++];
      if (c == '"') return out;
      if (static_cast<unsigned char>(c) < 0x20) {
        --i_;
        fail("control character inside a string");
      }
      if (c != '\\') {
        out += c;
        continue;
      }
      const char e = peek();
      ++i_;
      switch (e) {
        case '"': out += '"'; break;
        case '\\': out += '\\'; break;
        case '/': out += '/'; break;
        case 'b': out += '\b'; break;
        case 'f': out += '\f'; break;
        case 'n': out += '\n'; break;
        case 'r': out += '\r'; break;
        case 't': out += '\t'; break;
        case 'u': {
          std::uint32_t cp = hex4();
          if (cp >= 0xD800 && cp < 0xDC00) {  // surrogate pair
            if (peek() != '\\') fail("unpaired surrogate in \\u escape");
            ++i_;
            if (peek() != 'u') fail("unpaired surrogate in \\u escape");
            ++i_;
            const std::uint32_t lo = hex4();
            if (lo < 0xDC00 || lo > 0xDFFF) fail("bad low surrogate in \\u escape");
            cp = 0x10000 + ((cp - 0xD800) << 10) + (lo - 0xDC00);
          }
          put_utf8(out, cp);
          break;
        }
        default: --i_; fail("invalid escape sequence");
      }
    }
  }

  double parse_number() {
    const std::size_t start = i_;
    if (peek() == '-') ++i_;
    if (peek() == '0') {
      ++i_;
    } else if (peek() >= '1' && peek() <= '9') {
      while (peek() >= '0' && peek() <= '9') ++i_;
    } else {
      fail("a number needs digits");
    }
    if (peek() == '.') {
      ++i_;
      if (!(peek() >= '0' && peek() <= '9')) fail("a fraction needs digits");
      while (peek() >= '0' && peek() <= '9') ++i_;
    }
    if (peek() == 'e' || peek() == 'E') {
      ++i_;
      if (peek() == '+' || peek() == '-') ++i_;
      if (!(peek() >= '0' && peek() <= '9')) fail("an exponent needs digits");
      while (peek() >= '0' && peek() <= '9') ++i_;
    }
    double x = 0;
    const auto r = std::from_chars(s_.data() + start, s_.data() + i_, x);
    if (r.ec != std::errc() || !std::isfinite(x)) {
      i_ = start;
      fail("number out of range");
    }
    return x;
  }

  const std::string& s_;
  std::string path_;
  std::size_t i_ = 0;
};

inline void json_write_string(std::string& out, const std::string& s) {
  out += '"';
  for (const char c : s) {
    switch (c) {
      case '"': out += "\\\""; break;
      case '\\': out += "\\\\"; break;
      case '\n': out += "\\n"; break;
      case '\r': out += "\\r"; break;
      case '\t': out += "\\t"; break;
      default:
        if (static_cast<unsigned char>(c) < 0x20) {
          char buf[8];
          std::snprintf(buf, sizeof buf, "\\u%04x", static_cast<unsigned>(static_cast<unsigned char>(c)));
          out += buf;
        } else {
          out += c;
        }
    }
  }
  out += '"';
}

inline void json_write_number(std::string& out, double x) {
  if (!std::isfinite(x)) throw std::invalid_argument("JSON cannot represent a non-finite number");
  // Shortest representation that reads back to the same double: files round-trip exactly.
  char buf[32];
  const auto r = std::to_chars(buf, buf + sizeof buf, x);
  out.append(buf, r.ptr);
}

// Arrays of scalars are written on one line (boxes' 3-vectors stay readable); everything else is indented.
inline void json_write(std::string& out, const json_value& v, int indent, int level) {
  using k = json_value::kind;
  switch (v.type()) {
    case k::null: out += "null"; return;
    case k::boolean: out += v.as_bool() ? "true" : "false"; return;
    case k::number: json_write_number(out, v.as_number()); return;
    case k::string: json_write_string(out, v.as_string()); return;
    case k::array: {
      const auto& a = v.as_array();
      bool flat = true;
      for (const auto& e : a) flat = flat && (e.is_number() || e.is_bool() || e.is_null() || e.is_string());
      out += '[';
      for (std::size_t i = 0; i < a.size(); ++i) {
        if (i) out += flat ? ", " : ",";
        if (!flat && indent > 0) out += "\n" + std::string(static_cast<std::size_t>(indent * (level + 1)), ' ');
        json_write(out, a[i], indent, level + 1);
      }
      if (!flat && !a.empty() && indent > 0) out += "\n" + std::string(static_cast<std::size_t>(indent * level), ' ');
      out += ']';
      return;
    }
    case k::object: {
      const auto& o = v.as_object();
      out += '{';
      for (std::size_t i = 0; i < o.size(); ++i) {
        if (i) out += ',';
        if (indent > 0) out += "\n" + std::string(static_cast<std::size_t>(indent * (level + 1)), ' ');
        json_write_string(out, o[i].first);
        out += indent > 0 ? ": " : ":";
        json_write(out, o[i].second, indent, level + 1);
      }
      if (!o.empty() && indent > 0) out += "\n" + std::string(static_cast<std::size_t>(indent * level), ' ');
      out += '}';
      return;
    }
  }
}

}  // namespace detail

/// Parses JSON text (RFC 8259; no comments, no trailing commas). `path` only names the source in errors.
/// \throws io_error (syntax, or truncated at end of input) whose message reads "PATH:LINE: column C: problem".
/// \returns the document's value. O(length).
inline json_value parse_json(const std::string& text, const std::string& path = {}) {
  return detail::json_parser(text, path).parse_document();
}

/// Reads and parses a JSON file. \throws io_error cannot_open, syntax or truncated naming the path.
inline json_value read_json(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw io_error(file_error::cannot_open, path, 0, 0, "cannot open file for reading");
  std::ostringstream ss;
  ss << in.rdbuf();
  return parse_json(ss.str(), path);
}

/// Serializes a value; `indent` spaces per level (0 = one line). Numbers are written in the shortest form that
/// reads back to the same double. \throws std::invalid_argument for a non-finite number. O(size).
inline std::string to_json_string(const json_value& v, int indent = 2) {
  std::string out;
  detail::json_write(out, v, indent, 0);
  return out;
}

/// Writes a value to a file (whole file replaced). \throws io_error cannot_open / write_failed naming the path.
inline void write_json(const std::string& path, const json_value& v, int indent = 2) {
  const std::string text = to_json_string(v, indent) + "\n";
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  if (!out) throw io_error(file_error::cannot_open, path, 0, 0, "cannot open file for writing");
  out.write(text.data(), static_cast<std::streamsize>(text.size()));
  out.flush();
  if (!out) throw io_error(file_error::write_failed, path, 0, 0, "could not write the whole file");
}

}  // namespace shapestruct

#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic pop
#endif
