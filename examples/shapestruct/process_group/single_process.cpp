// SPDX-License-Identifier: MIT
// The process group of `shapestruct`: one process, which does all the work.
#include "../process_group.hpp"

namespace shapestruct::cli {

const work_share& run_share() {
  static const work_share alone{};
  return alone;
}

process_session::process_session(int&, char**&) {}
process_session::~process_session() = default;
int process_session::finish(int code) { return code; }

}  // namespace shapestruct::cli
