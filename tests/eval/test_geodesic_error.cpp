// SPDX-License-Identifier: MIT
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <vector>

#include <doctest/doctest.h>

#include "shapestruct/eval/geodesic_error.hpp"
#include "shapestruct/generate/primitive_meshes.hpp"
#include "shapestruct/geometry/mesh_measures.hpp"
#include "shapestruct/io/bim_benchmark_files.hpp"

using namespace shapestruct;

TEST_CASE("geodesic_errors: zero for the truth, the normalised Dijkstra distance otherwise") {
  const auto m = make_icosphere<double>(3);
  const dijkstra_geodesics<double> geo(m.V, m.F);
  const std::vector<index_t> truth = {0, 5, 17, 40};
  const std::vector<index_t> pred = {0, 5, 18, 100};
  const double norm = 2 * std::sqrt(total_area<double>(m.V, m.F));
  const auto e = geodesic_errors(geo, std::span<const index_t>(pred), std::span<const index_t>(truth), norm);
  CHECK(e[0] == 0);
  CHECK(e[1] == 0);
  CHECK(e[2] == doctest::Approx(geo.distances_from(17)[18] / norm));
  CHECK(e[3] == doctest::Approx(geo.distances_from(40)[100] / norm));
  const auto s = summarize_errors(std::span<const double>(e));
  CHECK(s.within_005 >= 0.5);
  CHECK(s.mean == doctest::Approx((e[2] + e[3]) / 4));
  CHECK_THROWS_AS((void)geodesic_errors(geo, std::span<const index_t>(pred), std::span<const index_t>(truth.data(), 2), norm),
                  invalid_input);
  CHECK_THROWS_AS((void)geodesic_errors(geo, std::span<const index_t>(pred), std::span<const index_t>(truth), 0.0),
                  invalid_input);
}

TEST_CASE("symmetric_vertices recovers a mirror symmetry from symmetric feature points") {
  const auto m = make_icosphere<double>(3);
  const dijkstra_geodesics<double> geo(m.V, m.F);
  // mirror x -> -x: find each feature's mirror vertex
  auto mirror = [&](index_t v) {
    index_t best = 0;
    double bd = 1e300;
    for (index_t u = 0; u < m.V.rows(); ++u) {
      const double d = (m.V.row(u) - Eigen::RowVector3d(-m.V(v, 0), m.V(v, 1), m.V(v, 2))).norm();
      if (d < bd) {
        bd = d;
        best = u;
      }
    }
    return best;
  };
  std::vector<index_t> feats, perm;
  for (index_t v : {1, 7, 30, 77, 200, 333}) {
    if (std::abs(m.V(v, 0)) < 0.2) continue;
    feats.push_back(v);
    feats.push_back(mirror(v));
    perm.push_back(static_cast<index_t>(feats.size() - 1));
    perm.push_back(static_cast<index_t>(feats.size() - 2));
  }
  REQUIRE(feats.size() >= 6);
  const std::vector<index_t> q = {12, 55, 140};
  const auto s = symmetric_vertices(geo, std::span<const index_t>(feats), std::span<const index_t>(perm), std::span<const index_t>(q));
  for (std::size_t k = 0; k < q.size(); ++k) CHECK((m.V.row(s[k]) - m.V.row(mirror(q[k]))).norm() < 0.2);
}

TEST_CASE("BIM benchmark file readers") {
  const auto dir = std::filesystem::temp_directory_path() / "shapestruct_bim_files_test";
  std::filesystem::create_directories(dir);
  {
    std::ofstream(dir / "a.query") << "SCAPE\n1\n0\nSCAPE\n1\n37\nTOSCA\ncat\n0\nTOSCA\ncat\n6\n";
    std::ofstream(dir / "a.vts") << "  1836     0.17     0.11      -0.97\n2270 0 0 0\n";
    std::ofstream(dir / "a.sym.info") << "0 1\n2 3 4\n";
    std::ofstream(dir / "r.txt") << "Stats:\n\tAverage\t[0.5]\n\tPerSampleErrors\t[0.1, 0.2, 0.3]\n\tTime\t[110]\n"
                                    "StatsWithFlip:\n\tAverage\t[0.25]\n\tFlipped\t[true]\n\tPerSampleErrors\t[0.05]\n";
    std::ofstream(dir / "bad.query") << "SCAPE\n1\n";
    std::ofstream(dir / "bad.vts") << "x 1 2 3\n";
  }
  const auto pairs = read_bim_query((dir / "a.query").string());
  REQUIRE(pairs.size() == 2);
  CHECK(pairs[0].source.name() == "mesh000");
  CHECK(pairs[0].target.relative_path() == "SCAPE/Meshes/mesh037.off");
  CHECK(pairs[1].target.name() == "cat6");
  const bim_mesh_ref shrec{"SHREC", "3", "7"};
  CHECK(shrec.name() == "47");
  CHECK(shrec.relative_path() == "watertight_shrec07/Meshes/47.off");
  const auto v = read_bim_feature_vertices((dir / "a.vts").string());
  CHECK(v == std::vector<index_t>{1836, 2270});
  const auto p = read_bim_symmetry((dir / "a.sym.info").string(), 6);
  CHECK(p == std::vector<index_t>{1, 0, 3, 4, 2, 5});
  const auto r = read_bim_result((dir / "r.txt").string());
  CHECK(r.at("Stats").average == doctest::Approx(0.5));
  CHECK(r.at("Stats").per_sample_errors.size() == 3);
  CHECK(r.at("Stats").time == doctest::Approx(110));
  CHECK(r.at("StatsWithFlip").flipped);
  CHECK_THROWS_AS((void)read_bim_query((dir / "bad.query").string()), io_error);
  CHECK_THROWS_AS((void)read_bim_feature_vertices((dir / "bad.vts").string()), io_error);
  CHECK_THROWS_AS((void)read_bim_symmetry((dir / "a.sym.info").string(), 3), io_error);
  CHECK_THROWS_AS((void)read_bim_query((dir / "missing.query").string()), io_error);
  std::filesystem::remove_all(dir);
}

