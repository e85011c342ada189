// Benchmark of the order analysis of a run-up record (issue #17): computed order tracking
// (tacho -> angle, resampling to the angle, order cuts of two orders, order map) and the
// waterfall of a record of 1e6 ... 1e7 samples. Goal (issue #17): 1e7 samples in < 2 s.
// Figures are recorded in docs/performance.md ("Order analysis").
//
// The record: a linear run-up 600 -> 6000 rpm at 51.2 kHz with orders 13 and 26 of the shaft and
// a 1 pulse/rev tacho; 32 samples per revolution, 8-revolution order blocks, waterfall blocks of
// 4096 samples with 50 % overlap, Hann.
#include <benchmark/benchmark.h>

#include <cmath>
#include <numbers>

#include "geardyn/signal/order_tracking.hpp"
#include "geardyn/signal/waterfall.hpp"

namespace {

using namespace geardyn;

struct Record {
  Eigen::VectorXd t, x, tacho;
};

Record run_up(Eigen::Index n) {
  const double fs = 51200.0;
  const double duration = static_cast<double>(n) / fs;
  const double n0 = 10.0, acc = 90.0 / duration;  // rev/s and rev/s^2
  Record r{Eigen::VectorXd(n), Eigen::VectorXd(n), Eigen::VectorXd(n)};
  for (Eigen::Index j = 0; j < n; ++j) {
    const double t = static_cast<double>(j) / fs;
    const double th = 2 * std::numbers::pi * (n0 * t + 0.5 * acc * t * t);
    r.t[j] = t;
    r.x[j] = std::cos(13 * th) + 0.5 * std::cos(26 * th + 0.3);
    r.tacho[j] = std::cos(th);
  }
  return r;
}

// Arg: samples. Order tracking from the tacho: pulses, angle, resampling, order cuts (2 orders)
// and the order map.
void BM_OrderTracking(benchmark::State& state) {
  const Record r = run_up(state.range(0));
  Eigen::VectorXd orders(2);
  orders << 13.0, 26.0;
  for (auto _ : state) {
    const Eigen::VectorXd pulses = signal::tacho_pulse_times(r.t, r.tacho, 0.0);
    const Eigen::VectorXd angle = signal::angle_from_pulse_times(r.t, pulses, 1);
    const signal::AngleDomainRecord rec = signal::resample_to_angle(r.t, r.x, angle, 64);
    const signal::OrderCuts cuts = signal::order_cuts(rec, orders, 8);
    const signal::OrderSpectra map = signal::order_spectra(rec, 8);
    benchmark::DoNotOptimize(cuts.amplitude.data());
    benchmark::DoNotOptimize(map.amplitude.data());
  }
  state.counters["samples"] = static_cast<double>(state.range(0));
}
BENCHMARK(BM_OrderTracking)
    ->Arg(1000000)
    ->Arg(3000000)
    ->Arg(10000000)
    ->Unit(benchmark::kMillisecond)
    ->Iterations(1);

// Arg: samples. The waterfall (4096-sample blocks, 50 % overlap) with block speeds from the
// tacho's angle.
void BM_Waterfall(benchmark::State& state) {
  const Record r = run_up(state.range(0));
  const Eigen::VectorXd angle =
      signal::angle_from_pulse_times(r.t, signal::tacho_pulse_times(r.t, r.tacho, 0.0), 1);
  signal::WaterfallOptions o;
  o.block_length = 4096;
  o.overlap = 0.5;
  for (auto _ : state) {
    const signal::Waterfall w = signal::waterfall_by_angle(r.t, r.x, angle, o);
    benchmark::DoNotOptimize(w.amplitude.data());
  }
  state.counters["samples"] = static_cast<double>(state.range(0));
}
BENCHMARK(BM_Waterfall)
    ->Arg(1000000)
    ->Arg(3000000)
    ->Arg(10000000)
    ->Unit(benchmark::kMillisecond)
    ->Iterations(1);

}  // namespace
