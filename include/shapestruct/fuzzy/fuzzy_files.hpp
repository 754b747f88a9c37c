// SPDX-License-Identifier: MIT
// fuzzy_files: writes and reads a collection's fuzzy correspondence (embedding, widths) as one binary file.
#pragma once

#include <cstdint>
#include <filesystem>
#include <vector>

#include "shapestruct/collection/collection_files.hpp"
#include "shapestruct/fuzzy/fuzzy_correspondence.hpp"

namespace shapestruct {

/// Layout of fuzzy.bin (host byte order, documented in docs/fuzzy.md): u32 magic "SSFC", u32 version,
/// f64 cutoff, f64 trivial eigenvalue, then arrays each as u64 length + data: offsets (i64, N + 1), eigenvalues
/// (f64, d), coordinates as i64 rows, i64 cols + f32 column-major (NK x d), tau (f32, NK).
inline void write_fuzzy_correspondence(const std::filesystem::path& path, const fuzzy_correspondence& f) {
  detail::binary_writer w;
  w.put<std::uint32_t>(0x43465353);
  w.put(detail::collection_file_version);
  w.put(f.cutoff());
  w.put(f.embedding().trivial_eigenvalue);
  const auto& e = f.embedding();
  w.put_array(e.offsets.data(), e.offsets.size());
  w.put_array(e.eigenvalues.data(), static_cast<std::size_t>(e.eigenvalues.size()));
  detail::put_matrix(w, e.coordinates);
  w.put_array(f.tau().data(), static_cast<std::size_t>(f.tau().size()));
  io_detail::write_file_atomically(path, w.bytes());
}

/// Reads fuzzy.bin. \throws io_error (cannot_open; syntax for a damaged or inconsistent file).
[[nodiscard]] inline fuzzy_correspondence read_fuzzy_correspondence(const std::filesystem::path& path) {
  const std::string bytes = io_detail::read_file_bytes(path);
  detail::binary_reader r(bytes, path.string());
  if (r.get<std::uint32_t>() != 0x43465353) r.fail("not a fuzzy correspondence file");
  if (r.get<std::uint32_t>() != detail::collection_file_version) r.fail("written by another version");
  const double cutoff = r.get<double>();
  diffusion_embedding e;
  e.trivial_eigenvalue = r.get<double>();
  e.offsets = r.get_array<index_t>();
  const auto ev = r.get_array<double>();
  e.eigenvalues = Eigen::Map<const Eigen::VectorXd>(ev.data(), static_cast<index_t>(ev.size()));
  e.coordinates = detail::get_matrix<Eigen::MatrixXf>(r);
  const auto tau = r.get_array<float>();
  if (e.offsets.size() < 2 || e.offsets.back() != e.coordinates.rows() ||
      tau.size() != static_cast<std::size_t>(e.coordinates.rows()) || ev.size() != static_cast<std::size_t>(e.coordinates.cols()))
    r.fail("inconsistent sizes");
  for (std::size_t k = 1; k < e.offsets.size(); ++k)
    if (e.offsets[k] < e.offsets[k - 1]) r.fail("offsets not increasing");
  return fuzzy_correspondence(std::move(e), Eigen::Map<const Eigen::VectorXf>(tau.data(), static_cast<index_t>(tau.size())),
                              cutoff);
}

}  // namespace shapestruct
