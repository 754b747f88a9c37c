// SPDX-License-Identifier: MIT
// file_fingerprint: what a shape file's cached results were made from, so that a rerun notices an edited file.
// The caches are keyed by file name; the fingerprint (size and content hash, not the path or the time) makes
// "the same file" mean the same bytes, wherever the folder was moved or copied to.
#pragma once

#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <string>

#include "shapestruct/io/file_bytes.hpp"

namespace shapestruct::cli {

/// "N bytes, fnv1a64 HEX" of the file's contents. \throws io_error (cannot_open) if it cannot be read.
[[nodiscard]] inline std::string file_fingerprint(const std::filesystem::path& file) {
  const std::string bytes = io_detail::read_file_bytes(file);
  std::uint64_t h = 1469598103934665603ULL;  // FNV-1a, 64 bit: fast, and collisions are no concern here
  for (const unsigned char c : bytes) h = (h ^ c) * 1099511628211ULL;
  char hex[17];
  std::snprintf(hex, sizeof hex, "%016llx", static_cast<unsigned long long>(h));
  return std::to_string(bytes.size()) + " bytes, fnv1a64 " + hex;
}

}  // namespace shapestruct::cli
