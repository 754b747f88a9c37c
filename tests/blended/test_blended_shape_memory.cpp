// SPDX-License-Identifier: MIT
// Tests of heap_bytes (core/heap_bytes.hpp) and of blended_shape::heap_bytes, which a cache of prepared shapes
// budgets by: it must count what the allocator really holds for a shape, not an estimate.
#include <cstddef>
#include <memory>
#include <vector>

#include <doctest/doctest.h>

#if defined(__SANITIZE_ADDRESS__)
// From the sanitizer runtime (declared here: Debian ships <sanitizer/allocator_interface.h> only with clang).
extern "C" std::size_t __sanitizer_get_current_allocated_bytes();
#elif defined(__GLIBC__)
#include <malloc.h>
#endif

#include "blended/blended_fixtures.hpp"
#include "shapestruct/blended/blended_shape.hpp"
#include "shapestruct/core/heap_bytes.hpp"

using namespace shapestruct;

namespace {
// Bytes the allocator has handed out and not yet taken back (0 where this build cannot tell).
std::size_t allocated_bytes() {
#if defined(__SANITIZE_ADDRESS__)
  return __sanitizer_get_current_allocated_bytes();
#elif defined(__GLIBC__)
  const struct mallinfo2 m = mallinfo2();
  return m.uordblks + m.hblkhd;
#else
  return 0;
#endif
}
}  // namespace

TEST_CASE("heap_bytes counts a container's capacity and a mesh's two arrays") {
  std::vector<double> v;
  v.reserve(100);
  v.push_back(1);
  CHECK(heap_bytes(v) == 100 * sizeof(double));
  const matrix_x<float> m(7, 3);
  CHECK(heap_bytes(m) == 21 * sizeof(float));
  const auto mesh = test::armed_sphere(2);
  CHECK(heap_bytes(mesh) ==
        std::size_t(mesh.V.rows()) * 3 * sizeof(double) + std::size_t(mesh.F.rows()) * 3 * sizeof(index_t));
}

TEST_CASE("blended_shape heap_bytes is what the allocator holds for the shape") {
  const auto mesh = test::armed_sphere(4);
  blended_shape_options o;
  o.threads = 1;
  const std::size_t before = allocated_bytes();
  auto shape = std::make_unique<blended_shape<double>>(mesh.V, mesh.F, o);
  const std::size_t after = allocated_bytes();
  const std::size_t counted = shape->heap_bytes() + sizeof(blended_shape<double>);
  MESSAGE("heap_bytes " << counted << " bytes, allocator " << (after - before) << " bytes");
  // The table alone (#V x samples doubles) is a lower bound whatever the allocator.
  CHECK(counted > std::size_t(mesh.V.rows()) * std::size_t(shape->samples().size()) * sizeof(double));
  if (after == before) {
    MESSAGE("this build cannot read the allocator's count; only the lower bound was checked");
    return;
  }
  // Within 2 %: the allocator adds a few bytes of bookkeeping to each of the shape's few hundred allocations.
  CHECK(double(counted) >= 0.98 * double(after - before));
  CHECK(double(counted) <= 1.02 * double(after - before));
  shape.reset();
  CHECK(allocated_bytes() <= before + (after - before) / 50);  // and it gives it all back
}

TEST_CASE("blended_shape heap_bytes counts a second feature set once, without what it shares") {
  const auto mesh = test::bumpy_creature();
  blended_shape_options o;
  o.threads = 1;
  const std::size_t before = allocated_bytes();
  auto shape = std::make_unique<blended_shape<double>>(mesh.V, mesh.F, o);
  const std::size_t after = allocated_bytes();
  REQUIRE(shape->alternative() != nullptr);
  const std::size_t counted = shape->heap_bytes() + sizeof(blended_shape<double>);
  MESSAGE("heap_bytes " << counted << " bytes, allocator " << (after - before) << " bytes");
  if (after == before) {
    MESSAGE("this build cannot read the allocator's count");
    return;
  }
  CHECK(double(counted) >= 0.98 * double(after - before));
  CHECK(double(counted) <= 1.02 * double(after - before));
}
