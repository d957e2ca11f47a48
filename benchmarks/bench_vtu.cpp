// Writing a scene frame as .vtu in each encoding (io/vtu_writer.hpp VtuFormat):
// a P2 tetrahedral box mesh with a frame's fields (displacement and velocity per
// node, one density per cell), ~1e5 and ~1e6 unknowns (3 per node). Counters:
// bytes = the file's size, bytes_per_s = bytes written per second. What it
// answers: the size and write-time ratios of ascii : binary : zlib, i.e. what
// `hofem run --vtu-format` costs per frame. Files go to the temporary directory
// and are removed. The real time (reported) includes the fsync that makes each
// frame durable before its rename (io/atomic_file), so it depends on the disk;
// the CPU time is the encoding and the copy into the page cache.
#include "io/vtu_writer.hpp"
#include "mesh/box_mesh.hpp"

#include <benchmark/benchmark.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <string>

namespace {

using hofem::VtuFormat;

// Smooth fields like a deforming body's: compressible as real frames are, not
// constant (which zlib would shrink to nothing) and not random.
std::vector<hofem::VtuField> point_fields(const hofem::Mesh& mesh) {
  Eigen::MatrixXd u(3, mesh.num_nodes()), v(3, mesh.num_nodes());
  for (int i = 0; i < mesh.num_nodes(); ++i) {
    const Eigen::Vector3d x = mesh.nodes.col(i);
    u.col(i) = 0.01 * Eigen::Vector3d(std::sin(3 * x.y()), std::cos(2 * x.z()) * x.x(), x.x() * x.y());
    v.col(i) = 0.3 * Eigen::Vector3d(std::cos(x.z()), x.y() * x.y(), std::sin(5 * x.x()));
  }
  return {{"displacement", u}, {"velocity", v}};
}

void BM_WriteVtu(benchmark::State& state, int n, VtuFormat format) {
  const hofem::Mesh mesh = hofem::box_mesh(hofem::unit_cube(n), hofem::CellType::Tetrahedron, 2);
  const auto points = point_fields(mesh);
  Eigen::MatrixXd density(1, mesh.num_elements());
  for (int e = 0; e < mesh.num_elements(); ++e) density(0, e) = 1.0 + 1e-3 * std::sqrt(static_cast<double>(e));
  const std::string path = (std::filesystem::temp_directory_path() /
                            ("hofem_bench_" + std::to_string(::getpid()) + ".vtu")).string();
  for (auto _ : state) hofem::write_vtu(path, mesh, points, {{"strain_energy_density", density}}, format);
  const auto bytes = static_cast<double>(std::filesystem::file_size(path));
  std::filesystem::remove(path);
  state.counters["unknowns"] = 3.0 * mesh.num_nodes();
  state.counters["bytes"] = bytes;
  state.counters["bytes_per_s"] = benchmark::Counter(bytes, benchmark::Counter::kIsIterationInvariantRate);
}

// Names: BM_WriteVtu/tet/order:2/n:N/format:F (benchmark, cell, then parameter:value,
// as bench_foundation.cpp names its benchmarks). n = 16: 35,937 nodes, 107,811
// unknowns; n = 34: 328,509 nodes, 985,527 unknowns.
const bool registered = [] {
  for (int n : {16, 34})
    for (VtuFormat f : {VtuFormat::ascii, VtuFormat::binary, VtuFormat::zlib})
      benchmark::RegisterBenchmark(("BM_WriteVtu/tet/order:2/n:" + std::to_string(n) + "/format:" +
                                    std::string(hofem::to_string(f))).c_str(),
                                   BM_WriteVtu, n, f)
          ->Unit(benchmark::kMillisecond)
          ->UseRealTime();
  return true;
}();

}  // namespace
