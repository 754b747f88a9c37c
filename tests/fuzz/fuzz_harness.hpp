// SPDX-License-Identifier: MIT
// Shared body of the libFuzzer harnesses: io_error is the expected outcome for bad input; anything else
// (another exception, a crash, a sanitizer report, an inconsistent result) is a finding.
#pragma once

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string_view>

#include "shapestruct/core/errors.hpp"
#include "shapestruct/io/mesh_file.hpp"

namespace shapestruct::fuzz {

/// Aborts (a finding) unless a successfully read mesh is self-consistent: finite coordinates, indices in
/// range, one face_polygon entry per triangle, colours and groups sized to match.
inline void check_result(const mesh_file<double>& m) {
  const index_t nv = m.mesh.V.rows(), nf = m.mesh.F.rows();
  if (!m.mesh.V.allFinite()) std::abort();
  for (index_t f = 0; f < nf; ++f)
    for (int c = 0; c < 3; ++c)
      if (m.mesh.F(f, c) < 0 || m.mesh.F(f, c) >= nv) std::abort();
  if (static_cast<index_t>(m.face_polygon.size()) != nf) std::abort();
  if (m.vertex_colors.rows() != 0 && m.vertex_colors.rows() != nv) std::abort();
  if (!m.face_group.empty()) {
    if (static_cast<index_t>(m.face_group.size()) != nf) std::abort();
    for (index_t g : m.face_group)
      if (g < 0 || g >= static_cast<index_t>(m.group_names.size())) std::abort();
  }
}

template <class Reader>
int run(Reader reader, const std::uint8_t* data, std::size_t size) {
  const std::string_view bytes(reinterpret_cast<const char*>(data), size);
  try {
    check_result(reader(bytes, "fuzz-input"));
  } catch (const io_error&) {
    // expected for malformed input
  }
  return 0;
}

}  // namespace shapestruct::fuzz
