// SPDX-License-Identifier: MIT
#include <doctest/doctest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>

#include <Eigen/Geometry>

#include "shapestruct/io/json_file.hpp"
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
  const auto v = parse_json_text(R"({"z": [1, 2.5, -3e2], "b": {"c": "x\"y\u00e9"}, "d": true, "e": null})");
  CHECK(v.at("z")[2].get<double>() == -300);
  CHECK(v.at("b").at("c").get<std::string>() == "x\"y\xc3\xa9");
  // Keys keep the file's order; arrays of scalars stay on one line; numbers in their shortest exact form.
  CHECK(format_json(v) == "{\n  \"z\": [1, 2.5, -300],\n  \"b\": {\n    \"c\": \"x\\\"y\xc3\xa9\"\n  },\n"
                          "  \"d\": true,\n  \"e\": null\n}");
  CHECK(format_json(v, 0) == "{\"z\":[1, 2.5, -300],\"b\":{\"c\":\"x\\\"y\xc3\xa9\"},\"d\":true,\"e\":null}");
  const auto again = parse_json_text(format_json(v));
  CHECK(format_json(again, 0) == format_json(v, 0));
  const double tricky = 0.1 + 0.2;
  CHECK(parse_json_text(format_json(nlohmann::ordered_json(tricky))).get<double>() == tricky);
  CHECK_THROWS_AS((void)format_json(nlohmann::ordered_json(std::nan(""))), std::invalid_argument);
}

TEST_CASE("json errors carry line and column, duplicate keys are refused") {
  try {
    (void)parse_json_text("{\n  \"a\": [1, 2,\n  ]\n}", "t.json");
    FAIL("expected throw");
  } catch (const io_error& e) {
    CHECK(e.reason() == file_error::syntax);
    CHECK(e.line() == 3);
    CHECK(std::string(e.what()).find("t.json:3: column 3") != std::string::npos);
  }
  try {
    (void)parse_json_text("{\"a\": 1,\n \"b\": {\"a\": 2},\n \"a\": 2}", "d.json");
    FAIL("expected throw");
  } catch (const io_error& e) {
    CHECK(e.line() == 3);
    CHECK(std::string(e.what()).find("d.json:3: column 2: duplicate key \"a\"") != std::string::npos);
  }
  CHECK_THROWS_AS(parse_json_text("{\"a\": 1, \"a\": 2}"), io_error);
  try {
    (void)parse_json_text("[1, 2", "e.json");
    FAIL("expected throw");
  } catch (const io_error& e) {
    CHECK(e.reason() == file_error::truncated);
    CHECK(std::string(e.what()).find("e.json:1: column 6") != std::string::npos);
  }
  CHECK_THROWS_AS(parse_json_text("01"), io_error);
  CHECK_THROWS_AS(parse_json_text("\"abc"), io_error);
  CHECK_THROWS_AS(parse_json_text("[1e999]"), io_error);
  CHECK_THROWS_AS(parse_json_text(std::string(300, '[') + std::string(300, ']')), io_error);
  CHECK_THROWS_AS(read_json_file("/nonexistent/x.json"), io_error);
  // Type errors name the key.
  const auto o = parse_json_text(R"({"mode": 3})");
  try {
    (void)json_required<std::string>(o, "mode", "m.json");
    FAIL("expected throw");
  } catch (const io_error& e) {
    CHECK(e.reason() == file_error::bad_value);
    CHECK(std::string(e.what()).find("m.json: \"mode\" must be a string") != std::string::npos);
  }
  CHECK(json_required<int>(o, "mode", "m.json") == 3);
  CHECK_THROWS_AS((void)json_required<double>(o, "missing", "m.json"), io_error);
}

