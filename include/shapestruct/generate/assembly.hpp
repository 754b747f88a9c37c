// SPDX-License-Identifier: MIT
// assembly: a generated man-made shape (chair, table, airplane) as a labelled polygon soup of parts.
#pragma once

#include <array>
#include <span>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "shapestruct/core/errors.hpp"
#include "shapestruct/core/triangle_mesh.hpp"
#include "shapestruct/generate/feature_point.hpp"

namespace shapestruct {

/// The classes of man-made assemblies. Conventions for all: +Y up, the front faces -Z, left is -X.
enum class assembly_kind : int { chair = 0, table = 1, airplane = 2 };

inline const char* to_string(assembly_kind k) noexcept {
  switch (k) {
    case assembly_kind::chair: return "chair";
    case assembly_kind::table: return "table";
    case assembly_kind::airplane: return "airplane";
  }
  return "unknown";
}

/// Part label names per class; a face label is an index into its class's list (stable across versions).
inline constexpr std::array<const char*, 7> chair_label_names = {"seat", "back", "leg", "arm", "stretcher", "pedestal", "base"};
inline constexpr std::array<const char*, 7> table_label_names = {"top", "leg", "apron", "pedestal", "base", "panel", "stretcher"};
inline constexpr std::array<const char*, 5> airplane_label_names = {"fuselage", "wing", "horizontal_tail", "vertical_tail", "engine"};

/// The label names of a class, in label-id order.
inline std::span<const char* const> assembly_label_names(assembly_kind k) {
  switch (k) {
    case assembly_kind::chair: return chair_label_names;
    case assembly_kind::table: return table_label_names;
    case assembly_kind::airplane: return airplane_label_names;
  }
  throw invalid_input(input_error::bad_parameter, no_index, "assembly_label_names: unknown assembly_kind");
}

/// One part instance: its label and the oriented box that contains it exactly (the primitive's own box).
template <class Scalar = double>
struct assembly_part {
  int label = 0;                                               ///< index into the class's label names
  vec3<Scalar> center = vec3<Scalar>::Zero();
  Eigen::Matrix<Scalar, 3, 3> axes = Eigen::Matrix<Scalar, 3, 3>::Identity();  ///< orthonormal columns
  vec3<Scalar> half_extents = vec3<Scalar>::Zero();            ///< along each axis

  /// True if p lies in the box, up to `tolerance` along each axis.
  [[nodiscard]] bool contains(const vec3<Scalar>& p, Scalar tolerance = Scalar(1e-9)) const {
    const vec3<Scalar> local = axes.transpose() * (p - center);
    return (local.cwiseAbs() - half_extents).maxCoeff() <= tolerance;
  }
};

/// A generated assembly: a polygon soup (separate, intersecting closed pieces, not one manifold).
template <class Scalar = double>
struct assembly {
  assembly_kind kind = assembly_kind::chair;
  triangle_mesh<Scalar> mesh;                     ///< all parts, concatenated
  std::vector<int> face_labels;                   ///< per face: part label
  std::vector<index_t> face_part;                 ///< per face: index into parts
  std::vector<assembly_part<Scalar>> parts;       ///< part instances (a chair has 4 "leg" instances, ...)
  std::vector<feature_point<Scalar>> features;    ///< named landmarks, each a mesh vertex
};

}  // namespace shapestruct
