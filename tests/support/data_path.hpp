// SPDX-License-Identifier: MIT
// Locating the benchmark data for data-driven tests; they skip cleanly when it is absent.
#pragma once

#include <cstdlib>
#include <filesystem>
#include <optional>
#include <string>

#include <doctest/doctest.h>

namespace shapestruct::test {

/// The benchmark data folder from $SHAPESTRUCT_DATA, or nullopt when unset or missing.
inline std::optional<std::filesystem::path> data_root() {
  const char* env = std::getenv("SHAPESTRUCT_DATA");
  if (env == nullptr || *env == '\0') return std::nullopt;
  std::filesystem::path p(env);
  if (!std::filesystem::is_directory(p)) return std::nullopt;
  return p;
}

}  // namespace shapestruct::test

/// Use at the top of a data-driven test: returns from the test (which CTest then reports as skipped, through
/// the SHAPESTRUCT_SKIP marker) when $SHAPESTRUCT_DATA or the named sub-folder is absent.
#define SHAPESTRUCT_REQUIRE_DATA(var, subfolder)                                                       \
  const auto var##_root = ::shapestruct::test::data_root();                                            \
  if (!var##_root || !std::filesystem::exists(*var##_root / (subfolder))) {                            \
    MESSAGE("SHAPESTRUCT_SKIP: $SHAPESTRUCT_DATA/" << (subfolder) << " not found; test skipped");      \
    return;                                                                                            \
  }                                                                                                    \
  const std::filesystem::path var = *var##_root / (subfolder)
