// SPDX-License-Identifier: MIT
// `shapestruct inspect`: reads mesh files and prints check_mesh()'s report for each.
#include <algorithm>
#include <cctype>
#include <filesystem>
#include <iostream>
#include <memory>
#include <string>
#include <vector>

#include "command.hpp"
#include "option_checks.hpp"
#include "short_faces_json.hpp"
#include "shapestruct/core/check_mesh.hpp"
#include "shapestruct/core/errors.hpp"
#include "shapestruct/geometry/sphere_repair.hpp"
#include "shapestruct/io/read_mesh.hpp"

namespace {

using namespace shapestruct;
namespace fs = std::filesystem;

std::string json_escape(const std::string& s) {
  std::string out;
  out.reserve(s.size() + 2);
  for (const char ch : s) {
    const auto c = static_cast<unsigned char>(ch);
    if (ch == '"' || ch == '\\') {
      out += '\\';
      out += ch;
    } else if (c < 0x20) {
      static const char hex[] = "0123456789abcdef";
      out += "\\u00";
      out += hex[c >> 4];
      out += hex[c & 15];
    } else {
      out += ch;
    }
  }
  return out;
}

std::string json_quote(const std::string& s) { return "\"" + json_escape(s) + "\""; }

bool has_mesh_extension(const fs::path& p) {
  std::string ext = p.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return char(std::tolower(c)); });
  return ext == ".off" || ext == ".obj" || ext == ".ply" || ext == ".stl";
}

/// The files to inspect: each FILE argument as given, each directory argument expanded (recursively) to its
/// .off/.obj/.ply/.stl files in sorted order, so whole data sets can be checked in one call.
std::vector<fs::path> expand_arguments(const std::vector<std::string>& args) {
  std::vector<fs::path> files;
  for (const auto& a : args) {
    std::error_code ec;
    if (fs::is_directory(a, ec)) {
      std::vector<fs::path> found;
      for (const auto& entry : fs::recursive_directory_iterator(a, ec))
        if (entry.is_regular_file(ec) && has_mesh_extension(entry.path())) found.push_back(entry.path());
      std::sort(found.begin(), found.end());
      files.insert(files.end(), found.begin(), found.end());
    } else {
      files.emplace_back(a);
    }
  }
  return files;
}

/// The command line of `shapestruct inspect`.
struct inspect_options {
  std::vector<std::string> inputs;  ///< FILE|DIR...
  bool json = false;
  long long max_examples = 10;
};

int run_inspect(const inspect_options& o) {
  const bool json = o.json;
  const long long max_examples = o.max_examples;
  const std::vector<fs::path> files = expand_arguments(o.inputs);
  if (files.empty()) throw cli::usage_error("no mesh file (.off .obj .ply .stl) in the given folders");

  const check_mesh_options options{.max_examples = static_cast<index_t>(max_examples)};
  int failures = 0;
  if (json) std::cout << "[\n";
  for (std::size_t i = 0; i < files.size(); ++i) {
    const fs::path& file = files[i];
    std::string error;
    mesh_report report;
    std::string short_faces_json, short_faces_text, match_json, match_text;
    try {
      const auto mf = read_mesh(file);
      report = check_mesh(mf.mesh, options);
      // What `shapestruct match` would do with it by default: repair it into a sphere, or refuse it.
      try {
        const auto fixed = repair_to_sphere<double>(mf.mesh.V, mf.mesh.F, sphere_repair_options::all(), "match");
        const std::string what = fixed.report.any() ? fixed.report.to_string() : "no repair needed";
        match_text = "  match (default repairs): accepted, " + what + "\n";
        match_json = "\"match\":{\"accepted\":true,\"repairs\":" + json_quote(fixed.report.any() ? what : "") + "},";
      } catch (const invalid_input& e) {
        const auto* d = dynamic_cast<const mesh_defect_error*>(&e);
        const std::string why = d ? d->problem() : std::string(e.what());
        match_text = "  match (default repairs): refused, " + why + "\n";
        match_json = "\"match\":{\"accepted\":false,\"reason\":" + json_quote(why) + "},";
      }
      if (mf.short_faces > 0) {
        const std::string at = (mf.short_face_at_is_byte_offset ? "byte " : "line ") + std::to_string(mf.first_short_face_at);
        short_faces_text = "  faces with fewer than 3 corners: " + std::to_string(mf.short_faces) + " (not in the mesh; the first at " + at + ")\n";
        short_faces_json = cli::short_faces_json_fields(mf);
      }
    } catch (const io_error& e) {
      error = e.what();
    } catch (const std::bad_alloc&) {
      error = file.string() + ": out of memory";
    } catch (const std::exception& e) {
      error = file.string() + ": " + e.what();
    }
    if (!error.empty()) {
      ++failures;
      std::cerr << "shapestruct inspect: " << error << "\n";
    }
    if (json) {
      std::cout << "{\"file\":\"" << json_escape(file.string()) << "\",";
      if (error.empty())
        std::cout << "\"ok\":true," << short_faces_json << match_json << "\"report\":" << report.to_json() << "}";
      else
        std::cout << "\"ok\":false,\"error\":\"" << json_escape(error) << "\"}";
      std::cout << (i + 1 < files.size() ? ",\n" : "\n");
    } else if (error.empty()) {
      std::cout << "== " << file.string() << "\n" << report.to_string() << short_faces_text << match_text;
      if (i + 1 < files.size()) std::cout << "\n";
    }
  }
  if (json) std::cout << "]\n";
  if (!json && files.size() > 1)
    std::cout << "\n" << files.size() - static_cast<std::size_t>(failures) << " of " << files.size() << " files read\n";
  return failures == 0 ? 0 : 1;
}

cli::command_fn setup_inspect(CLI::App& app) {
  auto o = std::make_shared<inspect_options>();
  app.add_option("FILE|DIR", o->inputs, "mesh files; a DIR stands for every .off .obj .ply .stl file below it, sorted")
      ->required();
  app.add_flag("--json", o->json, "one JSON array, an object {file, ok, match, report | error} per file");
  app.add_option("--max-examples", o->max_examples, "offending elements listed per problem (default 10)")
      ->type_name("N")
      ->check(cli::at_least(0LL));
  app.footer(
      "Reads each OFF/OBJ/PLY/STL file and prints check_mesh()'s report: counts of vertices, faces, edges and\n"
      "components; boundary edges and loops; non-manifold edges and vertices; inconsistently oriented edges;\n"
      "degenerate faces; duplicate, non-finite and unreferenced vertices; Euler characteristic and genus per\n"
      "component; and up to N offending element indices (0-based) per problem. Faces of fewer than 3\n"
      "corners in the file (not part of the mesh) are counted with the line of the first. The last line says\n"
      "whether 'shapestruct match' accepts the mesh with its default repairs, and what it would repair,\n"
      "or why it refuses it.\n"
      "\n"
      "Exit code 0 when every file was read, 1 when any could not be (the error, naming file and line or\n"
      "byte offset, goes to stderr), 2 on a usage error.");
  return [o] { return run_inspect(*o); };
}

const cli::register_command register_inspect{
    "inspect",
    {"print a mesh check (size, components, boundary, manifoldness, genus, defects) for mesh files", setup_inspect}};

}  // namespace