TEST_CASE("read_bim_feature_names: names by index, trimmed and lower-cased, blank lines skipped") {
  const auto dir = std::filesystem::temp_directory_path() / "shapestruct_bim_names_test";
  std::filesystem::create_directories(dir);
  {
    // TOSCA's .info files have blank lines and mixed case; the index before the colon, not the line, counts.
    std::ofstream(dir / "a.info") << "0: Nose\n\n2:  Left Hand \r\n1:right hand\n";
    std::ofstream(dir / "no_colon.info") << "0: nose\n1 left hand\n";
    std::ofstream(dir / "negative.info") << "-1: nose\n";
    std::ofstream(dir / "twice.info") << "0: nose\n0: chin\n";
  }
  const auto names = read_bim_feature_names((dir / "a.info").string());
  CHECK(names == std::vector<std::string>{"nose", "right hand", "left hand"});
  // Errors name the file and the line.
  const auto line_of = [&](const char* file) {
    try {
      (void)read_bim_feature_names((dir / file).string());
    } catch (const io_error& e) {
      return e.line();
    }
    return std::int64_t{-1};
  };
  CHECK(line_of("no_colon.info") == 2);
  CHECK(line_of("negative.info") == 1);
  CHECK(line_of("twice.info") == 2);
  CHECK_THROWS_AS((void)read_bim_feature_names((dir / "missing.info").string()), io_error);
  std::filesystem::remove_all(dir);
}

TEST_CASE("read_bim_feature_points and match_bim_features_by_name pair points across data sets by name") {
  namespace fs = std::filesystem;
  const auto root = fs::temp_directory_path() / "shapestruct_bim_points_test";
  fs::remove_all(root);
  fs::create_directories(root / "TOSCA/Corrs");
  fs::create_directories(root / "watertight_shrec07/Corrs");
  {
    // A TOSCA class: 3 points, a left-right symmetry (1 2); a SHREC'07 class without a .sym.info.
    std::ofstream(root / "TOSCA/Corrs/cat.pid") << "10 0 0 0\n20 0 0 0\n30 0 0 0\n";
    std::ofstream(root / "TOSCA/Corrs/cat.sym.info") << "1 2\n";
    std::ofstream(root / "TOSCA/Corrs/cat.info") << "0: Nose\n1: left paw\n2: right paw\n";
    std::ofstream(root / "watertight_shrec07/Corrs/385.vts") << "5 0.1 0.2 0.3\n6 0 0 0\n7 0 0 0\n";
    std::ofstream(root / "watertight_shrec07/Corrs/c20.info") << "0: right paw\n1: tail\n2: nose\n";
  }
  const bim_mesh_ref cat{"TOSCA", "cat", "0"}, fourleg{"SHREC", "20", "5"};  // SHREC'07 class 20, mesh 5 = 385
  const auto a = read_bim_feature_points(root, cat, true);
  const auto b = read_bim_feature_points(root, fourleg, true);
  CHECK(a.vertices == std::vector<index_t>{10, 20, 30});
  CHECK(a.symmetry == std::vector<index_t>{0, 2, 1});
  CHECK(b.vertices == std::vector<index_t>{5, 6, 7});
  CHECK(b.symmetry == std::vector<index_t>{0, 1, 2});  // no .sym.info: the identity
  CHECK(read_bim_feature_points(root, cat).names.empty());
  // cat -> 385: nose and right paw have partners, left paw and tail do not.
  const auto ab = match_bim_features_by_name(a, b);
  CHECK(ab.source == std::vector<index_t>{10, 30});
  CHECK(ab.target == std::vector<index_t>{7, 5});
  CHECK(ab.target_symmetric == std::vector<index_t>{7, 5});
  // 385 -> cat: the symmetric truth of "right paw" is the cat's left paw.
  const auto ba = match_bim_features_by_name(b, a);
  CHECK(ba.source == std::vector<index_t>{5, 7});
  CHECK(ba.target == std::vector<index_t>{30, 10});
  CHECK(ba.target_symmetric == std::vector<index_t>{20, 10});
  CHECK_THROWS_AS((void)read_bim_feature_points(root, bim_mesh_ref{"TOSCA", "dog", "0"}), io_error);
  fs::remove_all(root);
}
