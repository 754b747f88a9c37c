// SPDX-License-Identifier: MIT
// Library configuration: version and the internal-invariant assertion macro.
#pragma once

#include <cstdio>
#include <cstdlib>

#if __has_include(<shapestruct/version.hpp>)
#include <shapestruct/version.hpp>
#else
#define SHAPESTRUCT_VERSION_STRING "0.1.0"
#endif

/// SHAPESTRUCT_ASSERT(cond, msg) checks an internal invariant. It is on in Debug builds and whenever
/// SHAPESTRUCT_ENABLE_ASSERTS is defined (all our tests), and never used to check user data: user data gets
/// an invalid_input exception instead (see core/errors.hpp).
#if !defined(NDEBUG) || defined(SHAPESTRUCT_ENABLE_ASSERTS)
#define SHAPESTRUCT_ASSERT(cond, msg)                                                                  \
  do {                                                                                                 \
    if (!(cond)) {                                                                                     \
      std::fprintf(stderr, "shapestruct: internal invariant failed at %s:%d: %s (%s)\n", __FILE__,     \
                   __LINE__, #cond, msg);                                                              \
      std::abort();                                                                                    \
    }                                                                                                  \
  } while (0)
#else
#define SHAPESTRUCT_ASSERT(cond, msg) \
  do {                                \
  } while (0)
#endif
