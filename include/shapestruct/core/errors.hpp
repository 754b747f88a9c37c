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

/// The surface defects an algorithm needing a closed genus-0 manifold refuses, each with the repair (if any)
/// that removes it, so that a caller (e.g. a command-line tool) can name its own switch for that repair.
enum class mesh_defect {
  collapsed_face,       ///< a face with a repeated corner (repair: remove_collapsed_and_duplicate_faces)
  duplicate_face,       ///< two faces on the same three vertices (same repair)
  non_manifold_edge,    ///< an edge with more than two faces that are not duplicates (no repair)
  non_manifold_vertex,  ///< a vertex joining several fans of faces (repair: split_non_manifold_vertices)
  several_pieces,       ///< more than one connected component (repair: keep_largest_component)
  hole,                 ///< a boundary loop (repair: close_small_holes, up to a loop length)
  non_orientable,       ///< faces that cannot be oriented consistently (no repair)
  genus,                ///< handles: a closed surface that is not a topological sphere (no repair)
  coordinate_overflow,  ///< coordinates so large that lengths or areas overflow (rescale the input)
  zero_area,            ///< the surface has no area (no repair)
};

inline const char* to_string(mesh_defect d) noexcept {
  switch (d) {
    case mesh_defect::collapsed_face: return "collapsed_face";
    case mesh_defect::duplicate_face: return "duplicate_face";
    case mesh_defect::non_manifold_edge: return "non_manifold_edge";
    case mesh_defect::non_manifold_vertex: return "non_manifold_vertex";
    case mesh_defect::several_pieces: return "several_pieces";
    case mesh_defect::hole: return "hole";
    case mesh_defect::non_orientable: return "non_orientable";
    case mesh_defect::genus: return "genus";
    case mesh_defect::coordinate_overflow: return "coordinate_overflow";
    case mesh_defect::zero_area: return "zero_area";
  }
  return "unknown";
}

/// An invalid_input that is a surface defect: the reason (non_manifold, unsupported_topology, ...), which defect
/// it is, and the message in two halves, the problem and the library's remedy, so that a caller (e.g. a tool
/// with its own switches) can state the problem and give its own remedy without parsing the message.
/// what() is "who: problem; remedy".
class mesh_defect_error : public invalid_input {
 public:
  mesh_defect_error(input_error reason, mesh_defect defect, index_t element, const std::string& who,
                    const std::string& problem, const std::string& remedy)
      : invalid_input(reason, element, who + ": " + problem + (remedy.empty() ? "" : "; " + remedy)),
        defect_(defect),
        problem_(problem),
        remedy_(remedy) {}
  [[nodiscard]] mesh_defect defect() const noexcept { return defect_; }
  /// What is wrong, naming the element, e.g. "it has 2 holes (a boundary loop runs along edge (4, 9))".
  [[nodiscard]] const std::string& problem() const noexcept { return problem_; }
  /// The library's way out (an option, a repair function), or "" when there is none.
  [[nodiscard]] const std::string& remedy() const noexcept { return remedy_; }

 private:
  mesh_defect defect_;
  std::string problem_, remedy_;
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
