// SPDX-License-Identifier: MIT
// write_mesh: writes OFF, OBJ, PLY or STL, chosen by the file's extension (case-insensitive).
#pragma once

#include <filesystem>
#include <string>

#include "shapestruct/core/concepts/surface_mesh.hpp"
#include "shapestruct/core/errors.hpp"
#include "shapestruct/io/file_bytes.hpp"
#include "shapestruct/io/mesh_write_options.hpp"
#include "shapestruct/io/obj_format.hpp"
#include "shapestruct/io/off_format.hpp"
#include "shapestruct/io/ply_format.hpp"
#include "shapestruct/io/stl_format.hpp"

namespace shapestruct {

/// Writes a mesh as OFF, OBJ, PLY or STL according to the extension of `path` (any case). The file is
/// written to a temporary file in the same folder and renamed into place, so a failed write never leaves a
/// half-written file and never destroys an existing one.
/// \param path destination (.off, .obj, .ply or .stl); its folder must exist.
/// \param mesh any SurfaceMesh (triangle_mesh<S> is written without a copy).
/// \param options vertex colours (#V x 3 uint8, optional), binary PLY/STL, PLY byte order.
/// \throws invalid_input non_finite, bad_face or size_mismatch for data no file can hold; io_error
///         unsupported (unknown extension), cannot_open or write_failed.
/// Complexity: O(V + F).
template <SurfaceMesh Mesh>
void write_mesh(const std::filesystem::path& path, const Mesh& mesh, const mesh_write_options& options = {}) {
  const std::string ext = io_detail::lower_extension(path);
  if (ext == "off") write_off(path, mesh, options);
  else if (ext == "obj") write_obj(path, mesh, options);
  else if (ext == "ply") write_ply(path, mesh, options);
  else if (ext == "stl") write_stl(path, mesh, options);
  else
    throw io_error(file_error::unsupported, path.string(), 0, 0,
                   "unknown extension '" + path.extension().string() + "': use .off, .obj, .ply or .stl");
}

}  // namespace shapestruct
