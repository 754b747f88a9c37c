// SPDX-License-Identifier: MIT
// Tests of make_shape_record, the record cache files and make_collection_records' handling of bad files.
#include <doctest/doctest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>

#include "shapestruct/collection/collection_files.hpp"
#include "shapestruct/collection/make_shape_record.hpp"
#include "shapestruct/collection/spherical_harmonic_descriptor.hpp"
#include "shapestruct/fuzzy/collection_records.hpp"
#include "shapestruct/fuzzy/fuzzy_files.hpp"
#include "shapestruct/generate/primitive_meshes.hpp"
#include "shapestruct/geometry/dijkstra_geodesics.hpp"
#include "shapestruct/io/write_mesh.hpp"
#include "support/thread_exchange.hpp"

namespace ss = shapestruct;
namespace fs = std::filesystem;

namespace {
const ss::spherical_harmonic_descriptor describe{{.grid = 16, .radii = 4, .bands = 4}};

/// One sphere whose antipodal vertices are merged into one: a closed surface pinched at a vertex (as SCAPE's
/// template at vertex 419), a sphere again once the vertex is split.
ss::triangle_mesh<double> pinched_sphere() {
  auto m = ss::make_icosphere<double>(2);
  ss::index_t far = 0;
  (m.V.rowwise() - m.V.row(0)).rowwise().squaredNorm().maxCoeff(&far);
  m.V.row(far) = m.V.row(0) + Eigen::RowVector3d(0, 0, 1e-3);  // an antipode pulled to the pole...
  for (ss::index_t f = 0; f < m.F.rows(); ++f)
    for (int c = 0; c < 3; ++c)
      if (m.F(f, c) == far) m.F(f, c) = 0;  // ... and merged with it
  // vertex `far` is now unreferenced: move the last vertex into its slot to keep the mesh free of strays
  const ss::index_t last = m.V.rows() - 1;
  m.V.row(far) = m.V.row(last);
  for (ss::index_t f = 0; f < m.F.rows(); ++f)
    for (int c = 0; c < 3; ++c)
      if (m.F(f, c) == last) m.F(f, c) = far;
  m.V.conservativeResize(last, 3);
  return m;
}
}  // namespace

TEST_CASE("shape record of a sphere: geodesic samples at vertices, nearest samples, sample geodesics") {
  const auto m = ss::make_icosphere<double>(3);
  const auto r = ss::make_shape_record(m, "sphere", describe, {.samples = 32, .surface_points = 256});
  CHECK(r.closed_genus0);
  CHECK(r.sample_count() == 32);
  CHECK(r.surface_points.rows() == 256);
  CHECK(r.vertex_sample.size() == std::size_t(m.V.rows()));
  CHECK(r.area == doctest::Approx(4 * M_PI).epsilon(0.02));
  CHECK(r.descriptor.size() == 16);
  const ss::dijkstra_geodesics<double> geo(m.V, m.F);
  for (ss::index_t i = 0; i < 32; ++i) {
    const ss::index_t v = r.sample_vertex[std::size_t(i)];
    CHECK((r.samples.row(i) - m.V.row(v)).norm() == 0.0);
    CHECK(r.vertex_sample[std::size_t(v)] == i);  // a sample is its own nearest sample
    const auto d = geo.distances_from(v);
    for (ss::index_t j = 0; j < 32; ++j) CHECK(double(r.sample_geodesics(i, j)) == doctest::Approx(d[r.sample_vertex[std::size_t(j)]]).epsilon(1e-5));
  }
  // Every vertex's nearest sample is geodesically nearest.
  const auto D = geo.distance_table(std::span<const ss::index_t>(r.sample_vertex), 1);
  for (ss::index_t v = 0; v < m.V.rows(); v += 17) CHECK(D(v, r.vertex_sample[std::size_t(v)]) == doctest::Approx(D.row(v).minCoeff()));
  // Diam: the mean distance between samples of the unit sphere is about 4/3.
  CHECK(r.diameter == doctest::Approx(4.0 / 3.0).epsilon(0.1));
}

