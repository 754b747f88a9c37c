// SPDX-License-Identifier: MIT
// libFuzzer harness for read_ply (see docs/fuzzing.md).
#include <cstddef>
#include <cstdint>

#include "fuzz_harness.hpp"
#include "shapestruct/io/ply_format.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  return shapestruct::fuzz::run([](std::string_view b, std::string_view n) { return shapestruct::read_ply(b, n); },
                                data, size);
}
