// SPDX-License-Identifier: MIT
// A minimal OFF reader for the geometry data tests and benchmarks only (polygons fan-triangulated; no colours,
// no error positions). The library's reader is shapestruct/io/read_mesh.hpp; this one keeps the geometry
// tests independent of it.
#pragma once

#include <array>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "shapestruct/core/triangle_mesh.hpp"

namespace shapestruct::test {

inline triangle_mesh<double> read_off_minimal(const std::filesystem::path& path) {
  std::ifstream in(path);
  if (!in) throw std::runtime_error("read_off_minimal: cannot open " + path.string());
  std::stringstream text;
  for (std::string line; std::getline(in, line);) {
    const auto hash = line.find('#');
    text << (hash == std::string::npos ? line : line.substr(0, hash)) << '\n';
  }
  std::string magic;
  long nv = 0, nf = 0, ne = 0;
  if (!(text >> magic) || magic != "OFF" || !(text >> nv >> nf >> ne) || nv <= 0 || nf <= 0)
    throw std::runtime_error("read_off_minimal: bad header in " + path.string());
  triangle_mesh<double> m;
  m.V.resize(nv, 3);
  for (long i = 0; i < nv; ++i)
    if (!(text >> m.V(i, 0) >> m.V(i, 1) >> m.V(i, 2)))
      throw std::runtime_error("read_off_minimal: truncated vertices in " + path.string());
  std::vector<std::array<index_t, 3>> tris;
  tris.reserve(static_cast<std::size_t>(nf));
  for (long f = 0; f < nf; ++f) {
    int k = 0;
    if (!(text >> k) || k < 3) throw std::runtime_error("read_off_minimal: bad face in " + path.string());
    std::vector<index_t> poly(static_cast<std::size_t>(k));
    for (auto& v : poly)
      if (!(text >> v)) throw std::runtime_error("read_off_minimal: truncated faces in " + path.string());
    for (int t = 1; t + 1 < k; ++t) tris.push_back({poly[0], poly[std::size_t(t)], poly[std::size_t(t + 1)]});
    std::string rest;  // optional per-face colour
    std::getline(text, rest);
  }
  m.F.resize(static_cast<index_t>(tris.size()), 3);
  for (std::size_t f = 0; f < tris.size(); ++f) m.F.row(index_t(f)) << tris[f][0], tris[f][1], tris[f][2];
  return m;
}

}  // namespace shapestruct::test
