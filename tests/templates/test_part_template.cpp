// SPDX-License-Identifier: MIT
#include <doctest/doctest.h>

#include <filesystem>

#include <Eigen/Geometry>

#include "shapestruct/io/json.hpp"
#include "shapestruct/templates/part_template.hpp"

using namespace shapestruct;

namespace {
part_template two_boxes() {
  part_template t;
  t.id = "demo";
  part_box a;
  a.name = "seat";
  a.center = {0, 0.1, 0};
  a.size = {0.4, 0.05, 0.4};
  a.feature_mean = Eigen::VectorXd::Constant(6, 0.3);
  a.feature_sigma = Eigen::VectorXd::Constant(6, 0.1);
  a.must_exist = true;
  part_box b = a;
  b.name = "back \"tall\"";
  b.label = 1;
  b.center = {0, 0.4, -0.2};
  b.axes = Eigen::AngleAxisd(0.3, Eigen::Vector3d::UnitY()).toRotationMatrix();
  b.must_exist = false;
  t.parts = {a, b};
  return t;
}
}  // namespace

TEST_CASE("json parses, writes and round-trips") {
  const auto v = parse_json(R"({"a": [1, 2.5, -3e2], "b": {"c": "x\"y\u00e9"}, "d": true, "e": null})");
  CHECK(v.find("a")->as_array()[2].as_number() == -300);
  CHECK(v.find("b")->find("c")->as_string() == "x\"y\xc3\xa9");
  const auto again = parse_json(to_json_string(v));
  CHECK(to_json_string(again, 0) == to_json_string(v, 0));
  const double tricky = 0.1 + 0.2;
  CHECK(parse_json(to_json_string(json_value(tricky))).as_number() == tricky);
}

TEST_CASE("json errors carry line and column") {
  try {
    (void)parse_json("{\n  \"a\": [1, 2,\n  ]\n}", "t.json");
    FAIL("expected throw");
  } catch (const io_error& e) {
    CHECK(e.line() == 3);
    CHECK(std::string(e.what()).find("t.json:3: column 3") != std::string::npos);
  }
  CHECK_THROWS_AS(parse_json("{\"a\": 1, \"a\": 2}"), io_error);
  CHECK_THROWS_AS(parse_json("[1, 2"), io_error);
  CHECK_THROWS_AS(parse_json("01"), io_error);
  CHECK_THROWS_AS(parse_json("\"abc"), io_error);
  CHECK_THROWS_AS(read_json("/nonexistent/x.json"), io_error);
}

TEST_CASE("part_template JSON round trip is exact") {
  const auto t = two_boxes();
  const auto dir = std::filesystem::temp_directory_path() / "shapestruct_tpl_test";
  std::filesystem::create_directories(dir);
  const auto path = (dir / "t.json").string();
  write_templates(path, {t, t});
  const auto back = read_templates(path);
  REQUIRE(back.size() == 2);
  const auto& r = back[1];
  CHECK(r.id == t.id);
  REQUIRE(r.parts.size() == 2);
  for (std::size_t i = 0; i < 2; ++i) {
    CHECK(r.parts[i].name == t.parts[i].name);
    CHECK(r.parts[i].label == t.parts[i].label);
    CHECK(r.parts[i].center == t.parts[i].center);
    CHECK(r.parts[i].axes == t.parts[i].axes);
    CHECK(r.parts[i].size == t.parts[i].size);
    CHECK(r.parts[i].feature_mean == t.parts[i].feature_mean);
    CHECK(r.parts[i].must_exist == t.parts[i].must_exist);
  }
  std::filesystem::remove_all(dir);
}

TEST_CASE("part_template bad input: no parts, inconsistent dimensions, bad numbers") {
  auto t = two_boxes();
  t.parts.clear();
  CHECK_THROWS_AS(validate_template(t), invalid_input);
  try {
    (void)template_from_json(parse_json(R"({"id": "x", "parts": []})"), "x.json");
    FAIL("expected throw");
  } catch (const invalid_input& e) {
    CHECK(e.reason() == input_error::empty);
    CHECK(std::string(e.what()).find("x.json") != std::string::npos);
  }
  t = two_boxes();
  t.parts[1].feature_mean = Eigen::VectorXd::Zero(4);
  try {
    validate_template(t);
    FAIL("expected throw");
  } catch (const invalid_input& e) {
    CHECK(e.reason() == input_error::size_mismatch);
    CHECK(e.element() == 1);
  }
  t = two_boxes();
  t.parts[0].size[1] = -1;
  CHECK_THROWS_AS(validate_template(t), invalid_input);
  t = two_boxes();
  t.parts[0].center[0] = std::nan("");
  CHECK_THROWS_AS(validate_template(t), invalid_input);
  t = two_boxes();
  t.parts[0].axes(0, 0) = 2;
  CHECK_THROWS_AS(validate_template(t), invalid_input);
  CHECK_THROWS_AS(template_from_json(parse_json(R"({"parts": [{"center": [0, 0], "size": [1, 1, 1]}]})")), io_error);
  CHECK_THROWS_AS(template_from_json(parse_json(R"({"parts": [{"size": [1, 1, 1]}]})")), io_error);
  CHECK_THROWS_AS(template_from_json(parse_json(R"([1, 2])")), io_error);
}

TEST_CASE("part_template JSON: axes written to four decimals are snapped, axes far from orthonormal are rejected") {
  // A box turned 45 degrees about the up axis, as a user types it.
  const auto t = template_from_json(parse_json(
      R"({"parts": [{"center": [0, 0, 0], "size": [1, 1, 1],
                     "axes": [[0.7071, 0, 0.7071], [0, 1, 0], [-0.7071, 0, 0.7071]]}]})"));
  const Eigen::Matrix3d& a = t.parts[0].axes;
  CHECK((a * a.transpose()).isIdentity(1e-12));
  CHECK(a(0, 0) == doctest::Approx(std::sqrt(0.5)).epsilon(1e-9));
  CHECK(a(2, 0) == doctest::Approx(-std::sqrt(0.5)).epsilon(1e-9));
  CHECK_THROWS_AS(template_from_json(parse_json(
                      R"({"parts": [{"center": [0, 0, 0], "size": [1, 1, 1],
                                     "axes": [[0.8, 0, 0.7], [0, 1, 0], [-0.7, 0, 0.7]]}]})")),
                  invalid_input);
}
