// SPDX-License-Identifier: MIT
// progress_line: the command-line tool's one-line progress display (stage, done / total, time spent and left),
// shared by `shapestruct fuzzy` and `shapestruct analyze`.
#pragma once

#include <chrono>
#include <cstdio>
#include <string>

#include <unistd.h>

namespace shapestruct::cli {

/// One progress line per stage, rewritten in place: done / total, percent, time left.
class progress_line {
 public:
  /// `prefix` is written before every stage name (analyze: "fuzzy/"; empty for fuzzy itself).
  explicit progress_line(bool quiet, std::string prefix = {})
      : quiet_(quiet), terminal_(isatty(2) != 0), prefix_(std::move(prefix)) {}
  void update(const std::string& stage, std::size_t done, std::size_t total) {
    // On a terminal the line is redrawn in place; in a log only each stage's last state is written.
    if (quiet_ || total == 0 || (!terminal_ && done < total)) return;
    const auto now = std::chrono::steady_clock::now();
    if (stage != stage_) {
      if (!stage_.empty()) std::fprintf(stderr, "\n");
      stage_ = stage;
      start_ = now;
    }
    const double spent = std::chrono::duration<double>(now - start_).count();
    const double left = done > 0 ? spent * double(total - done) / double(done) : 0.0;
    const int width = 30;
    const int filled = static_cast<int>(double(width) * double(done) / double(total));
    std::fprintf(stderr, "\r%-10s [%s%s] %zu/%zu %5.1f%%  %6.1f s spent, %6.1f s left ", (prefix_ + stage).c_str(),
                 std::string(std::size_t(filled), '#').c_str(), std::string(std::size_t(width - filled), '.').c_str(),
                 done, total, 100.0 * double(done) / double(total), spent, left);
    std::fflush(stderr);
  }
  void finish() {
    if (!quiet_ && !stage_.empty()) std::fprintf(stderr, "\n");
    stage_.clear();
  }

 private:
  bool quiet_;
  bool terminal_;
  std::string prefix_;
  std::string stage_;
  std::chrono::steady_clock::time_point start_;
};

}  // namespace shapestruct::cli
