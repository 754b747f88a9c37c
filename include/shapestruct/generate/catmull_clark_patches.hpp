// SPDX-License-Identifier: MIT
// catmull_clark_patches: Catmull-Clark subdivision of a closed quad cage that keeps, for every cage quad,
// the regular grid of fine vertices it becomes (the parameterisation the creature ground truth lives on).
#pragma once

#include <algorithm>
#include <array>
#include <cstdint>
#include <string>
#include <unordered_map>
#include <vector>

#include <Eigen/Core>

#include "shapestruct/core/errors.hpp"
#include "shapestruct/core/types.hpp"

namespace shapestruct {

/// The result of subdividing a quad cage `levels` times: cage quad q becomes a (2^levels + 1)^2 grid of
/// vertex ids `grid[q]` (row-major, index j * (size + 1) + i, i along corner 0 -> 1, j along 0 -> 3) into
/// `positions`. Grids of neighbouring quads share the vertices of their common edge.
struct quad_patch_grids {
  int size = 1;                                   ///< 2^levels cells per patch side
  std::vector<Eigen::Vector3d> positions;         ///< all fine vertices (unreferenced cage vertices kept)
  std::vector<std::vector<index_t>> grid;         ///< per cage quad; empty for quads not subdivided

  /// Bilinear interpolation of the fine grid of quad `q` at (u, v) in [0, 1]^2: a continuous surface,
  /// because neighbouring grids agree (linearly) along shared edges. O(1).
  [[nodiscard]] Eigen::Vector3d evaluate(index_t q, double u, double v) const {
    const auto& g = grid[static_cast<std::size_t>(q)];
    const double x = std::clamp(u, 0.0, 1.0) * size, y = std::clamp(v, 0.0, 1.0) * size;
    const int i = std::min(static_cast<int>(x), size - 1), j = std::min(static_cast<int>(y), size - 1);
    const double a = x - i, b = y - j;
    const auto at = [&](int ii, int jj) -> const Eigen::Vector3d& {
      return positions[static_cast<std::size_t>(g[static_cast<std::size_t>(jj * (size + 1) + ii)])];
    };
    return (1 - a) * (1 - b) * at(i, j) + a * (1 - b) * at(i + 1, j) + a * b * at(i + 1, j + 1) +
           (1 - a) * b * at(i, j + 1);
  }
};

/// Catmull-Clark subdivision of the quads `quads[q]` for the q with `active[q]` (a closed manifold quad
/// mesh over `cage`, counter-clockwise from outside), `levels` times.
/// \param cage   cage vertex positions (vertices no active quad uses are carried along untouched)
/// \param quads  cage quads (corner ids into cage)
/// \param active which quads belong to the surface (size quads.size())
/// \param levels number of subdivisions, in [0, 6]
/// \throws invalid_input (bad_parameter) for levels outside [0, 6]; (non_manifold, edge's first vertex) if
///         an edge of the active quads does not have exactly two quads.
/// \returns per-quad fine grids. Cost O(#active quads * 4^levels).
inline quad_patch_grids catmull_clark_patches(const std::vector<Eigen::Vector3d>& cage,
                                              const std::vector<std::array<index_t, 4>>& quads,
                                              const std::vector<bool>& active, int levels) {
  if (levels < 0 || levels > 6)
    throw invalid_input(input_error::bad_parameter, no_index, "catmull_clark_patches: levels must be in [0, 6]");
  quad_patch_grids out;
  out.positions = cage;
  out.grid.assign(quads.size(), {});
  for (std::size_t q = 0; q < quads.size(); ++q)
    if (active[q]) out.grid[q] = {quads[q][0], quads[q][1], quads[q][3], quads[q][2]};
  const auto key = [](index_t a, index_t b) {
    if (a > b) std::swap(a, b);
    return (static_cast<std::uint64_t>(a) << 32) | static_cast<std::uint64_t>(b);
  };
  for (int level = 0; level < levels; ++level) {
    const int g = out.size, g2 = 2 * g;
    const auto& P = out.positions;
    const std::size_t nv = P.size();
    std::vector<Eigen::Vector3d> next(P);
    std::vector<Eigen::Vector3d> face_sum(nv, Eigen::Vector3d::Zero()), edge_sum(nv, Eigen::Vector3d::Zero());
    std::vector<int> valence(nv, 0);
    struct edge_rec {
      index_t a, b, id;
      Eigen::Vector3d face_points = Eigen::Vector3d::Zero();
      int faces = 0;
    };
    std::unordered_map<std::uint64_t, std::size_t> edge_index;
    std::vector<edge_rec> edges;
    std::vector<std::vector<index_t>> new_grid(quads.size());
    // Pass 1: face points, edges (with their adjacent face points).
    for (std::size_t q = 0; q < quads.size(); ++q) {
      if (!active[q]) continue;
      const auto& G = out.grid[q];
      auto& N = new_grid[q];
      N.assign(static_cast<std::size_t>((g2 + 1) * (g2 + 1)), no_index);
      const auto old = [&](int i, int j) { return G[static_cast<std::size_t>(j * (g + 1) + i)]; };
      const auto put = [&](int i, int j, index_t id) { N[static_cast<std::size_t>(j * (g2 + 1) + i)] = id; };
      for (int j = 0; j <= g; ++j)
        for (int i = 0; i <= g; ++i) put(2 * i, 2 * j, old(i, j));
      for (int j = 0; j < g; ++j)
        for (int i = 0; i < g; ++i) {
          const index_t c[4] = {old(i, j), old(i + 1, j), old(i + 1, j + 1), old(i, j + 1)};
          Eigen::Vector3d fp = Eigen::Vector3d::Zero();
          for (const index_t v : c) fp += P[static_cast<std::size_t>(v)];
          fp *= 0.25;
          const index_t fid = static_cast<index_t>(next.size());
          next.push_back(fp);
          put(2 * i + 1, 2 * j + 1, fid);
          for (const index_t v : c) {
            face_sum[static_cast<std::size_t>(v)] += fp;
          }
          // The four cell edges and the fine-grid slot of their edge point.
          const int slots[4][2] = {{2 * i + 1, 2 * j}, {2 * i + 2, 2 * j + 1}, {2 * i + 1, 2 * j + 2}, {2 * i, 2 * j + 1}};
          for (int e = 0; e < 4; ++e) {
            const index_t a = c[e], b = c[(e + 1) % 4];
            auto [it, fresh] = edge_index.emplace(key(a, b), edges.size());
            if (fresh) edges.push_back({a, b, no_index});
            edge_rec& er = edges[it->second];
            er.face_points += fp;
            ++er.faces;
            put(slots[e][0], slots[e][1], static_cast<index_t>(it->second));  // edge number for now
          }
        }
    }
    // Pass 2: edge points, and the edge midpoints each vertex averages.
    for (auto& e : edges) {
      if (e.faces != 2)
        throw invalid_input(input_error::non_manifold, e.a,
                            "catmull_clark_patches: the cage edge at vertex " + std::to_string(e.a) + " has " +
                                std::to_string(e.faces) + " quads; the cage must be a closed manifold");
      const Eigen::Vector3d pa = P[static_cast<std::size_t>(e.a)], pb = P[static_cast<std::size_t>(e.b)];
      e.id = static_cast<index_t>(next.size());
      next.push_back(0.25 * (pa + pb + e.face_points));
      const Eigen::Vector3d mid = 0.5 * (pa + pb);
      edge_sum[static_cast<std::size_t>(e.a)] += mid;
      edge_sum[static_cast<std::size_t>(e.b)] += mid;
      ++valence[static_cast<std::size_t>(e.a)];
      ++valence[static_cast<std::size_t>(e.b)];
    }
    // Pass 3: replace edge numbers by edge-point ids (odd-even / even-odd slots).
    for (std::size_t q = 0; q < quads.size(); ++q) {
      if (!active[q]) continue;
      auto& N = new_grid[q];
      for (int j = 0; j <= g2; ++j)
        for (int i = 0; i <= g2; ++i)
          if ((i + j) % 2 == 1) {
            auto& x = N[static_cast<std::size_t>(j * (g2 + 1) + i)];
            x = edges[static_cast<std::size_t>(x)].id;
          }
    }
    // Pass 4: vertex points, (F + 2R + (n - 3) P) / n with F, R the averages of adjacent face points and
    // edge midpoints (on a closed manifold a vertex has as many faces as edges).
    for (std::size_t v = 0; v < nv; ++v) {
      const int n = valence[v];
      if (n == 0) continue;
      next[v] = (face_sum[v] / n + 2.0 * edge_sum[v] / n + (n - 3.0) * P[v]) / n;
    }
    out.positions.swap(next);
    out.grid.swap(new_grid);
    out.size = g2;
  }
  return out;
}

}  // namespace shapestruct
