// SPDX-License-Identifier: MIT
// `shapestruct generate`: writes a synthetic collection (creatures or assemblies) with its ground truth.
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "command.hpp"
#include "option_checks.hpp"
#include "shapestruct/core/errors.hpp"
#include "shapestruct/generate/assembly_generator.hpp"
#include "shapestruct/generate/creature_generator.hpp"
#include "shapestruct/io/json_file.hpp"
#include "shapestruct/io/segmentation_file.hpp"
#include "shapestruct/io/write_mesh.hpp"

namespace {

using namespace shapestruct;
namespace fs = std::filesystem;

/// Writes `text` to `path`, naming the path in the error (io_error) if that fails.
void write_text(const fs::path& path, const std::string& text) {
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  if (!out) throw io_error(file_error::cannot_open, path.string(), 0, 0, "cannot open file for writing");
  out.write(text.data(), static_cast<std::streamsize>(text.size()));
  out.flush();
  if (!out) throw io_error(file_error::write_failed, path.string(), 0, 0, "could not write the whole file");
}

std::string number(double x) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.9g", x);
  return buf;
}

std::string stem_of(const std::string& prefix, std::uint64_t i) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%06llu", static_cast<unsigned long long>(i));
  return prefix + "_" + buf;
}

void write_labels(const fs::path& path, const std::vector<int>& labels) {
  const std::vector<index_t> l(labels.begin(), labels.end());
  write_segmentation(path, l);
}

void write_points(const fs::path& path, const std::vector<feature_point<double>>& features) {
  std::string out;
  for (const auto& f : features)
    out += f.name + " " + number(f.position.x()) + " " + number(f.position.y()) + " " + number(f.position.z()) + "\n";
  write_text(path, out);
}

void write_corr(const fs::path& path, const creature<double>& c) {
  std::string out;
  out.reserve(c.canonical.size() * 28);
  for (const auto& p : c.canonical) out += std::to_string(p.patch) + " " + number(p.u) + " " + number(p.v) + "\n";
  write_text(path, out);
}

void write_sym(const fs::path& path, const creature<double>& c) {
  std::string out;
  out.reserve(c.symmetry.size() * 40);
  for (std::size_t v = 0; v < c.symmetry.size(); ++v) {
    const auto& s = c.symmetry[v];
    out += std::to_string(c.symmetry_vertex[v]) + " " + std::to_string(s.face) + " " + number(s.bary[0]) + " " +
           number(s.bary[1]) + " " + number(s.bary[2]) + "\n";
  }
  write_text(path, out);
}

nlohmann::ordered_json names_json(std::span<const char* const> names) {
  auto a = nlohmann::ordered_json::array();
  for (const char* n : names) a.push_back(n);
  return a;
}

/// The command line of `shapestruct generate`.
struct generate_options {
  std::string kind;
  long long count = 0;
  std::string out_dir;
  long long seed = 0;
  long long first = 0;
  std::string format = "off";
  long long threads = 0;
  bool force = false;
};

