// SPDX-License-Identifier: MIT
// Helpers shared by the io tests: checking the reason and position of an io_error, temporary folders.
#pragma once

#include <filesystem>
#include <random>
#include <string>

#include <doctest/doctest.h>

#include "shapestruct/core/errors.hpp"

namespace shapestruct::test {

/// Runs `f`, requires it to throw io_error with `reason`, and returns the error for further checks.
template <class F>
io_error require_io_error(F&& f, file_error reason) {
  try {
    f();
  } catch (const io_error& e) {
    INFO("message: " << std::string(e.what()));
    CHECK(std::string(to_string(e.reason())) == std::string(to_string(reason)));
    return e;
  }
  FAIL("expected io_error " << to_string(reason) << ", nothing was thrown");
  return io_error(file_error::syntax, "", 0, 0, "unreachable");
}

/// A fresh folder under the system temp folder, removed when the object goes out of scope.
struct temp_folder {
  std::filesystem::path path;
  temp_folder() {
    std::mt19937_64 rng(std::random_device{}());
    path = std::filesystem::temp_directory_path() / ("shapestruct-io-test-" + std::to_string(rng()));
    std::filesystem::create_directories(path);
  }
  ~temp_folder() {
    std::error_code ec;
    std::filesystem::remove_all(path, ec);
  }
  temp_folder(const temp_folder&) = delete;
  temp_folder& operator=(const temp_folder&) = delete;
};

}  // namespace shapestruct::test
