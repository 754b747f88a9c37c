// SPDX-License-Identifier: MIT
// heap_bytes: the bytes a container owns on the heap, so that a cache of prepared shapes can keep to a memory
// budget. Counts capacities, not the allocator's bookkeeping (16 bytes or so per allocation with glibc).
#pragma once

#include <cstddef>
#include <vector>

#include <Eigen/Core>

#include "shapestruct/core/triangle_mesh.hpp"

namespace shapestruct {

template <class T, class Allocator>
[[nodiscard]] std::size_t heap_bytes(const std::vector<T, Allocator>& v) noexcept {
  return v.capacity() * sizeof(T);
}

template <class Derived>
[[nodiscard]] std::size_t heap_bytes(const Eigen::PlainObjectBase<Derived>& m) noexcept {
  return static_cast<std::size_t>(m.size()) * sizeof(typename Derived::Scalar);
}

template <class Scalar>
[[nodiscard]] std::size_t heap_bytes(const triangle_mesh<Scalar>& mesh) noexcept {
  return heap_bytes(mesh.V) + heap_bytes(mesh.F);
}

}  // namespace shapestruct
