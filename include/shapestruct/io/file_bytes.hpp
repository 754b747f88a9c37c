// SPDX-License-Identifier: MIT
// file_bytes: whole-file reading and crash-safe (temporary file + rename) writing shared by every format.
#pragma once

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <string>
#include <string_view>
#include <system_error>

#include "shapestruct/core/errors.hpp"

namespace shapestruct::io_detail {

/// Throws io_error. Kept out of line: inlined at call sites with constant line/offset arguments, the message
/// composition trips g++ 12's false -Wrestrict positive (GCC bug 105651) under -Werror.
[[noreturn, gnu::noinline, gnu::cold]] inline void raise(file_error reason, const std::string& path, std::int64_t line,
                                                         std::int64_t byte_offset, const std::string& problem) {
  throw io_error(reason, path, line, byte_offset, problem);
}

/// Reads the whole file into memory. Every reader parses from one buffer: one system call instead of
/// stream machinery per token, and the byte count is known up front so header counts can be checked
/// against it before anything is allocated.
/// \param path the file to read.
/// \returns the file's bytes.
/// \throws io_error (cannot_open) if the file cannot be opened or read completely.
/// Complexity: O(file size).
[[nodiscard]] inline std::string read_file_bytes(const std::filesystem::path& path) {
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec))
    raise(file_error::cannot_open, path.string(), 0, 0, "is a directory, not a mesh file");
  std::FILE* f = std::fopen(path.c_str(), "rb");
  if (f == nullptr) raise(file_error::cannot_open, path.string(), 0, 0, "cannot open the file for reading");
  std::string bytes;
  char chunk[1 << 16];
  // Chunked reads rather than seek/tell: works for pipes and /proc files whose size is not known up front.
  for (;;) {
    const std::size_t got = std::fread(chunk, 1, sizeof chunk, f);
    bytes.append(chunk, got);
    if (got < sizeof chunk) break;
  }
  const bool failed = std::ferror(f) != 0;
  std::fclose(f);
  if (failed) raise(file_error::cannot_open, path.string(), 0, 0, "read error while reading the file");
  return bytes;
}

/// Writes `bytes` to `path` atomically: the data goes to a temporary file in the same folder which is then
/// renamed over `path`. A failed write (full disk, missing folder, no permission) therefore never leaves a
/// half-written file and never destroys an existing one.
/// \param path destination; its folder must exist.
/// \param bytes the complete file contents.
/// \throws io_error (cannot_open if the temporary file cannot be created, write_failed if writing, flushing
///         or renaming fails).
/// Complexity: O(bytes.size()).
inline void write_file_atomically(const std::filesystem::path& path, std::string_view bytes) {
  const std::filesystem::path folder = path.has_parent_path() ? path.parent_path() : std::filesystem::path(".");
  // The name only has to be unlikely to collide with another writer in the same folder; the time stamp and
  // the address of a stack variable differ between concurrent writers in one or several processes.
  const auto stamp = std::chrono::steady_clock::now().time_since_epoch().count();
  const int local = 0;
  std::string tmp_name(".");  // built by appending: "literal" + std::string trips g++ 12's -Wrestrict bug
  tmp_name.append(path.filename().string()).append(".tmp-").append(std::to_string(stamp)).append("-");
  tmp_name.append(std::to_string(reinterpret_cast<std::uintptr_t>(&local) % 100000));
  const std::filesystem::path tmp = folder / tmp_name;
  std::FILE* f = std::fopen(tmp.c_str(), "wb");
  if (f == nullptr)
    raise(file_error::cannot_open, path.string(), 0, 0,
                   "cannot create a temporary file in the destination folder");
  const bool wrote = std::fwrite(bytes.data(), 1, bytes.size(), f) == bytes.size();
  const bool flushed = std::fflush(f) == 0;
  const bool closed = std::fclose(f) == 0;
  std::error_code ec;
  if (!wrote || !flushed || !closed) {
    std::filesystem::remove(tmp, ec);
    raise(file_error::write_failed, path.string(), 0, 0,
                   "could not write all " + std::to_string(bytes.size()) + " bytes (disk full?); file left unchanged");
  }
  std::filesystem::rename(tmp, path, ec);
  if (ec) {
    std::error_code ignored;
    std::filesystem::remove(tmp, ignored);
    raise(file_error::write_failed, path.string(), 0, 0,
                   "could not move the temporary file into place: " + ec.message());
  }
}

/// Lower-case extension without the dot ("OFF" -> "off"); empty if none.
[[nodiscard]] inline std::string lower_extension(const std::filesystem::path& path) {
  std::string ext = path.extension().string();
  if (!ext.empty() && ext[0] == '.') ext.erase(0, 1);
  for (char& c : ext)
    if (c >= 'A' && c <= 'Z') c = static_cast<char>(c - 'A' + 'a');
  return ext;
}

}  // namespace shapestruct::io_detail
