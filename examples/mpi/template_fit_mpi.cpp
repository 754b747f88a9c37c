// SPDX-License-Identifier: MIT
// Distributes template fitting over MPI ranks (machines): rank r fits the shapes r, r + size, r + 2 size, ... of
// the folder with the given template set and writes its results into the shared OUT folder, exactly as
// `shapestruct templates --no-learn` would; rank 0 then reports the clusters.
//   mpirun -np 2 example_template_fit_mpi DIR OUT TEMPLATES.json [--threads N]
// Learning is a separate, cheap step on a subset (shapestruct templates DIR -o OUT0 then OUT0/templates.json).
#include <mpi.h>

#include <iostream>
#include <string>
#include <vector>

#include "shapestruct/templates/collection_runner.hpp"

using namespace shapestruct;

int main(int argc, char** argv) {
  MPI_Init(&argc, &argv);
  int rank = 0, size = 1;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  MPI_Comm_size(MPI_COMM_WORLD, &size);
  int code = 0;
  try {
    if (argc < 4) throw std::invalid_argument("usage: example_template_fit_mpi DIR OUT TEMPLATES.json [--threads N]");
    int threads = 1;
    for (int i = 4; i + 1 < argc; ++i)
      if (std::string(argv[i]) == "--threads") threads = std::stoi(argv[i + 1]);
    const auto templates = read_templates(argv[3]);
    const auto all = list_shape_files(argv[1]);
    std::vector<std::filesystem::path> mine;
    for (std::size_t i = static_cast<std::size_t>(rank); i < all.size(); i += static_cast<std::size_t>(size))
      mine.push_back(all[i]);
    // Rank 0 writes templates.json first; the others then find it and use it unchanged.
    if (rank == 0) {
      std::filesystem::create_directories(argv[2]);
      write_templates((std::filesystem::path(argv[2]) / "templates.json").string(), templates);
    }
    MPI_Barrier(MPI_COMM_WORLD);
    collection_run_options opt;
    opt.run_learning = false;
    opt.threads = threads;
    opt.write_ply = false;
    opt.summary_name = "summary.rank" + std::to_string(rank) + ".json";
    opt.problem = [&](const std::string& f, const std::string& m) {
      std::cerr << "rank " << rank << ": skipped " << f << ": " << m << "\n";
    };
    const auto sum = run_template_collection(mine, argv[2], templates, opt);
    unsigned long long local[3] = {sum.processed, sum.skipped, sum.failed}, total[3] = {0, 0, 0};
    MPI_Reduce(local, total, 3, MPI_UNSIGNED_LONG_LONG, MPI_SUM, 0, MPI_COMM_WORLD);
    std::vector<unsigned long long> cl(sum.cluster_sizes.begin(), sum.cluster_sizes.end()), clt(cl.size(), 0);
    MPI_Reduce(cl.data(), clt.data(), static_cast<int>(cl.size()), MPI_UNSIGNED_LONG_LONG, MPI_SUM, 0, MPI_COMM_WORLD);
    if (rank == 0) {
      std::cout << size << " ranks: " << total[0] << " shapes fitted, " << total[1] << " already done, " << total[2]
                << " failed\n";
      for (std::size_t t = 0; t < clt.size(); ++t)
        std::cout << "  cluster " << t << " (" << templates[t].id << "): " << clt[t] << " shapes\n";
    }
  } catch (const std::exception& e) {
    std::cerr << "rank " << rank << ": " << e.what() << "\n";
    code = 1;
  }
  MPI_Finalize();
  return code;
}
