// SPDX-License-Identifier: MIT
// Readers for the files of the BIM correspondence benchmark: .query pair lists, .pid / .vts feature points,
// .sym.info symmetries and the original authors' BenchResult_*.txt per-pair results.
#pragma once

#include <cctype>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <map>
#include <numeric>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "shapestruct/core/errors.hpp"
#include "shapestruct/core/types.hpp"

namespace shapestruct {

/// One mesh of the benchmark as named in a .query file: data set ("SCAPE", "TOSCA", "SHREC"), class and id.
/// For SHREC the id is the 1-based index within the class (20 meshes per class), so the file is
/// 20 (class - 1) + id.
struct bim_mesh_ref {
  std::string dataset, cls, id;

  /// SHREC'07 file number (1-400) of a SHREC reference; the id itself for other data sets.
  [[nodiscard]] std::string global_id() const {
    if (dataset != "SHREC") return id;
    try {
      return std::to_string(20 * (std::stoi(cls) - 1) + std::stoi(id));
    } catch (const std::exception&) {
      return id;
    }
  }

  /// The mesh's name as used in BenchResult file names: mesh%03d (SCAPE), <class><id> (TOSCA), <id> (SHREC).
  [[nodiscard]] std::string name() const {
    if (dataset == "SCAPE") {
      std::string s = id;
      while (s.size() < 3) s = "0" + s;
      return "mesh" + s;
    }
    if (dataset == "TOSCA") return cls + id;
    return global_id();
  }
  /// Path of the mesh relative to the data root.
  [[nodiscard]] std::string relative_path() const {
    if (dataset == "SCAPE") return "SCAPE/Meshes/" + name() + ".off";
    if (dataset == "TOSCA") return "TOSCA/Meshes/" + name() + ".off";
    return "watertight_shrec07/Meshes/" + global_id() + ".off";
  }
};

/// A (source, target) pair of a .query file.
struct bim_pair {
  bim_mesh_ref source, target;
};

namespace detail {
inline std::ifstream bim_open(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw io_error(file_error::cannot_open, path, 0, 0, "cannot open the file");
  return in;
}
inline std::string bim_trim(const std::string& s) {
  const auto b = s.find_first_not_of(" \t\r\n");
  if (b == std::string::npos) return {};
  const auto e = s.find_last_not_of(" \t\r\n");
  return s.substr(b, e - b + 1);
}
}  // namespace detail

/// Reads a .query file: each mesh is three lines (data set, class, id), two meshes per pair.
/// \throws io_error (cannot_open, truncated when the line count is not a multiple of 6).
inline std::vector<bim_pair> read_bim_query(const std::string& path) {
  auto in = detail::bim_open(path);
  std::vector<std::string> lines;
  std::string line;
  while (std::getline(in, line)) {
    line = detail::bim_trim(line);
    if (!line.empty()) lines.push_back(line);
  }
  if (lines.size() % 6 != 0)
    throw io_error(file_error::truncated, path, static_cast<std::int64_t>(lines.size()), 0,
                   "a .query file has 6 non-empty lines per pair; got " + std::to_string(lines.size()));
  std::vector<bim_pair> out;
  for (std::size_t i = 0; i < lines.size(); i += 6)
    out.push_back({{lines[i], lines[i + 1], lines[i + 2]}, {lines[i + 3], lines[i + 4], lines[i + 5]}});
  return out;
}

/// Reads the first integer column of a .pid (SCAPE/TOSCA: "vertex 0 0 0") or .vts ("vertex x y z") file:
/// the 0-based feature vertices, line i = feature point i.
/// \throws io_error (cannot_open; syntax naming the line if a line does not start with an integer).
inline std::vector<index_t> read_bim_feature_vertices(const std::string& path) {
  auto in = detail::bim_open(path);
  std::vector<index_t> out;
  std::string line;
  std::int64_t ln = 0;
  while (std::getline(in, line)) {
    ++ln;
    if (detail::bim_trim(line).empty()) continue;
    std::istringstream ss(line);
    long long v = 0;
    if (!(ss >> v)) throw io_error(file_error::syntax, path, ln, 0, "expected a vertex index at the start of the line");
    if (v < 0) throw io_error(file_error::bad_value, path, ln, 0, "negative vertex index " + std::to_string(v));
    out.push_back(static_cast<index_t>(v));
  }
  return out;
}

/// Reads a feature-name file (.info: SCAPE/TOSCA "<class>.info", SHREC'07 "c<class>.info"), one "k: name" per
/// line, k the 0-based index of the feature point in the matching .pid/.vts list. Blank lines are skipped (some
/// TOSCA files have them, so the line number is not the index). Names are trimmed and lower-cased so the same
/// anatomical point can be matched by name across data sets (the cross-set benchmark lists Corr_Humans/Animals).
/// \returns names[k] for every index k in the file (an empty string for an index the file does not name).
/// \throws io_error (cannot_open; syntax naming the line if it has no "k:" prefix; bad_value for a negative or
/// repeated index).
/// Complexity: O(file size).
inline std::vector<std::string> read_bim_feature_names(const std::string& path) {
  auto in = detail::bim_open(path);
  std::vector<std::string> out;
  std::vector<bool> seen;
  std::string line;
  std::int64_t ln = 0;
  while (std::getline(in, line)) {
    ++ln;
    const std::string t = detail::bim_trim(line);
    if (t.empty()) continue;
    const auto colon = t.find(':');
    long long k = -1;
    try {
      std::size_t used = 0;
      k = std::stoll(t.substr(0, colon), &used);
      if (colon == std::string::npos || detail::bim_trim(t.substr(used, colon - used)).size() != 0)
        throw std::invalid_argument("prefix");
    } catch (const std::exception&) {
      throw io_error(file_error::syntax, path, ln, 0, "expected \"<index>: <name>\"");
    }
    if (k < 0) throw io_error(file_error::bad_value, path, ln, 0, "negative feature index " + std::to_string(k));
    const auto ku = static_cast<std::size_t>(k);
    if (ku >= out.size()) {
      out.resize(ku + 1);
      seen.resize(ku + 1, false);
    }
    if (seen[ku]) throw io_error(file_error::bad_value, path, ln, 0, "feature index " + std::to_string(k) + " named twice");
    seen[ku] = true;
    std::string name = detail::bim_trim(t.substr(colon + 1));
    for (char& c : name) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    out[ku] = std::move(name);
  }
  return out;
}

/// Reads a .sym.info file (one symmetry orbit per line, indices into the feature list) into a permutation of
/// [0, n): orbit (a b) swaps a and b; a longer orbit (a b c ...) is a cycle a->b->c->...->a; indices on no line
/// are fixed points.
/// \throws io_error (cannot_open; bad_value naming the line for an index outside [0, n)).
inline std::vector<index_t> read_bim_symmetry(const std::string& path, index_t n) {
  auto in = detail::bim_open(path);
  std::vector<index_t> perm(static_cast<std::size_t>(n));
  std::iota(perm.begin(), perm.end(), index_t(0));
  std::string line;
  std::int64_t ln = 0;
  while (std::getline(in, line)) {
    ++ln;
    std::istringstream ss(line);
    std::vector<index_t> orbit;
    long long v;
    while (ss >> v) {
      if (v < 0 || v >= n)
        throw io_error(file_error::bad_value, path, ln, 0,
                       "symmetry index " + std::to_string(v) + " outside [0, " + std::to_string(n) + ")");
      orbit.push_back(static_cast<index_t>(v));
    }
    if (orbit.size() < 2) continue;  // a single index is its own image
    for (std::size_t k = 0; k < orbit.size(); ++k)
      perm[static_cast<std::size_t>(orbit[k])] = orbit[(k + 1) % orbit.size()];
  }
  return perm;
}

/// The feature points of one benchmark mesh: their vertices, the symmetry permutation of its class, and their
/// names when asked for (the cross-set lists match feature points by name).
struct bim_feature_points {
  std::vector<index_t> vertices;
  std::vector<index_t> symmetry;   ///< symmetry[k]: the feature point k maps to under the class's symmetry
  std::vector<std::string> names;  ///< names[k] of feature point k; empty unless asked for
};

/// Reads the feature points of mesh `m` under the data root: SCAPE/Corrs/1.pid, 1.sym.info, 1.info (SCAPE's
/// ids are the template's vertices), TOSCA/Corrs/<class>.pid, .sym.info, .info, and for SHREC'07
/// watertight_shrec07/Corrs/<file number>.vts, <class>.sym.info (the identity when the class has none),
/// c<class>.info.
/// \throws io_error as the readers above.
inline bim_feature_points read_bim_feature_points(const std::filesystem::path& data, const bim_mesh_ref& m,
                                                  bool with_names = false) {
  bim_feature_points out;
  std::filesystem::path pid, sym, info;
  if (m.dataset == "SCAPE") {
    pid = data / "SCAPE/Corrs/1.pid", sym = data / "SCAPE/Corrs/1.sym.info", info = data / "SCAPE/Corrs/1.info";
  } else if (m.dataset == "TOSCA") {
    const std::filesystem::path dir = data / "TOSCA/Corrs";
    pid = dir / (m.cls + ".pid"), sym = dir / (m.cls + ".sym.info"), info = dir / (m.cls + ".info");
  } else {
    const std::filesystem::path dir = data / "watertight_shrec07/Corrs";
    pid = dir / (m.global_id() + ".vts"), sym = dir / (m.cls + ".sym.info"), info = dir / ("c" + m.cls + ".info");
  }
  out.vertices = read_bim_feature_vertices(pid.string());
  const auto n = static_cast<index_t>(out.vertices.size());
  if (m.dataset != "SHREC" || std::filesystem::exists(sym)) {
    out.symmetry = read_bim_symmetry(sym.string(), n);
  } else {
    out.symmetry.resize(out.vertices.size());
    std::iota(out.symmetry.begin(), out.symmetry.end(), index_t(0));
  }
  if (with_names) out.names = read_bim_feature_names(info.string());
  return out;
}

/// Feature points of a source and a target mesh paired by name, as the cross-set lists are scored: source
/// vertex, the target vertex of the same name, and that point's partner under the target class's symmetry.
struct bim_named_features {
  std::vector<index_t> source, target, target_symmetric;
};

/// Pairs the named feature points of `a` and `b` (read with names); points without a name or a partner of the
/// same name are left out, so the result may be empty.
/// Complexity: O((|a| + |b|) log |b|).
[[nodiscard]] inline bim_named_features match_bim_features_by_name(const bim_feature_points& a,
                                                                   const bim_feature_points& b) {
  std::map<std::string, std::size_t> by_name;
  for (std::size_t j = 0; j < b.names.size() && j < b.vertices.size(); ++j)
    if (!b.names[j].empty()) by_name.emplace(b.names[j], j);
  bim_named_features out;
  for (std::size_t k = 0; k < a.names.size() && k < a.vertices.size(); ++k) {
    const auto it = a.names[k].empty() ? by_name.end() : by_name.find(a.names[k]);
    if (it == by_name.end()) continue;
    out.source.push_back(a.vertices[k]);
    out.target.push_back(b.vertices[it->second]);
    out.target_symmetric.push_back(b.vertices[static_cast<std::size_t>(b.symmetry[it->second])]);
  }
  return out;
}

/// One block (Stats, StatsWithFlip, ...) of a BenchResult file.
struct bim_result_block {
  double average = 0;
  std::vector<double> per_sample_errors;
  double time = 0;  ///< seconds ("Time"), 0 when absent
  bool flipped = false;
};

/// The blocks of a BenchResult_<Method>_<A>_to_<B>.txt file by name ("Stats", "StatsWithFlip", ...).
/// \throws io_error (cannot_open; syntax naming the line for an unparsable number).
inline std::map<std::string, bim_result_block> read_bim_result(const std::string& path) {
  auto in = detail::bim_open(path);
  std::map<std::string, bim_result_block> out;
  std::string line, current;
  std::int64_t ln = 0;
  while (std::getline(in, line)) {
    ++ln;
    const std::string t = detail::bim_trim(line);
    if (t.empty()) continue;
    if (t.back() == ':' && line[0] != '\t' && line[0] != ' ') {
      current = t.substr(0, t.size() - 1);
      out[current];
      continue;
    }
    const auto lb = t.find('['), rb = t.rfind(']');
    if (current.empty() || lb == std::string::npos || rb == std::string::npos || rb < lb) continue;
    const std::string key = detail::bim_trim(t.substr(0, lb));
    std::string body = t.substr(lb + 1, rb - lb - 1);
    auto& blk = out[current];
    try {
      if (key == "Average") blk.average = std::stod(body);
      else if (key == "Time") blk.time = std::stod(body);
      else if (key == "Flipped") blk.flipped = body == "true";
      else if (key == "PerSampleErrors") {
        for (char& c : body)
          if (c == ',') c = ' ';
        std::istringstream ss(body);
        double x;
        while (ss >> x) blk.per_sample_errors.push_back(x);
      }
    } catch (const std::exception&) {
      throw io_error(file_error::syntax, path, ln, 0, "cannot parse the value of " + key);
    }
  }
  return out;
}

}  // namespace shapestruct
