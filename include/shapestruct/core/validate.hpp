// SPDX-License-Identifier: MIT
// validate_mesh: the O(V + F) entry check every public algorithm runs on its input.
#pragma once

#include <string>

#include <Eigen/Core>

#include "shapestruct/core/errors.hpp"
#include "shapestruct/core/types.hpp"

namespace shapestruct {

/// How much an entry point checks its input. `trust` skips validation for callers that already validated.
enum class validation_level { full, trust };

/// Throws invalid_input if (V, F) is empty, has a non-finite coordinate, or has a face with an index out of
/// range or a repeated vertex. `who` names the calling function in the message.
/// \throws invalid_input with reason empty, non_finite (vertex index) or bad_face (face index).
template <class DerivedV, class DerivedF>
void validate_mesh(const Eigen::MatrixBase<DerivedV>& V, const Eigen::MatrixBase<DerivedF>& F, const char* who,
                   validation_level level = validation_level::full) {
  if (level == validation_level::trust) return;
  if (V.rows() == 0 || F.rows() == 0)
    throw invalid_input(input_error::empty, no_index,
                        std::string(who) + ": the mesh is empty (" + std::to_string(V.rows()) + " vertices, " +
                            std::to_string(F.rows()) + " faces)");
  if (V.cols() != 3 || F.cols() != 3)
    throw invalid_input(input_error::size_mismatch, no_index,
                        std::string(who) + ": V must be #V x 3 and F must be #F x 3");
  if (!V.allFinite()) {
    for (index_t i = 0; i < V.rows(); ++i)
      if (!V.row(i).allFinite())
        throw invalid_input(input_error::non_finite, i,
                            std::string(who) + ": vertex " + std::to_string(i) + " has a non-finite coordinate");
  }
  const index_t n = V.rows();
  for (index_t f = 0; f < F.rows(); ++f) {
    const index_t a = static_cast<index_t>(F(f, 0)), b = static_cast<index_t>(F(f, 1)),
                  c = static_cast<index_t>(F(f, 2));
    if (a < 0 || b < 0 || c < 0 || a >= n || b >= n || c >= n)
      throw invalid_input(input_error::bad_face, f,
                          std::string(who) + ": face " + std::to_string(f) + " refers to a vertex outside [0, " +
                              std::to_string(n) + ")");
    if (a == b || b == c || a == c)
      throw invalid_input(input_error::bad_face, f,
                          std::string(who) + ": face " + std::to_string(f) + " repeats a vertex");
  }
}

/// Throws invalid_input if the points are empty or one has a non-finite coordinate.
template <class DerivedP>
void validate_points(const Eigen::MatrixBase<DerivedP>& P, const char* who,
                     validation_level level = validation_level::full) {
  if (level == validation_level::trust) return;
  if (P.rows() == 0) throw invalid_input(input_error::empty, no_index, std::string(who) + ": the point set is empty");
  if (!P.allFinite()) {
    for (index_t i = 0; i < P.rows(); ++i)
      if (!P.row(i).allFinite())
        throw invalid_input(input_error::non_finite, i,
                            std::string(who) + ": point " + std::to_string(i) + " has a non-finite coordinate");
  }
}

}  // namespace shapestruct