TEST_CASE("shape record of a soup: Euclidean samples on the surface, a pinched sphere is still intrinsic") {
  const auto box = ss::make_box<double>(1.0, 0.5, 0.25);
  const auto r = ss::make_shape_record(box, "box", describe, {.samples = 20, .surface_points = 200, .metric = ss::sample_metric::euclidean});
  CHECK(r.sample_vertex[0] == ss::no_index);
  CHECK(r.sample_geodesics.size() == 0);
  CHECK(r.vertex_sample.size() == std::size_t(box.V.rows()));
  const auto p = ss::make_shape_record(pinched_sphere(), "pinched", describe, {.samples = 16, .surface_points = 64});
  CHECK(p.closed_genus0);
  CHECK(p.sample_vertex[0] != ss::no_index);
  const auto torus = ss::make_torus<double>(1.0, 0.3, 24, 12);
  const auto t = ss::make_shape_record(torus, "torus", describe, {.samples = 16, .surface_points = 64});
  CHECK_FALSE(t.closed_genus0);
  CHECK(t.sample_vertex[0] == ss::no_index);  // automatic: Euclidean off genus 0
}

TEST_CASE("shape record bad input is invalid_input naming the shape") {
  const auto sphere = ss::make_icosphere<double>(1);  // 42 vertices
  CHECK_THROWS_AS((void)ss::make_shape_record(sphere, "s", describe, {.samples = 0}), ss::invalid_input);
  CHECK_THROWS_AS((void)ss::make_shape_record(sphere, "s", describe, {.samples = 64, .surface_points = 32}), ss::invalid_input);
  try {
    (void)ss::make_shape_record(sphere, "tiny", describe, {.samples = 50, .surface_points = 64});
    FAIL("fewer vertices than samples must throw");
  } catch (const ss::invalid_input& e) {
    CHECK(e.reason() == ss::input_error::empty);
    CHECK(std::string(e.what()).find("tiny") != std::string::npos);
    CHECK(std::string(e.what()).find("--samples") != std::string::npos);
  }
  const auto torus = ss::make_torus<double>(1.0, 0.3, 12, 8);
  CHECK_THROWS_AS((void)ss::make_shape_record(torus, "t", describe, {.samples = 8, .surface_points = 64, .metric = ss::sample_metric::geodesic}),
                  ss::invalid_input);
  auto nan = sphere;
  nan.V(3, 1) = std::numeric_limits<double>::quiet_NaN();
  CHECK_THROWS_AS((void)ss::make_shape_record(nan, "n", describe, {.samples = 8, .surface_points = 64}), ss::invalid_input);
}

TEST_CASE("record and fuzzy files round-trip exactly, damaged files are io_error") {
  const auto dir = fs::temp_directory_path() / "shapestruct_test_record_files";
  fs::remove_all(dir);
  fs::create_directories(dir);
  const auto r = ss::make_shape_record(ss::make_icosphere<double>(2), "sphere", describe, {.samples = 16, .surface_points = 64});
  ss::write_shape_record(dir / "sphere.rec", r);
  const auto back = ss::read_shape_record(dir / "sphere.rec");
  CHECK(back.name == r.name);
  CHECK(back.samples == r.samples);
  CHECK(back.sample_vertex == r.sample_vertex);
  CHECK(back.vertex_sample == r.vertex_sample);
  CHECK(back.surface_points == r.surface_points);
  CHECK(back.sample_geodesics == r.sample_geodesics);
  CHECK(back.descriptor == r.descriptor);
  CHECK(back.diameter == r.diameter);
  CHECK(back.closed_genus0 == r.closed_genus0);
  {
    std::ofstream cut(dir / "cut.rec", std::ios::binary);
    const std::string bytes = ss::io_detail::read_file_bytes(dir / "sphere.rec");
    cut << bytes.substr(0, bytes.size() / 2);
  }
  CHECK_THROWS_AS((void)ss::read_shape_record(dir / "cut.rec"), ss::io_error);
  CHECK_THROWS_AS((void)ss::read_pair_alignment(dir / "sphere.rec"), ss::io_error);  // a record is no alignment
  CHECK_THROWS_AS((void)ss::read_fuzzy_correspondence(dir / "missing.bin"), ss::io_error);
  fs::remove_all(dir);
}

