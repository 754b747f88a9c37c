// SPDX-License-Identifier: MIT
// work_share: this process's part of a collection job that several processes (MPI ranks, machines sharing a
// folder) run together. The library stays free of any message-passing library: the caller supplies exchange().
#pragma once

#include <cstddef>
#include <functional>
#include <string>
#include <string_view>
#include <vector>

#include "shapestruct/core/errors.hpp"
#include "shapestruct/core/types.hpp"

namespace shapestruct {

/// Item i of a collection job belongs to part i % parts (round robin over the sorted items, so shapes of every
/// size spread evenly). A stage that takes a work_share computes only its own items, writes them to the shared
/// cache folder, calls exchange() (a collective: every part calls it at the same point, in the same order) and
/// then reads the other parts' items from the folder. Since every item depends only on its inputs, the results
/// are the same whatever the number of parts. The default is one part: everything runs here, exchange unused.
struct work_share {
  std::size_t part = 0;   ///< this process, in [0, parts)
  std::size_t parts = 1;  ///< processes sharing the job
  /// Sends this part's message to every part and returns all parts' messages, in part order. Also a barrier:
  /// it returns only when every part has called it. Needed when parts > 1 (for MPI: MPI_Allgatherv).
  std::function<std::vector<std::string>(const std::string&)> exchange;

  [[nodiscard]] bool distributed() const noexcept { return parts > 1; }
  [[nodiscard]] bool owns(std::size_t item) const noexcept { return item % parts == part; }
  /// The part that writes a job's global files (summaries): part 0.
  [[nodiscard]] bool leader() const noexcept { return part == 0; }

  /// exchange(message), or {message} for one part.
  [[nodiscard]] std::vector<std::string> all_gather(const std::string& message) const {
    if (!distributed()) return {message};
    std::vector<std::string> all = exchange(message);
    if (all.size() != parts)
      throw invalid_input(input_error::bad_parameter, no_index,
                          "work_share: exchange returned " + std::to_string(all.size()) + " messages for " +
                              std::to_string(parts) + " parts");
    return all;
  }

  /// \throws invalid_input (bad_parameter) naming `who` for parts = 0, part >= parts, or no exchange with
  ///         several parts.
  void validate(const char* who) const {
    if (parts == 0 || part >= parts || (parts > 1 && !exchange))
      throw invalid_input(input_error::bad_parameter, no_index,
                          std::string(who) + ": work_share needs part < parts and, for several parts, an exchange "
                                             "function (got part " + std::to_string(part) + " of " +
                              std::to_string(parts) + ")");
  }
};

namespace detail {

/// Length-prefixed concatenation of strings (any bytes), for the messages of work_share::exchange.
inline std::string pack_strings(const std::vector<std::string>& items) {
  std::string out;
  for (const auto& s : items) {
    out += std::to_string(s.size());
    out += ':';
    out += s;
  }
  return out;
}

/// The inverse of pack_strings. \throws invalid_input (bad_parameter) for a malformed message.
inline std::vector<std::string> unpack_strings(std::string_view packed) {
  std::vector<std::string> out;
  std::size_t i = 0;
  while (i < packed.size()) {
    const std::size_t colon = packed.find(':', i);
    if (colon == std::string_view::npos)
      throw invalid_input(input_error::bad_parameter, no_index, "work_share: malformed message");
    std::size_t n = 0;
    for (std::size_t k = i; k < colon; ++k) {
      if (packed[k] < '0' || packed[k] > '9')
        throw invalid_input(input_error::bad_parameter, no_index, "work_share: malformed message");
      n = n * 10 + std::size_t(packed[k] - '0');
    }
    if (colon + 1 + n > packed.size())
      throw invalid_input(input_error::bad_parameter, no_index, "work_share: truncated message");
    out.emplace_back(packed.substr(colon + 1, n));
    i = colon + 1 + n;
  }
  return out;
}

}  // namespace detail
}  // namespace shapestruct
