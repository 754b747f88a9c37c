// SPDX-License-Identifier: MIT
// runner_errors: the benchmark runners' main. An exception (an unreadable data folder, a bad number after a flag)
// becomes one line on stderr and exit status 1 instead of std::terminate.
#pragma once

#include <exception>
#include <iostream>

namespace shapestruct::bench {

/// Returns run()'s exit status, or 1 after printing "<program>: <what>" for an exception it throws.
template <class Run>
int run_reporting_errors(const char* program, Run&& run) {
  try {
    return run();
  } catch (const std::exception& e) {
    std::cerr << program << ": " << e.what() << "\n";
    return 1;
  }
}

}  // namespace shapestruct::bench