TEST_CASE("collection records: unreadable, empty and non-finite files are skipped with the reason, the rest kept") {
  const auto dir = fs::temp_directory_path() / "shapestruct_test_collection_records";
  fs::remove_all(dir);
  fs::create_directories(dir);
  ss::write_mesh(dir / "a.off", ss::make_icosphere<double>(2));
  ss::write_mesh(dir / "b.off", ss::make_box<double>(1, 1, 1));
  std::ofstream(dir / "empty.off") << "OFF\n0 0 0\n";
  std::ofstream(dir / "nan.off") << "OFF\n3 1 0\n0 0 0\n1 0 nan\n0 1 0\n3 0 1 2\n";
  std::ofstream(dir / "garbage.off") << "this is not a mesh\n";
  const std::vector<fs::path> files{dir / "a.off", dir / "empty.off", dir / "b.off", dir / "nan.off", dir / "garbage.off",
                                    dir / "missing.off"};
  ss::collection_records_options o;
  o.record.samples = 8;
  o.record.surface_points = 64;
  o.cache_folder = dir / "records";
  const auto c = ss::make_collection_records(files, o);
  REQUIRE(c.records.size() == 2);
  CHECK(c.records[0].name == "a");
  CHECK(c.records[1].name == "b");
  REQUIRE(c.skipped.size() == 4);
  for (const auto& s : c.skipped) CHECK_FALSE(s.reason.empty());
  CHECK(fs::exists(dir / "records/a.rec"));
  // A second run reads the cached records: identical.
  const auto again = ss::make_collection_records(files, o);
  CHECK(again.records[0].samples == c.records[0].samples);
  fs::remove_all(dir);
}

TEST_CASE("collection records: three processes sharing the files give one process's records and skips") {
  const auto dir = fs::temp_directory_path() / "shapestruct_test_collection_records_shared";
  fs::remove_all(dir);
  fs::create_directories(dir);
  ss::write_mesh(dir / "a.off", ss::make_icosphere<double>(2));
  ss::write_mesh(dir / "b.off", ss::make_box<double>(1, 1, 1));
  ss::write_mesh(dir / "c.off", ss::make_icosphere<double>(1));
  std::ofstream(dir / "nan.off") << "OFF\n3 1 0\n0 0 0\n1 0 nan\n0 1 0\n3 0 1 2\n";
  const std::vector<fs::path> files{dir / "a.off", dir / "nan.off", dir / "b.off", dir / "c.off", dir / "missing.off"};
  ss::collection_records_options o;
  o.record.samples = 8;
  o.record.surface_points = 64;
  const auto alone = ss::make_collection_records(files, o);
  o.cache_folder = dir / "records";
  const auto parts = ss::test::run_parts(3, [&](const ss::work_share& share) {
    auto own = o;
    own.share = share;
    return ss::make_collection_records(files, own);
  });
  for (const auto& c : parts) {
    REQUIRE(c.records.size() == alone.records.size());
    for (std::size_t k = 0; k < c.records.size(); ++k) {
      CHECK(c.records[k].name == alone.records[k].name);
      CHECK(c.records[k].samples == alone.records[k].samples);
      CHECK(c.records[k].descriptor == alone.records[k].descriptor);
    }
    REQUIRE(c.skipped.size() == 2);
    CHECK(c.skipped[0].file == files[1]);
    CHECK(c.skipped[1].file == files[4]);
    CHECK(c.skipped[0].reason == alone.skipped[0].reason);
  }
  // Sharing needs the folder the parts exchange records through.
  o.cache_folder.clear();
  ss::test::thread_exchange ex(2);
  o.share = ex.share(0);
  CHECK_THROWS_AS((void)ss::make_collection_records(files, o), ss::invalid_input);
  fs::remove_all(dir);
}
