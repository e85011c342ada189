// Writes the stiffness and mass of the benchmark gear sector (the mesh of BM_SectorModes30/size:1
// in bench/solid_bench.cpp) as Matrix Market files, with geardyn's 30 lowest modes, for the
// comparison with scipy in bench/scipy_eigsh.py. Not a test; see docs/performance.md.
//
//   geardyn_export_matrices <folder> [global_size_m tooth_size_m]
//
// writes <folder>/K.mtx, <folder>/M.mtx (coordinate real symmetric) and <folder>/sector.json:
// sizes, the shift sigma = eig::automatic_shift(K, M) used by geardyn, geardyn's 30 lowest
// natural frequencies [Hz] and the wall and CPU time of its eigen-solve on this machine.
#include <fmt/format.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <exception>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <string>

#include "bench_sector.hpp"
#include "geardyn/core/units.hpp"
#include "geardyn/eig/symmetric_eigen.hpp"
#include "geardyn/meshgen/gear_sector.hpp"
#include "geardyn/meshio/matrix_market.hpp"
#include "geardyn/solid/assembly.hpp"

namespace {

using namespace geardyn;

double cpu_seconds() { return static_cast<double>(std::clock()) / CLOCKS_PER_SEC; }

}  // namespace

int main(int argc, char** argv) {
  if (argc != 2 && argc != 4) {
    std::fprintf(stderr, "usage: %s <folder> [global_size_m tooth_size_m]\n", argv[0]);
    return 2;
  }
  try {
    const std::filesystem::path folder = argv[1];
    const double global_size = argc == 4 ? std::stod(argv[2]) : bench::kFineSizes[0];
    const double tooth_size = argc == 4 ? std::stod(argv[3]) : bench::kFineSizes[1];
    std::filesystem::create_directories(folder);

    auto t0 = std::chrono::steady_clock::now();
    const solid::Mesh mesh = meshgen::gear_sector(bench::sector_params(global_size, tooth_size));
    const double mesh_s =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    solid::AssemblyOptions ao;
    ao.threads = 1;
    const solid::SolidSystem sys = solid::assemble(mesh, ao);
    std::printf("mesh %.1f s: %zu nodes, %zu elements; assembly %.2f s: %d DOFs, nnz(K) %ld\n",
                mesh_s, mesh.coords.size(), mesh.elements.size(), sys.seconds, sys.num_dofs(),
                static_cast<long>(sys.K.nonZeros()));

    const double sigma = eig::automatic_shift(sys.K, sys.M);
    eig::SymmetricEigenOptions eo;
    eo.n_modes = 30;
    eo.method = eig::Method::Sparse;
    const double c0 = cpu_seconds();
    t0 = std::chrono::steady_clock::now();
    const eig::SymmetricEigenResult r = eig::solve_symmetric(sys.K, sys.M, eo);
    const double eig_s =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    const double eig_cpu = cpu_seconds() - c0;
    std::printf("geardyn solve_symmetric: %.2f s wall, %.2f s CPU; %s\n", eig_s, eig_cpu,
                r.brief_report().c_str());
    if (r.status != Status::Ok) {
      std::fprintf(stderr, "eigen-solve failed: %s\n", r.message.c_str());
      return 1;
    }

    t0 = std::chrono::steady_clock::now();
    meshio::write_matrix_market(folder / "K.mtx", sys.K, true);
    meshio::write_matrix_market(folder / "M.mtx", sys.M, true);
    std::printf("matrices written in %.1f s\n",
                std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());

    std::string freqs;
    for (Eigen::Index i = 0; i < r.eigenvalues.size(); ++i)
      freqs += fmt::format("{}{:.17g}", i ? ", " : "",
                           units::rad_per_s_to_hz(std::sqrt(std::max(r.eigenvalues[i], 0.0))));
    std::ofstream json(folder / "sector.json");
    json << fmt::format(
        "{{\n  \"mesh\": \"gear sector 1/10, z = 40, m = 4.5 mm, tet10, global size {} m, tooth "
        "size {} m\",\n  \"nodes\": {},\n  \"elements\": {},\n  \"dofs\": {},\n  \"nnz_K\": {},\n"
        "  \"sigma\": {:.17g},\n  \"n_modes\": 30,\n  \"geardyn_seconds\": {:.4f},\n"
        "  \"geardyn_cpu_seconds\": {:.4f},\n  \"geardyn_factorization\": \"{}\",\n"
        "  \"geardyn_operations\": {},\n  \"geardyn_frequencies_hz\": [{}]\n}}\n",
        global_size, tooth_size, mesh.coords.size(), mesh.elements.size(), sys.num_dofs(),
        sys.K.nonZeros(), sigma, eig_s, eig_cpu, r.factorization, r.operations, freqs);
    if (!json) throw std::runtime_error("cannot write " + (folder / "sector.json").string());
    std::printf("sigma = %.17g; wrote %s\n", sigma, (folder / "sector.json").c_str());
    return 0;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "error: %s\n", e.what());
    return 1;
  }
}
