// SPDX-License-Identifier: MIT
// The processes of one run of the tool: this one alone (`shapestruct`), or the ranks of an MPI job
// (`shapestruct-mpi`, the same tool linked with process_group/mpi_processes.cpp instead of single_process.cpp).
#pragma once

#include <string>

#include "shapestruct/core/work_share.hpp"

namespace shapestruct::cli {

/// This process's share of the run (part = MPI rank, parts = ranks); one part without MPI.
[[nodiscard]] const work_share& run_share();

/// Joins the group for main()'s lifetime (MPI_Init / MPI_Finalize in the MPI build).
class process_session {
 public:
  process_session(int& argc, char**& argv);
  ~process_session();
  process_session(const process_session&) = delete;
  process_session& operator=(const process_session&) = delete;
  /// main()'s exit code, passed through. With several processes, a failure in one of them would leave the
  /// others waiting at the next exchange: a non-zero code other than 2 (a usage error, which every rank finds
  /// alike before any exchange) ends the whole job.
  int finish(int code);
  /// Refuses (with a message, exit code 2) a command that does not run across several processes.
  [[nodiscard]] static bool runs_across_processes(const std::string& command) { return command == "analyze"; }
};

}  // namespace shapestruct::cli
