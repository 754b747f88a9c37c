// SPDX-License-Identifier: MIT
// Numerical outcome of an algorithm: returned in results, never thrown (the Spectra/Eigen convention).
#pragma once

namespace shapestruct {

/// How a numerical computation ended. Invalid *input* is an exception (invalid_input); a numerical
/// outcome on valid input is one of these values in the result's `info` field.
enum class status {
  ok,               ///< converged / computed as documented
  not_converged,    ///< an iterative method stopped at its iteration limit; the result is the last iterate
  numerical_issue,  ///< a factorisation or solve failed (e.g. a singular system); the result is unusable
};

inline const char* to_string(status s) noexcept {
  switch (s) {
    case status::ok: return "ok";
    case status::not_converged: return "not_converged";
    case status::numerical_issue: return "numerical_issue";
  }
  return "unknown";
}

}  // namespace shapestruct
