// SPDX-License-Identifier: MIT
// run_template_psb: PSB Rand index of `shapestruct templates` labels for one class, beside the human-to-human RI.
//   run_template_psb PSB_DIR OUT_DIR FIRST_ID LAST_ID
// PSB_DIR = $SHAPESTRUCT_DATA/psb/data (off/<id>.off, seg/Benchmark/<id>/<id>_<k>.seg); OUT_DIR holds <id>.seg
// written by `shapestruct templates` for meshes FIRST_ID..LAST_ID. Rand index (higher is better; PSB papers
// report 1 - RI) is averaged over all human segmentations of each mesh, then over meshes; the human baseline
// averages RI over all pairs of different human segmentations of the same mesh. Faces are weighted by area.
#include <filesystem>
#include <iostream>
#include <string>
#include <vector>

#include "shapestruct/eval/rand_index.hpp"
#include "shapestruct/geometry/mesh_measures.hpp"
#include "shapestruct/io/read_mesh.hpp"
#include "shapestruct/io/segmentation_file.hpp"
#include "runner_errors.hpp"

namespace fs = std::filesystem;
using namespace shapestruct;

static int run(int argc, char** argv) {
  if (argc < 5) {
    std::cerr << "usage: run_template_psb PSB_DIR OUT_DIR FIRST_ID LAST_ID\n";
    return 2;
  }
  const fs::path psb = argv[1], out = argv[2];
  const int first = std::stoi(argv[3]), last = std::stoi(argv[4]);
  double ours = 0, human = 0;
  int n = 0, nh = 0;
  for (int id = first; id <= last; ++id) {
    const std::string s = std::to_string(id);
    if (!fs::exists(out / (s + ".seg"))) continue;
    const auto m = read_mesh(psb / "off" / (s + ".off")).mesh;
    const auto A = face_areas<double>(m.V, m.F);
    const std::vector<double> w(A.data(), A.data() + A.size());
    const auto pred = read_segmentation(out / (s + ".seg"), m.F.rows());
    std::vector<std::vector<index_t>> humans;
    for (const auto& e : fs::directory_iterator(psb / "seg" / "Benchmark" / s))
      if (e.path().extension() == ".seg") humans.push_back(read_segmentation(e.path(), m.F.rows()));
    if (humans.empty()) continue;
    double r = 0;
    for (const auto& h : humans) r += rand_index(pred, h, w);
    ours += r / double(humans.size());
    ++n;
    double rh = 0;
    int pairs = 0;
    for (std::size_t a = 0; a < humans.size(); ++a)
      for (std::size_t b = a + 1; b < humans.size(); ++b, ++pairs) rh += rand_index(humans[a], humans[b], w);
    if (pairs > 0) {
      human += rh / pairs;
      ++nh;
    }
  }
  if (n == 0) {
    std::cerr << "run_template_psb: no predicted .seg found\n";
    return 1;
  }
  std::cout << "meshes " << n << "  RI ours " << ours / n << "  RI human-human " << (nh ? human / nh : 0) << "\n";
  return 0;
}

int main(int argc, char** argv) {
  return shapestruct::bench::run_reporting_errors("run_template_psb", [&] { return run(argc, argv); });
}