int run_generate(const generate_options& o) {
  const bool force = o.force;
  const std::string& out_dir = o.out_dir;
  const long long seed = o.seed;
  const long long first = o.first;
  const long long threads = o.threads;
  const std::string& format = o.format;
  const std::string& kind = o.kind;
  const long long count = o.count;
  std::optional<assembly_kind> akind;
  const bool creatures = kind == "creatures";
  if (kind == "chairs") akind = assembly_kind::chair;
  else if (kind == "tables") akind = assembly_kind::table;
  else if (kind == "airplanes") akind = assembly_kind::airplane;

  // Never clobber what a user has: a non-empty folder needs --force (and then only our file names are
  // replaced; nothing else in it is touched).
  const fs::path dir(out_dir);
  std::error_code ec;
  if (fs::exists(dir, ec)) {
    if (!fs::is_directory(dir, ec))
      throw io_error(file_error::cannot_open, dir.string(), 0, 0, "exists and is not a folder");
    if (!fs::is_empty(dir, ec) && !force)
      throw io_error(file_error::cannot_open, dir.string(), 0, 0,
                     "folder is not empty; pass --force to write into it (files of the same name are replaced)");
  } else if (!fs::create_directories(dir, ec) || ec) {
    throw io_error(file_error::cannot_open, dir.string(), 0, 0, "cannot create the folder: " + ec.message());
  }

  const auto t0 = std::chrono::steady_clock::now();
  using ojson = nlohmann::ordered_json;  // keys are written in insertion order
  ojson manifest = ojson::object();
  manifest["kind"] = kind;
  manifest["seed"] = static_cast<long long>(seed);
  manifest["first"] = static_cast<long long>(first);
  manifest["count"] = static_cast<long long>(count);
  manifest["format"] = format;
  manifest["up"] = "+y";
  manifest["front"] = "-z";
  manifest["left"] = "-x";
  ojson label_names = ojson::object();
  ojson shapes = ojson::array();
  const auto useed = static_cast<std::uint64_t>(seed), ufirst = static_cast<std::uint64_t>(first);
  const auto nthreads = static_cast<unsigned>(threads);
  // Shapes are generated in parallel chunks and written in order, so memory stays bounded for large N.
  const std::size_t chunk = 64;
  if (creatures) {
    const creature_generator<double> gen(useed, {.threads = nthreads});
    label_names["creature"] = names_json(creature_part_names);
    const auto canon = gen.canonical();
    write_mesh(dir / ("canonical." + format), canon.mesh);
    write_corr(dir / "canonical.corr", canon);
    write_labels(dir / "canonical.seg", canon.face_labels);
    manifest["canonical"] = ojson::object({{"mesh", "canonical." + format}, {"corr", "canonical.corr"},
                                           {"seg", "canonical.seg"}});
    for (long long done = 0; done < count; done += static_cast<long long>(chunk)) {
      const std::size_t n = static_cast<std::size_t>(std::min<long long>(static_cast<long long>(chunk), count - done));
      const auto batch = gen.generate_range(ufirst + static_cast<std::uint64_t>(done), n, nthreads);
      for (std::size_t k = 0; k < n; ++k) {
        const auto& c = batch[k];
        const std::uint64_t index = ufirst + static_cast<std::uint64_t>(done) + k;
        const std::string stem = stem_of("creature", index);
        write_mesh(dir / (stem + "." + format), c.mesh);
        write_labels(dir / (stem + ".seg"), c.face_labels);
        write_points(dir / (stem + ".pts"), c.features);
        write_corr(dir / (stem + ".corr"), c);
        write_sym(dir / (stem + ".sym"), c);
        ojson limbs = ojson::array();
        for (int s = 0; s < creature_slot_count; ++s)
          if (c.has_slot[static_cast<std::size_t>(s)]) limbs.push_back(creature_slot_tip_names[static_cast<std::size_t>(s)]);
        shapes.push_back(ojson::object({{"index", index},
                                        {"class", "creature"},
                                        {"mesh", stem + "." + format},
                                        {"seg", stem + ".seg"},
                                        {"pts", stem + ".pts"},
                                        {"corr", stem + ".corr"},
                                        {"sym", stem + ".sym"},
                                        {"vertices", static_cast<long long>(c.mesh.num_vertices())},
                                        {"faces", static_cast<long long>(c.mesh.num_faces())},
                                        {"limb_tips", std::move(limbs)}}));
      }
    }
  } else {
    const assembly_generator<double> gen(akind, useed, {.threads = nthreads});
    for (const auto k : {assembly_kind::chair, assembly_kind::table, assembly_kind::airplane})
      if (!akind || *akind == k) label_names[std::string(to_string(k))] = names_json(assembly_label_names(k));
    for (long long done = 0; done < count; done += static_cast<long long>(chunk)) {
      const std::size_t n = static_cast<std::size_t>(std::min<long long>(static_cast<long long>(chunk), count - done));
      const auto batch = gen.generate_range(ufirst + static_cast<std::uint64_t>(done), n, nthreads);
      for (std::size_t k = 0; k < n; ++k) {
        const auto& a = batch[k];
        const std::uint64_t index = ufirst + static_cast<std::uint64_t>(done) + k;
        const std::string stem = stem_of(to_string(a.kind), index);
        write_mesh(dir / (stem + "." + format), a.mesh);
        write_labels(dir / (stem + ".seg"), a.face_labels);
        write_points(dir / (stem + ".pts"), a.features);
        shapes.push_back(ojson::object({{"index", index},
                                        {"class", to_string(a.kind)},
                                        {"mesh", stem + "." + format},
                                        {"seg", stem + ".seg"},
                                        {"pts", stem + ".pts"},
                                        {"vertices", static_cast<long long>(a.mesh.num_vertices())},
                                        {"faces", static_cast<long long>(a.mesh.num_faces())},
                                        {"parts", static_cast<long long>(a.parts.size())}}));
      }
    }
  }
  manifest["label_names"] = std::move(label_names);
  manifest["shapes"] = std::move(shapes);
  write_json_file((dir / "collection.json").string(), manifest);
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  std::cout << "wrote " << count << " " << kind << " to " << dir.string() << " in " << number(seconds) << " s ("
            << number(static_cast<double>(count) / seconds) << " shapes/s, files included)\n";
  return 0;
}

