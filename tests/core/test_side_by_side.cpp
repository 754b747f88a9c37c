// SPDX-License-Identifier: MIT
#include <doctest/doctest.h>

#include <atomic>
#include <stdexcept>
#include <string>
#include <thread>

#include "shapestruct/detail/side_by_side.hpp"

using shapestruct::detail::side_by_side;

TEST_CASE("side_by_side returns both results, concurrently or one after the other") {
  for (const bool concurrently : {true, false}) {
    const auto r = side_by_side(concurrently, [] { return 7; }, [] { return std::string("b"); });
    CHECK(r.first == 7);
    CHECK(r.second == "b");
  }
  // Concurrently, the first task runs on another thread; otherwise on this one.
  const auto here = std::this_thread::get_id();
  CHECK(side_by_side(true, [] { return std::this_thread::get_id(); }, [] { return 0; }).first != here);
  CHECK(side_by_side(false, [] { return std::this_thread::get_id(); }, [] { return 0; }).first == here);
}

TEST_CASE("side_by_side reports the first task's error when both fail, and only after both have finished") {
  for (const bool concurrently : {true, false}) {
    std::atomic<bool> first_done{false}, second_done{false};
    const auto fail_first = [&]() -> int {
      first_done = true;
      throw std::runtime_error("first");
    };
    const auto fail_second = [&]() -> int {
      second_done = true;
      throw std::runtime_error("second");
    };
    CHECK_THROWS_WITH((void)side_by_side(concurrently, fail_first, fail_second), "first");
    CHECK(first_done);
    CHECK(second_done);
    CHECK_THROWS_WITH((void)side_by_side(concurrently, [] { return 1; }, fail_second), "second");
    CHECK_THROWS_WITH((void)side_by_side(concurrently, fail_first, [] { return 2; }), "first");
  }
}
