// SPDX-License-Identifier: MIT
// side_by_side: two independent tasks at once (the first on a new thread), errors reported in their order.
#pragma once

#include <exception>
#include <future>
#include <optional>
#include <type_traits>
#include <utility>

namespace shapestruct::detail {

/// Runs first() on a new thread and second() on this one when `concurrently`, else both on this thread (second()
/// first, then first()), and returns both results. When both throw, first's exception is rethrown (as if they had run in order), and either
/// way only after both have finished.
template <class First, class Second>
[[nodiscard]] auto side_by_side(bool concurrently, First&& first, Second&& second)
    -> std::pair<std::invoke_result_t<First&>, std::invoke_result_t<Second&>> {
  auto first_result = std::async(concurrently ? std::launch::async : std::launch::deferred, [&] { return first(); });
  std::optional<std::invoke_result_t<Second&>> second_result;
  std::exception_ptr second_failed;
  try {
    second_result.emplace(second());
  } catch (...) {
    second_failed = std::current_exception();
  }
  auto a = first_result.get();
  if (second_failed) std::rethrow_exception(second_failed);
  return {std::move(a), std::move(*second_result)};
}

}  // namespace shapestruct::detail