cli::command_fn setup_generate(CLI::App& app) {
  auto o = std::make_shared<generate_options>();
  app.add_option("KIND", o->kind, "creatures | chairs | tables | airplanes | assemblies (a mix of the three\nassembly classes)")
      ->required()
      ->check(cli::one_of({"creatures", "chairs", "tables", "airplanes", "assemblies"}));
  app.add_option("N", o->count, "number of shapes")->required()->check(cli::at_least(1LL));
  app.add_option("-o,--output", o->out_dir,
                 "output folder; created if missing; a non-empty DIR is refused unless --force")
      ->type_name("DIR")
      ->required();
  app.add_option("--seed", o->seed, "collection seed (default 0)")->type_name("S")->check(cli::at_least(0LL));
  app.add_option("--first", o->first, "index of the first shape (default 0)")->type_name("I")->check(cli::at_least(0LL));
  app.add_option("--format", o->format, "mesh format: off (default), obj or ply")
      ->type_name("off|obj|ply")
      ->check(cli::one_of({"off", "obj", "ply"}));
  app.add_option("--threads", o->threads, "generation threads, 0 = all cores (default); output is identical\nfor any T")
      ->type_name("T")
      ->check(cli::at_least(0LL));
  app.add_flag("--force", o->force, "write into a non-empty DIR (replaces files of the same names only)");
  app.footer(
      "Writes shapes I .. I+N-1 (default I = 0) of the collection (KIND, S); shape i depends only on\n"
      "(KIND, S, i), so any subset can be regenerated. Per shape STEM (e.g. creature_000007, chair_000003):\n"
      "  STEM.off|obj|ply  the mesh (assemblies: a polygon soup of separate parts)\n"
      "  STEM.seg          one 0-based part label per face per line (names in collection.json)\n"
      "  STEM.pts          landmarks, one 'name x y z' per line (each is a mesh vertex)\n"
      "  STEM.corr         creatures: per vertex 'patch u v', its point in the common domain; the same line\n"
      "                    on canonical.corr / canonical.off (written once) or any creature is the same place\n"
      "  STEM.sym          creatures: per vertex 'w f b0 b1 b2': w the vertex nearest its left-right mirror\n"
      "                    image, (f, b) the exact mirror point as face and barycentric weights\n"
      "  collection.json   kind, seed, count, label names, conventions (+y up, -z front) and the file list\n"
      "See docs/synthetic_collections.md.");
  return [o] { return run_generate(*o); };
}

const cli::register_command register_generate{
    "generate",
    {"write a synthetic collection (creatures, chairs, tables, airplanes) with exact ground truth", setup_generate}};

}  // namespace
