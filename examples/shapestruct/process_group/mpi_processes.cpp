// SPDX-License-Identifier: MIT
// The process group of `shapestruct-mpi`: the ranks of MPI_COMM_WORLD (OpenMPI), which exchange small messages
// with MPI_Allgatherv; the results themselves travel through the shared output folder.
#include <mpi.h>

#include <cstdio>
#include <cstdlib>
#include <stdexcept>
#include <string>
#include <vector>

#include "../process_group.hpp"

namespace shapestruct::cli {
namespace {

work_share& group_share() {
  static work_share share{};
  return share;
}

std::vector<std::string> exchange_all(const std::string& message) {
  int ranks = 1;
  MPI_Comm_size(MPI_COMM_WORLD, &ranks);
  if (message.size() > static_cast<std::size_t>(INT32_MAX))
    throw std::length_error("shapestruct-mpi: a message between ranks exceeds 2 GiB");
  const int mine = static_cast<int>(message.size());
  std::vector<int> sizes(static_cast<std::size_t>(ranks)), offsets(static_cast<std::size_t>(ranks));
  MPI_Allgather(&mine, 1, MPI_INT, sizes.data(), 1, MPI_INT, MPI_COMM_WORLD);
  long long total = 0;
  for (int r = 0; r < ranks; ++r) {
    offsets[std::size_t(r)] = static_cast<int>(total);
    total += sizes[std::size_t(r)];
  }
  if (total > INT32_MAX) throw std::length_error("shapestruct-mpi: the messages of one exchange exceed 2 GiB");
  std::string all(static_cast<std::size_t>(total), '\0');
  MPI_Allgatherv(message.data(), mine, MPI_CHAR, all.data(), sizes.data(), offsets.data(), MPI_CHAR, MPI_COMM_WORLD);
  std::vector<std::string> out;
  for (int r = 0; r < ranks; ++r) out.push_back(all.substr(std::size_t(offsets[std::size_t(r)]), std::size_t(sizes[std::size_t(r)])));
  return out;
}

}  // namespace

const work_share& run_share() { return group_share(); }

process_session::process_session(int& argc, char**& argv) {
  MPI_Init(&argc, &argv);
  int rank = 0, ranks = 1;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  MPI_Comm_size(MPI_COMM_WORLD, &ranks);
  auto& share = group_share();
  share.part = static_cast<std::size_t>(rank);
  share.parts = static_cast<std::size_t>(ranks);
  share.exchange = exchange_all;
}

process_session::~process_session() { MPI_Finalize(); }

int process_session::finish(int code) {
  if (code != 0 && code != 2 && run_share().distributed()) {
    std::fprintf(stderr, "shapestruct-mpi: rank %zu failed (exit code %d): ending the job\n", run_share().part, code);
    std::fflush(stderr);
    MPI_Abort(MPI_COMM_WORLD, code);
  }
  return code;
}

}  // namespace shapestruct::cli
