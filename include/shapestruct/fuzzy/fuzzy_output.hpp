// SPDX-License-Identifier: MIT
// fuzzy_output: the output folder of `shapestruct fuzzy` read back (the shapes, their records and f).
#pragma once
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>
#include "shapestruct/collection/collection_files.hpp"
#include "shapestruct/collection/shape_record.hpp"
#include "shapestruct/core/errors.hpp"
#include "shapestruct/fuzzy/fuzzy_correspondence.hpp"
#include "shapestruct/fuzzy/fuzzy_files.hpp"
#include "shapestruct/io/json_file.hpp"

namespace shapestruct {

/// A fuzzy collection as `shapestruct fuzzy` leaves it on disk (docs/fuzzy.md, "The output folder").
struct fuzzy_output {
  std::filesystem::path folder;
  std::string mode;                          ///< "intrinsic" or "extrinsic"
  std::vector<std::filesystem::path> files;  ///< every shape's input file, in the collection's order
  std::vector<shape_record> records;         ///< name, samples, nearest sample of every vertex, ...
  fuzzy_correspondence fuzzy;                ///< f, from fuzzy.bin
  std::vector<std::int8_t> orientation;      ///< +1 / -1 per shape (fuzzy_collection_result::orientation), or empty
  [[nodiscard]] index_t shapes() const noexcept { return static_cast<index_t>(records.size()); }
};

/// Reads collection.json, records/NAME.rec of every shape and fuzzy.bin from `folder`.
/// \throws io_error (cannot_open) naming the first missing file (so a folder that is not fuzzy output is refused
///         with the file it lacks), (syntax / bad_value) for a damaged or inconsistent file.
[[nodiscard]] inline fuzzy_output read_fuzzy_output(const std::filesystem::path& folder) {
  namespace fs = std::filesystem;
  fuzzy_output out;
  out.folder = folder;
  for (const char* needed : {"collection.json", "fuzzy.bin"})
    if (!fs::is_regular_file(folder / needed))
      throw io_error(file_error::cannot_open, (folder / needed).string(), 0, 0,
                     std::string("missing: ") + needed + " (is this the output folder of `shapestruct fuzzy`?)");
  const std::string manifest_path = (folder / "collection.json").string();
  const nlohmann::ordered_json manifest = read_json_file(manifest_path);
  const auto* shapes = json_member(manifest, "shapes");
  if (json_member(manifest, "mode") == nullptr || shapes == nullptr)
    throw io_error(file_error::syntax, manifest_path, 0, 0, "has no \"mode\" or no \"shapes\"");
  out.mode = json_required<std::string>(manifest, "mode", manifest_path);
  if (!shapes->is_array()) throw io_error(file_error::bad_value, manifest_path, 0, 0, "\"shapes\" must be an array");
  for (const auto& s : *shapes) {
    if (json_member(s, "name") == nullptr || json_member(s, "file") == nullptr)
      throw io_error(file_error::syntax, manifest_path, 0, 0, "a shape without \"name\" or \"file\"");
    const auto name = json_required<std::string>(s, "name", manifest_path);
    const fs::path record = folder / "records" / (name + ".rec");
    if (!fs::is_regular_file(record))
      throw io_error(file_error::cannot_open, record.string(), 0, 0, "missing: the record of shape '" + name + "'");
    out.records.push_back(read_shape_record(record));
    out.files.emplace_back(json_required<std::string>(s, "file", manifest_path));
    if (json_member(s, "orientation") != nullptr) {
      const int o = json_required<int>(s, "orientation", manifest_path);
      if (o != 1 && o != -1)
        throw io_error(file_error::bad_value, manifest_path, 0, 0, "shape '" + name + "': \"orientation\" must be 1 or -1");
      out.orientation.push_back(std::int8_t(o));
    }
  }
  if (!out.orientation.empty() && out.orientation.size() != out.records.size())
    throw io_error(file_error::bad_value, manifest_path, 0, 0, "\"orientation\" is given for some shapes but not all");
  out.fuzzy = read_fuzzy_correspondence(folder / "fuzzy.bin");
  if (out.fuzzy.shapes() != out.shapes())
    throw io_error(file_error::bad_value, (folder / "fuzzy.bin").string(), 0, 0,
                   "holds " + std::to_string(out.fuzzy.shapes()) + " shapes, collection.json " + std::to_string(out.shapes()));
  for (index_t k = 0; k < out.shapes(); ++k)
    if (out.fuzzy.embedding().samples_of(k) != out.records[std::size_t(k)].sample_count())
      throw io_error(file_error::bad_value, (folder / "fuzzy.bin").string(), 0, 0,
                     "shape '" + out.records[std::size_t(k)].name + "' has " +
                         std::to_string(out.fuzzy.embedding().samples_of(k)) + " samples, its record " +
                         std::to_string(out.records[std::size_t(k)].sample_count()));
  return out;
}

}  // namespace shapestruct
