// Equivalent radiated power over speed (issue #17, performance list): ERP of a surface of ~1e5
// nodes at 1000 speeds from a reduced response of m = 100 ... 400 coordinates (goal < 10 s).
// Surface: the exterior of a 223 x 223 x 1 hex8 plate (100 352 surface nodes, 99 904 faces);
// recovery: a dense random 3n x m matrix (the content does not matter for the cost); one complex
// q per speed.
//   ErpOperator route: W = R_n^T diag(A) R_n built once (n m^2 flops), then q^H W q per speed.
//   Direct route: per speed expand u = R q on every surface node (3 n m), project on the normals,
//   sum A |v_n|^2 (what a straightforward post-processor does); timed on 20 speeds and scaled
//   to 1000 (the cost per speed does not depend on the speed).
// Counters: surface_s (exterior_surface of the mesh), build_s (W), per_speed_us, total_1000_s,
// wall-clock, and the same as CPU time of the thread (*_cpu_*), which a shared machine disturbs
// less.
#include <benchmark/benchmark.h>
#include <time.h>

#include <chrono>
#include <cmath>
#include <complex>
#include <numbers>

#include "geardyn/acoustics/radiation.hpp"
#include "geardyn/solid/structured_mesh.hpp"

namespace geardyn {
namespace {

double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

double thread_cpu_s() {  // CPU time of this thread: robust on a shared machine
  timespec t{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

struct Case {
  solid::Mesh mesh;
  acoustics::Surface surface;
  double surface_s = 0;
};

const Case& plate_case() {
  static const Case c = [] {
    Case k;
    k.mesh = solid::box_mesh(Eigen::Vector3d::Zero(), Eigen::Vector3d(0.5, 0.5, 0.005), 223, 223, 1,
                             solid::ElementType::Hex8, {"steel", 1, 2.1e11, 0.3, 7850, {}});
    const auto start = std::chrono::steady_clock::now();
    k.surface = acoustics::exterior_surface(k.mesh);
    k.surface_s = seconds_since(start);
    return k;
  }();
  return c;
}

Eigen::VectorXcd speed_response(int m, int speed) {  // a smooth, speed-dependent q
  Eigen::VectorXcd q(m);
  for (int k = 0; k < m; ++k) q[k] = std::polar(1e-6 / (1 + k), 0.01 * speed * (k + 1));
  return q;
}

void BM_ErpOperator1000Speeds(benchmark::State& state) {
  const Case& c = plate_case();
  const int m = static_cast<int>(state.range(0));
  const Eigen::MatrixXd R = Eigen::MatrixXd::Random(3 * c.surface.num_nodes(), m);
  const acoustics::Air air;
  double build = 0, speeds = 0, build_cpu = 0, speeds_cpu = 0, sum = 0;
  for (auto _ : state) {
    auto start = std::chrono::steady_clock::now();
    double cpu = thread_cpu_s();
    const acoustics::ErpOperator op(c.surface, R);
    build = seconds_since(start);
    build_cpu = thread_cpu_s() - cpu;
    start = std::chrono::steady_clock::now();
    cpu = thread_cpu_s();
    for (int s = 0; s < 1000; ++s)
      sum += op.power(speed_response(m, s), 2 * std::numbers::pi * (100 + s), air);
    speeds = seconds_since(start);
    speeds_cpu = thread_cpu_s() - cpu;
  }
  benchmark::DoNotOptimize(sum);
  state.counters["surface_nodes"] = c.surface.num_nodes();
  state.counters["surface_s"] = c.surface_s;
  state.counters["build_s"] = build;
  state.counters["per_speed_us"] = 1e6 * speeds / 1000;
  state.counters["total_1000_s"] = build + speeds;
  state.counters["build_cpu_s"] = build_cpu;
  state.counters["per_speed_cpu_us"] = 1e6 * speeds_cpu / 1000;
  state.counters["total_1000_cpu_s"] = build_cpu + speeds_cpu;
}
BENCHMARK(BM_ErpOperator1000Speeds)
    ->Arg(100)
    ->Arg(200)
    ->Arg(400)
    ->Unit(benchmark::kSecond)
    ->Iterations(1)
    ->UseRealTime();

void BM_ErpDirect1000Speeds(benchmark::State& state) {
  const Case& c = plate_case();
  const int m = static_cast<int>(state.range(0));
  const Eigen::MatrixXd R = Eigen::MatrixXd::Random(3 * c.surface.num_nodes(), m);
  const acoustics::Air air;
  constexpr int kSpeeds = 20;
  double speeds = 0, speeds_cpu = 0, sum = 0;
  for (auto _ : state) {
    const auto start = std::chrono::steady_clock::now();
    const double cpu = thread_cpu_s();
    Eigen::MatrixXd Q(m, 2), U;
    for (int s = 0; s < kSpeeds; ++s) {
      const Eigen::VectorXcd q = speed_response(m, s);
      Q.col(0) = q.real();
      Q.col(1) = q.imag();
      U.noalias() = R * Q;  // one pass over R for the real and imaginary parts
      Eigen::VectorXcd u(R.rows());
      u.real() = U.col(0);
      u.imag() = U.col(1);
      const double omega = 2 * std::numbers::pi * (100 + s);
      sum += acoustics::erp(c.surface, acoustics::normal_velocity(c.surface, u, omega), air);
    }
    speeds = seconds_since(start);
    speeds_cpu = thread_cpu_s() - cpu;
  }
  benchmark::DoNotOptimize(sum);
  state.counters["surface_nodes"] = c.surface.num_nodes();
  state.counters["per_speed_us"] = 1e6 * speeds / kSpeeds;
  state.counters["total_1000_s"] = speeds * 1000 / kSpeeds;
  state.counters["per_speed_cpu_us"] = 1e6 * speeds_cpu / kSpeeds;
  state.counters["total_1000_cpu_s"] = speeds_cpu * 1000 / kSpeeds;
}
BENCHMARK(BM_ErpDirect1000Speeds)
    ->Arg(100)
    ->Arg(200)
    ->Arg(400)
    ->Unit(benchmark::kSecond)
    ->Iterations(1)
    ->UseRealTime();

}  // namespace
}  // namespace geardyn
