// SPDX-License-Identifier: MIT
// The JSON fields `inspect --json` and analyze's inspect stage write for faces of fewer than 3 corners.
#pragma once

#include <string>

#include "shapestruct/io/mesh_file.hpp"

namespace shapestruct::cli {

/// `"short_faces":N,"first_short_face_line":L,` (or `_byte`), or "" when the file has no such face.
inline std::string short_faces_json_fields(const mesh_file<double>& file) {
  if (file.short_faces == 0) return "";
  return "\"short_faces\":" + std::to_string(file.short_faces) + ",\"first_short_face_" +
         (file.short_face_at_is_byte_offset ? "byte" : "line") + "\":" + std::to_string(file.first_short_face_at) + ",";
}

}  // namespace shapestruct::cli
