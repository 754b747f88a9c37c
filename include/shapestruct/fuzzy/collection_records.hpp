// SPDX-License-Identifier: MIT
// collection_records: the shape records of a folder of mesh files, made in parallel, cached, bad files skipped.
#pragma once

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <functional>
#include <map>
#include <mutex>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "shapestruct/collection/collection_files.hpp"
#include "shapestruct/collection/make_shape_record.hpp"
#include "shapestruct/collection/shape_record.hpp"
#include "shapestruct/collection/spherical_harmonic_descriptor.hpp"
#include "shapestruct/core/errors.hpp"
#include "shapestruct/core/work_share.hpp"
#include "shapestruct/detail/parallel_for.hpp"
#include "shapestruct/io/read_mesh.hpp"

namespace shapestruct {

/// A shape file that could not join the collection, and why.
struct skipped_shape {
  std::filesystem::path file;
  std::string reason;
};

/// The records of a collection and the files they came from (records[i] from files[i]).
struct collection_records {
  std::vector<shape_record> records;
  std::vector<std::filesystem::path> files;
  std::vector<skipped_shape> skipped;
};

/// Options of make_collection_records.
struct collection_records_options {
  shape_record_options record{};
  spherical_harmonic_descriptor_options descriptor{};
  /// Records are cached here as NAME.rec ("" = not cached). Keyed by file name only: the record of a file edited
  /// since is reused, so clear it (`shapestruct fuzzy` guards this with its cache.json of file fingerprints).
  std::filesystem::path cache_folder{};
  int threads = 0;                       ///< 0 = all cores; the result does not depend on it
  std::function<void(std::size_t, std::size_t)> on_progress{};  ///< (done, total) of this part's files
  /// Several processes: each makes the records of its own files, then reads the others' from the cache folder
  /// (required then). The result is the same as with one process.
  work_share share{};
};

/// Reads every file, makes its record (make_shape_record with the spherical-harmonic descriptor) and forgets
/// the mesh, in parallel; with a cache folder, a record already there is read instead. A file that cannot be
/// read, is empty, has a non-finite coordinate or is otherwise unusable is reported in `skipped` with the reason
/// and left out; the others keep their order. Shape names are the file stems; a stem seen twice is skipped.
/// \throws io_error if the cache folder cannot be created; invalid_input (bad_parameter) for a distributed
///         share without a cache folder.
[[nodiscard]] inline collection_records make_collection_records(const std::vector<std::filesystem::path>& files,
                                                               const collection_records_options& options = {}) {
  namespace fs = std::filesystem;
  const work_share& share = options.share;
  share.validate("make_collection_records");
  if (share.distributed() && options.cache_folder.empty())
    throw invalid_input(input_error::bad_parameter, no_index,
                        "make_collection_records: several processes share records through the cache folder: set one");
  if (!options.cache_folder.empty()) {
    std::error_code ec;
    fs::create_directories(options.cache_folder, ec);
    if (ec)
      throw io_error(file_error::cannot_open, options.cache_folder.string(), 0, 0,
                     "cannot create the record cache folder: " + ec.message());
  }
  const spherical_harmonic_descriptor describe(options.descriptor);
  std::vector<shape_record> made(files.size());
  std::vector<std::string> error(files.size());
  std::mutex m;
  std::size_t done = 0;
  const unsigned workers = detail::resolve_threads(options.threads, "make_collection_records");
  std::vector<std::size_t> mine;
  for (std::size_t i = 0; i < files.size(); ++i)
    if (share.owns(i)) mine.push_back(i);
  detail::parallel_for(mine.size(), workers, [&](std::size_t j) {
    const std::size_t i = mine[j];
    const std::string stem = files[i].stem().string();
    const fs::path cached = options.cache_folder.empty() ? fs::path{} : options.cache_folder / (stem + ".rec");
    try {
      bool have = false;
      if (!cached.empty() && fs::exists(cached)) {
        try {
          made[i] = read_shape_record(cached);
          have = made[i].sample_count() == options.record.samples;
        } catch (const io_error&) {
          have = false;  // damaged by an interrupted write of an older version: make it again
        }
      }
      if (!have) {
        const auto file = read_mesh(files[i]);
        if (file.mesh.V.rows() == 0 || file.mesh.F.rows() == 0)
          throw invalid_input(input_error::empty, no_index, "the file holds no triangles");
        made[i] = make_shape_record(file.mesh, stem, describe, options.record);
        if (!cached.empty()) write_shape_record(cached, made[i]);
      }
    } catch (const std::exception& e) {
      error[i] = e.what();
    }
    std::lock_guard lock(m);
    ++done;
    if (options.on_progress) options.on_progress(done, mine.size());
  });
  if (share.distributed()) {
    // Every part learns the others' failures; their records come from the cache folder.
    std::vector<std::string> failures;
    for (const auto i : mine)
      if (!error[i].empty()) failures.insert(failures.end(), {std::to_string(i), error[i]});
    for (const auto& message : share.all_gather(detail::pack_strings(failures))) {
      const auto items = detail::unpack_strings(message);
      for (std::size_t k = 0; k + 1 < items.size(); k += 2) error[std::stoul(items[k])] = items[k + 1];
    }
    for (std::size_t i = 0; i < files.size(); ++i) {
      if (share.owns(i) || !error[i].empty()) continue;
      try {
        made[i] = read_shape_record(options.cache_folder / (files[i].stem().string() + ".rec"));
      } catch (const std::exception& e) {
        error[i] = std::string("the record made by another process cannot be read: ") + e.what();
      }
    }
  }
  collection_records out;
  std::set<std::string> seen;
  for (std::size_t i = 0; i < files.size(); ++i) {
    if (!error[i].empty()) {
      out.skipped.push_back({files[i], error[i]});
      continue;
    }
    if (!seen.insert(made[i].name).second) {
      out.skipped.push_back({files[i], "another file has the same name '" + made[i].name + "'"});
      continue;
    }
    out.records.push_back(std::move(made[i]));
    out.files.push_back(files[i]);
  }
  return out;
}

/// Keeps the records that intrinsic alignment can take (closed genus-0 surfaces sampled geodesically, see
/// shape_record::closed_genus0) and moves the others to `skipped`, each with `reason`. Order is kept.
inline void keep_intrinsic_shapes(collection_records& c,
                                  const std::string& reason = "not a closed genus-0 surface (intrinsic mode)") {
  std::vector<shape_record> records;
  std::vector<std::filesystem::path> files;
  for (std::size_t i = 0; i < c.records.size(); ++i) {
    const auto& r = c.records[i];
    if (r.closed_genus0 && !r.sample_vertex.empty() && r.sample_vertex[0] != no_index) {
      records.push_back(std::move(c.records[i]));
      files.push_back(c.files[i]);
    } else {
      c.skipped.push_back({c.files[i], reason});
    }
  }
  c.records = std::move(records);
  c.files = std::move(files);
}

/// Index of every record by its name.
[[nodiscard]] inline std::map<std::string, index_t> index_by_name(const std::vector<shape_record>& records) {
  std::map<std::string, index_t> out;
  for (std::size_t i = 0; i < records.size(); ++i) out.emplace(records[i].name, static_cast<index_t>(i));
  return out;
}

}  // namespace shapestruct
