// SPDX-License-Identifier: MIT
// Typed exceptions for invalid input (algorithm preconditions) and unreadable files (parsers).
#pragma once

#include <cstdint>
#include <stdexcept>
#include <string>

#include "shapestruct/core/types.hpp"

namespace shapestruct {

/// Why an algorithm rejected its input. Each reason has at least one test per entry point that throws it.
enum class input_error {
  empty,                 ///< no vertices, faces or points where some are required
  bad_face,              ///< a face index out of range, or a face repeating a vertex
  non_finite,            ///< a NaN or infinite coordinate
  degenerate_face,       ///< a zero-area face where the option says degenerate faces are errors
  non_manifold,          ///< a non-manifold edge or vertex where the mathematics needs a manifold
  unsupported_topology,  ///< e.g. boundary, genus or several components where a closed genus-0 surface is needed
  size_mismatch,         ///< two inputs that must agree in size do not
  bad_parameter,         ///< an option out of its documented range
};

inline const char* to_string(input_error e) noexcept {
  switch (e) {
    case input_error::empty: return "empty";
    case input_error::bad_face: return "bad_face";
    case input_error::non_finite: return "non_finite";
    case input_error::degenerate_face: return "degenerate_face";
    case input_error::non_manifold: return "non_manifold";
    case input_error::unsupported_topology: return "unsupported_topology";
    case input_error::size_mismatch: return "size_mismatch";
    case input_error::bad_parameter: return "bad_parameter";
  }
  return "unknown";
}

/// Thrown when user data violates an algorithm's documented precondition. Carries the reason, the
/// offending element's index (vertex, face, edge, point, or no_index) and a full sentence naming the
/// function and, where there is one, the option that would accept the input.
class invalid_input : public std::invalid_argument {
 public:
  invalid_input(input_error reason, index_t element, const std::string& message)
      : std::invalid_argument(message), reason_(reason), element_(element) {}

  [[nodiscard]] input_error reason() const noexcept { return reason_; }
  [[nodiscard]] index_t element() const noexcept { return element_; }

 private:
  input_error reason_;
  index_t element_;
};

/// Why a file could not be read or written.
enum class file_error {
  cannot_open,   ///< the file does not exist or cannot be opened / created
  syntax,        ///< a token is not what the format allows at that place
  truncated,     ///< the file ends before the data its header announces
  bad_index,     ///< a face refers to a vertex that does not exist
  bad_value,     ///< a number is out of range, non-finite where not allowed, or a count is negative
  unsupported,   ///< a valid feature of the format that shapestruct does not read (named in the message)
  too_large,     ///< a count in the header would need more memory than the file could possibly describe
  write_failed,  ///< the output could not be written completely
};

inline const char* to_string(file_error e) noexcept {
  switch (e) {
    case file_error::cannot_open: return "cannot_open";
    case file_error::syntax: return "syntax";
    case file_error::truncated: return "truncated";
    case file_error::bad_index: return "bad_index";
    case file_error::bad_value: return "bad_value";
    case file_error::unsupported: return "unsupported";
    case file_error::too_large: return "too_large";
    case file_error::write_failed: return "write_failed";
  }
  return "unknown";
}

/// Thrown by readers and writers. The message reads "PATH:LINE: problem" for text formats and
/// "PATH: byte OFFSET: problem" for binary ones; the parts are also available separately.
class io_error : public std::runtime_error {
 public:
  /// line and byte_offset are 0 when unknown (lines count from 1).
  io_error(file_error reason, std::string path, std::int64_t line, std::int64_t byte_offset,
           const std::string& problem)
      : std::runtime_error(compose(path, line, byte_offset, problem)),
        reason_(reason),
        path_(std::move(path)),
        line_(line),
        byte_offset_(byte_offset) {}

  [[nodiscard]] file_error reason() const noexcept { return reason_; }
  [[nodiscard]] const std::string& path() const noexcept { return path_; }
  [[nodiscard]] std::int64_t line() const noexcept { return line_; }
  [[nodiscard]] std::int64_t byte_offset() const noexcept { return byte_offset_; }

 private:
  static std::string compose(const std::string& path, std::int64_t line, std::int64_t offset,
                             const std::string& problem) {
    // Appends piece by piece: `"literal" + std::string` here trips g++ 12's false -Wrestrict (GCC bug 105651).
    std::string where = path.empty() ? std::string("<memory>") : path;
    if (line > 0) where.append(":").append(std::to_string(line));
    else if (offset > 0) where.append(": byte ").append(std::to_string(offset));
    return where.append(": ").append(problem);
  }

  file_error reason_;
  std::string path_;
  std::int64_t line_;
  std::int64_t byte_offset_;
};

}  // namespace shapestruct