TEST_CASE("template files: syntax errors, duplicate keys and wrong types are io_errors naming the file") {
  const auto dir = std::filesystem::temp_directory_path() / "shapestruct_tpl_errors_test";
  std::filesystem::create_directories(dir);
  const auto write = [&](const std::string& name, const std::string& text) {
    const auto path = (dir / name).string();
    std::ofstream(path) << text;
    return path;
  };
  const auto what_of = [](const std::string& path) {
    try {
      (void)read_templates(path);
    } catch (const io_error& e) {
      return std::string(e.what());
    }
    return std::string("no io_error");
  };
  const auto syntax = write("syntax.json", "{\"parts\": [\n  {\"center\": [0, 0, 0] \"size\": [1, 1, 1]}\n]}\n");
  // The column is where the reader noticed: the last character of the offending token (here the '"' closing
  // "size", which should have followed a ',').
  CHECK(what_of(syntax).find(syntax + ":2: column 29: syntax error") != std::string::npos);
  const auto dup = write("dup.json", "{\"parts\": [\n  {\"center\": [0, 0, 0], \"size\": [1, 1, 1], \"size\": [2, 2, 2]}\n]}\n");
  CHECK(what_of(dup).find(dup + ":2: column 44: duplicate key \"size\"") != std::string::npos);
  const auto type = write("type.json", R"({"parts": [{"center": [0, 0, 0], "size": [1, 1, 1], "must_exist": "yes"}]})");
  CHECK(what_of(type).find(type + ": part 0: \"must_exist\" must be true or false") != std::string::npos);
  const auto vec = write("vec.json", R"({"parts": [{"center": [0, "a", 0], "size": [1, 1, 1]}]})");
  CHECK(what_of(vec).find(vec + ": part 0: \"center\" must contain only numbers") != std::string::npos);
  const auto set = write("set.json", R"({"templates": {"parts": []}})");
  CHECK(what_of(set).find(set + ": \"templates\" must be an array") != std::string::npos);
  std::filesystem::remove_all(dir);
}

TEST_CASE("write_templates is deterministic and keeps the key order") {
  const auto dir = std::filesystem::temp_directory_path() / "shapestruct_tpl_det_test";
  std::filesystem::create_directories(dir);
  const auto a = (dir / "a.json").string(), b = (dir / "b.json").string();
  write_templates(a, {two_boxes()});
  write_templates(b, read_templates(a));
  const auto slurp = [](const std::string& p) {
    std::ifstream in(p, std::ios::binary);
    std::ostringstream ss;
    ss << in.rdbuf();
    return ss.str();
  };
  const std::string text = slurp(a);
  CHECK(text == slurp(b));
  const auto pos = [&](const char* key) { return text.find(std::string("\"") + key + "\":"); };
  CHECK(pos("id") < pos("up_axis"));
  CHECK(pos("up_axis") < pos("parts"));
  CHECK(pos("name") < pos("label"));
  CHECK(pos("label") < pos("center"));
  CHECK(pos("center") < pos("axes"));
  CHECK(pos("feature_sigma") < pos("must_exist"));
  CHECK(text.find("\"size\": [0.4, 0.05, 0.4]") != std::string::npos);
  std::filesystem::remove_all(dir);
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
    (void)template_from_json(parse_json_text(R"({"id": "x", "parts": []})"), "x.json");
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
  CHECK_THROWS_AS(template_from_json(parse_json_text(R"({"parts": [{"center": [0, 0], "size": [1, 1, 1]}]})")), io_error);
  CHECK_THROWS_AS(template_from_json(parse_json_text(R"({"parts": [{"size": [1, 1, 1]}]})")), io_error);
  CHECK_THROWS_AS(template_from_json(parse_json_text(R"([1, 2])")), io_error);
}

TEST_CASE("part_template JSON: axes written to four decimals are snapped, axes far from orthonormal are rejected") {
  // A box turned 45 degrees about the up axis, as a user types it.
  const auto t = template_from_json(parse_json_text(
      R"({"parts": [{"center": [0, 0, 0], "size": [1, 1, 1],
                     "axes": [[0.7071, 0, 0.7071], [0, 1, 0], [-0.7071, 0, 0.7071]]}]})"));
  const Eigen::Matrix3d& a = t.parts[0].axes;
  CHECK((a * a.transpose()).isIdentity(1e-12));
  CHECK(a(0, 0) == doctest::Approx(std::sqrt(0.5)).epsilon(1e-9));
  CHECK(a(2, 0) == doctest::Approx(-std::sqrt(0.5)).epsilon(1e-9));
  CHECK_THROWS_AS(template_from_json(parse_json_text(
                      R"({"parts": [{"center": [0, 0, 0], "size": [1, 1, 1],
                                     "axes": [[0.8, 0, 0.7], [0, 1, 0], [-0.7, 0, 0.7]]}]})")),
                  invalid_input);
}
