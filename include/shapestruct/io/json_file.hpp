// SPDX-License-Identifier: MIT
// json_file: JSON files through nlohmann-json with the library's error conventions (io_error naming the file and
// line:column, duplicate keys refused, type errors naming the key) and a deterministic, readable writer.
#pragma once

#include <charconv>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <fstream>
#include <iterator>
#include <sstream>
#include <stdexcept>
#include <string>
#include <string_view>
#include <type_traits>
#include <unordered_set>
#include <vector>

#include <nlohmann/json.hpp>

#include "shapestruct/core/errors.hpp"
#include "shapestruct/io/file_bytes.hpp"

namespace shapestruct {

namespace detail {

/// A `const char*` that also records, in *seen, how far the parser has read: nlohmann's parser callback reports
/// no position, so a duplicate key is located through this.
struct json_tracking_iterator {
  using iterator_category = std::input_iterator_tag;
  using value_type = char;
  using difference_type = std::ptrdiff_t;
  using pointer = const char*;
  using reference = const char&;

  const char* p = nullptr;
  const char** seen = nullptr;

  reference operator*() const noexcept { return *p; }
  json_tracking_iterator& operator++() noexcept {
    ++p;
    *seen = p;
    return *this;
  }
  json_tracking_iterator operator++(int) noexcept {
    json_tracking_iterator old = *this;
    ++*this;
    return old;
  }
  friend bool operator==(const json_tracking_iterator& a, const json_tracking_iterator& b) noexcept {
    return a.p == b.p;
  }
  friend bool operator!=(const json_tracking_iterator& a, const json_tracking_iterator& b) noexcept {
    return a.p != b.p;
  }
};

/// Thrown from the parser callback; turned into an io_error with line:column by parse_json_text.
struct json_refused {
  std::size_t offset;  ///< 0-based byte offset the problem is reported at
  std::string what;
};

/// 1-based line and column of a 0-based byte offset (column counted in bytes).
inline std::pair<std::int64_t, std::int64_t> json_line_column(std::string_view text, std::size_t offset) {
  std::int64_t line = 1, col = 1;
  for (std::size_t k = 0; k < offset && k < text.size(); ++k) {
    if (text[k] == '\n') {
      ++line;
      col = 1;
    } else {
      ++col;
    }
  }
  return {line, col};
}

[[noreturn]] inline void json_fail(std::string_view text, std::size_t offset, const std::string& path,
                                   const std::string& problem) {
  const auto [line, col] = json_line_column(text, offset);
  throw io_error(offset >= text.size() ? file_error::truncated : file_error::syntax, path, line, 0,
                 "column " + std::to_string(col) + ": " + problem);
}

inline void json_write_number(std::string& out, double x) {
  if (!std::isfinite(x)) throw std::invalid_argument("JSON cannot represent a non-finite number");
  // Shortest representation that reads back to the same double: files round-trip exactly.
  char buf[32];
  const auto r = std::to_chars(buf, buf + sizeof buf, x);
  out.append(buf, r.ptr);
}

inline void json_write_string(std::string& out, const std::string& s) {
  // nlohmann's escaping; bytes that are not UTF-8 (e.g. from a file name) become U+FFFD instead of throwing.
  out += nlohmann::ordered_json(s).dump(-1, ' ', false, nlohmann::ordered_json::error_handler_t::replace);
}

// Arrays of scalars are written on one line (boxes' 3-vectors stay readable); everything else is indented.
inline void json_write(std::string& out, const nlohmann::ordered_json& v, int indent, int level) {
  using t = nlohmann::ordered_json::value_t;
  switch (v.type()) {
    case t::null: out += "null"; return;
    case t::boolean: out += v.get<bool>() ? "true" : "false"; return;
    case t::number_integer: out += std::to_string(v.get<std::int64_t>()); return;
    case t::number_unsigned: out += std::to_string(v.get<std::uint64_t>()); return;
    case t::number_float: json_write_number(out, v.get<double>()); return;
    case t::string: json_write_string(out, v.get_ref<const std::string&>()); return;
    case t::array: {
      bool flat = true;
      for (const auto& e : v) flat = flat && e.is_primitive();
      out += '[';
      std::size_t i = 0;
      for (const auto& e : v) {
        if (i++) out += flat ? ", " : ",";
        if (!flat && indent > 0) out += "\n" + std::string(static_cast<std::size_t>(indent * (level + 1)), ' ');
        json_write(out, e, indent, level + 1);
      }
      if (!flat && !v.empty() && indent > 0) out += "\n" + std::string(static_cast<std::size_t>(indent * level), ' ');
      out += ']';
      return;
    }
    case t::object: {
      out += '{';
      std::size_t i = 0;
      for (const auto& [key, value] : v.items()) {
        if (i++) out += ',';
        if (indent > 0) out += "\n" + std::string(static_cast<std::size_t>(indent * (level + 1)), ' ');
        json_write_string(out, key);
        out += indent > 0 ? ": " : ":";
        json_write(out, value, indent, level + 1);
      }
      if (!v.empty() && indent > 0) out += "\n" + std::string(static_cast<std::size_t>(indent * level), ' ');
      out += '}';
      return;
    }
    case t::binary:
    case t::discarded: break;
  }
  throw std::invalid_argument("JSON cannot represent a binary or discarded value");
}

template <class T>
constexpr const char* json_kind_name() {
  if constexpr (std::is_same_v<T, bool>) return "true or false";
  else if constexpr (std::is_same_v<T, std::string>) return "a string";
  else if constexpr (std::is_integral_v<T>) return "an integer";
  else return "a number";
}

}  // namespace detail

/// Parses JSON text (RFC 8259 through nlohmann-json: no comments, no trailing commas) into an ordered_json, whose
/// objects keep their keys in the file's order. Unlike nlohmann's default, an object with the same key twice is
/// refused, and nesting deeper than 256 levels too. `path` only names the source in errors.
/// \throws io_error (syntax, or truncated at end of input) whose message reads "PATH:LINE: column C: problem"; C is
/// where the reader noticed the problem, i.e. the last character of the offending token (the key's opening quote
/// for a duplicate key), counted in bytes from 1.
/// \returns the document's value. O(length).
inline nlohmann::ordered_json parse_json_text(std::string_view text, const std::string& path = {}) {
  using json = nlohmann::ordered_json;
  constexpr int max_depth = 256;
  const char* seen = text.data();
  std::vector<std::unordered_set<std::string>> keys;  // one set per object being read
  const json::parser_callback_t check = [&](int depth, json::parse_event_t event, json& parsed) {
    switch (event) {
      case json::parse_event_t::object_start:
      case json::parse_event_t::array_start:
        if (depth >= max_depth)
          throw detail::json_refused{static_cast<std::size_t>(seen - text.data()) - 1, "nesting deeper than 256 levels"};
        if (event == json::parse_event_t::object_start) keys.emplace_back();
        break;
      case json::parse_event_t::object_end: keys.pop_back(); break;
      case json::parse_event_t::key: {
        const auto& key = parsed.get_ref<const std::string&>();
        if (!keys.back().insert(key).second) {
          // The parser has just read the key's closing quote; report the key's opening quote.
          std::size_t at = static_cast<std::size_t>(seen - text.data()) - 1;
          while (at > 0) {
            --at;
            if (text[at] != '"') continue;
            std::size_t backslashes = 0;
            while (at > backslashes && text[at - 1 - backslashes] == '\\') ++backslashes;
            if (backslashes % 2 == 0) break;
          }
          std::string quoted;
          detail::json_write_string(quoted, key);
          throw detail::json_refused{at, "duplicate key " + quoted};
        }
        break;
      }
      default: break;
    }
    return true;
  };
  try {
    return json::parse(detail::json_tracking_iterator{text.data(), &seen},
                       detail::json_tracking_iterator{text.data() + text.size(), &seen}, check);
  } catch (const detail::json_refused& r) {
    detail::json_fail(text, r.offset, path, r.what);
  } catch (const json::parse_error& e) {
    // e.byte counts the characters read, the offending one included; nlohmann's message names the line and
    // column too ("... at line L, column C: problem"): keep the problem only, the position is recomputed.
    std::string problem = e.what();
    const auto at = problem.find(", column ");
    const auto colon = at == std::string::npos ? std::string::npos : problem.find(": ", at);
    if (colon != std::string::npos) problem.erase(0, colon + 2);
    detail::json_fail(text, e.byte > 0 ? e.byte - 1 : 0, path, problem);
  } catch (const json::exception& e) {
    // E.g. out_of_range 406, a number too large for a double: reported where the parser stopped reading.
    std::string problem = e.what();
    if (problem.rfind("[json.exception.", 0) == 0 && problem.find("] ") != std::string::npos)
      problem.erase(0, problem.find("] ") + 2);
    detail::json_fail(text, seen > text.data() ? static_cast<std::size_t>(seen - text.data()) - 1 : 0, path, problem);
  }
}

/// Reads and parses a JSON file (see parse_json_text). \throws io_error cannot_open, syntax or truncated naming the
/// path.
inline nlohmann::ordered_json read_json_file(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw io_error(file_error::cannot_open, path, 0, 0, "cannot open file for reading");
  std::ostringstream ss;
  ss << in.rdbuf();
  return parse_json_text(ss.str(), path);
}

/// Serializes a value; `indent` spaces per level (0 = one line). Object keys keep their order; arrays holding no
/// array or object are written on one line; numbers are written in the shortest form that reads back to the
/// same double. The same value always gives the same bytes.
/// \throws std::invalid_argument for a non-finite number. O(size).
inline std::string format_json(const nlohmann::ordered_json& v, int indent = 2) {
  std::string out;
  detail::json_write(out, v, indent, 0);
  return out;
}

/// Writes a value to a file (format_json, then a newline), atomically (temporary file + rename).
/// \throws io_error cannot_open / write_failed naming the path; std::invalid_argument as format_json.
inline void write_json_file(const std::string& path, const nlohmann::ordered_json& v, int indent = 2) {
  io_detail::write_file_atomically(path, format_json(v, indent) + "\n");
}

/// The member `key` of `object`, or nullptr when it has none (or is no object). O(#members).
[[nodiscard]] inline const nlohmann::ordered_json* json_member(const nlohmann::ordered_json& object,
                                                              std::string_view key) {
  if (!object.is_object()) return nullptr;
  const auto it = object.find(key);
  return it == object.end() ? nullptr : &*it;
}

/// The member `key` of `object` as a T (bool, an arithmetic type or std::string).
/// \throws io_error bad_value naming `path` and the key when it is missing or of another type (an integral T
/// also refuses a number with a fraction).
template <class T>
[[nodiscard]] T json_required(const nlohmann::ordered_json& object, std::string_view key, const std::string& path) {
  const auto* v = json_member(object, key);
  if (v == nullptr)
    throw io_error(file_error::bad_value, path, 0, 0, "needs \"" + std::string(key) + "\"");
  bool ok = false;
  if constexpr (std::is_same_v<T, bool>) ok = v->is_boolean();
  else if constexpr (std::is_same_v<T, std::string>) ok = v->is_string();
  else if constexpr (std::is_integral_v<T>)
    ok = v->is_number_integer() || (v->is_number_float() && std::floor(v->get<double>()) == v->get<double>());
  else ok = v->is_number();
  if (!ok)
    throw io_error(file_error::bad_value, path, 0, 0,
                   "\"" + std::string(key) + "\" must be " + detail::json_kind_name<T>() + ", found " + v->type_name());
  if constexpr (std::is_integral_v<T> && !std::is_same_v<T, bool>) {
    if (v->is_number_float()) return static_cast<T>(v->get<double>());
  }
  return v->get<T>();
}

}  // namespace shapestruct
