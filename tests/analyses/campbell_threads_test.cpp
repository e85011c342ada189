// Campbell sweeps on threads (issue 19). run_campbell solves the speeds in fixed chunks, each
// from one seeded solver state, and tracks them in order afterwards (campbell.hpp), so every
// result -- tracks, critical speeds, onsets, counters -- is the same bit for bit for any thread
// count; these tests compare 1, 2 and 3 threads exactly, on the projection path (the rotor of
// Friswell et al., "Dynamics of Rotating Machines", CUP 2010, Example 5.9.1, and the ROSS
// comparison rotor of bench/ross with free axial and torsional motion) and on the dense path.
#include <gtest/gtest.h>

#include <bit>
#include <cstdint>
#include <string>
#include <vector>

#include "geardyn/analyses/campbell.hpp"
#include "geardyn/analyses/model_file.hpp"
#include "geardyn/assembly/system_builder.hpp"
#include "geardyn/core/error.hpp"
#include "geardyn/linalg/blas_library.hpp"
#include "support/rotor_models.hpp"

namespace geardyn::analyses {
namespace {

constexpr double kRadPerRpm = 2.0 * 3.14159265358979323846 / 60.0;

// The comparison rotor of bench/ross/geardyn_models.py (`elements` Timoshenko elements of a
// 1.5 m x 50 mm steel shaft, disks of 280 and 350 mm at nodes elements/3 and 2 elements/3,
// bearings of 1e6 N/m at both ends with viscous damping `c`), with a campbell analysis over
// 0..4000 rpm. The bearings hold only the lateral motion: axial and torsional rigid-body roots.
std::string ross_rotor(int elements, double c, const std::string& analysis_keys = "") {
  std::string t =
      "version = 1\n[[materials]]\nname = \"steel\"\nyoungs_modulus = 211e9\n"
      "shear_modulus = 81.2e9\ndensity = 7810\n"
      "[[shafts]]\nname = \"shaft\"\nmaterial = \"steel\"\naxis = [0, 0, 1]\n"
      "[[shafts.elements]]\nlength = 1.5\nouter_diameter = 0.05\ndivisions = " +
      std::to_string(elements) + "\n";
  const int nodes[2] = {elements / 3, 2 * elements / 3};
  const char* outer[2] = {"0.28", "0.35"};
  for (int d = 0; d < 2; ++d)
    t += "[[disks]]\nname = \"disk" + std::to_string(d) + "\"\nnode = \"shaft." +
         std::to_string(nodes[d]) + "\"\nouter_diameter = " + outer[d] +
         "\ninner_diameter = 0.05\nthickness = 0.07\nmaterial = \"steel\"\n";
  for (int node : {0, elements})
    t += "[[bearings]]\nname = \"b" + std::to_string(node) + "\"\nnode = \"shaft." +
         std::to_string(node) + "\"\nkxx = 1e6\nkyy = 1e6\ncxx = " + std::to_string(c) +
         "\ncyy = " + std::to_string(c) + "\n";
  return t + "[[analyses]]\nname = \"campbell\"\ntype = \"campbell\"\nspeed_start_rpm = 0\n" +
         "speed_stop_rpm = 4000\nspeed_count = 100\nn_modes = 6\n" + analysis_keys;
}

struct Case {
  model::Model model;
  fe::LinearSystem system;
  CampbellSettings settings;
};

Case ross_case(int elements, double c) {
  Case k;
  k.model = parse_model(ross_rotor(elements, c), "ross.toml");
  k.settings = k.model.analyses[0].settings_of<CampbellSettings>();
  k.system = assembly::build_system(k.model);
  return k;
}

CampbellResult run(const Case& k, int threads, bool warm = true) {
  CampbellSettings s = k.settings;
  s.threads = threads;
  s.warm_start = warm;
  return run_campbell(k.model, s, Context("campbell").with_system(&k.system));
}

// Bit for bit (NaN included: a point without a mode is NaN in every run).
bool same(double a, double b) {
  return std::bit_cast<std::uint64_t>(a) == std::bit_cast<std::uint64_t>(b);
}
bool same(std::complex<double> a, std::complex<double> b) {
  return same(a.real(), b.real()) && same(a.imag(), b.imag());
}

void expect_identical(const CampbellResult& a, const CampbellResult& b) {
  EXPECT_EQ(a.status, b.status);
  EXPECT_EQ(a.method, b.method);
  EXPECT_EQ(a.total_operations, b.total_operations);
  EXPECT_EQ(a.refinement_solves, b.refinement_solves);
  EXPECT_EQ(a.projection_basis, b.projection_basis);
  EXPECT_EQ(a.projection_fallbacks, b.projection_fallbacks);
  EXPECT_EQ(a.rigid_body_roots, b.rigid_body_roots);
  EXPECT_EQ(a.ambiguous_points, b.ambiguous_points);
  EXPECT_TRUE(same(a.max_residual, b.max_residual));
  ASSERT_EQ(a.tracks.size(), b.tracks.size());
  for (std::size_t t = 0; t < a.tracks.size(); ++t)
    for (std::size_t i = 0; i < a.tracks[t].size(); ++i) {
      const TrackPoint &p = a.tracks[t][i], &q = b.tracks[t][i];
      EXPECT_TRUE(same(p.eigenvalue, q.eigenvalue)) << "track " << t << " speed " << i;
      EXPECT_TRUE(same(p.frequency_hz, q.frequency_hz) && same(p.damping_ratio, q.damping_ratio) &&
                  same(p.mac, q.mac) && same(p.residual, q.residual))
          << "track " << t << " speed " << i;
      EXPECT_TRUE(p.whirl == q.whirl && p.kind == q.kind && p.ambiguous == q.ambiguous)
          << "track " << t << " speed " << i;
    }
  ASSERT_EQ(a.critical_speeds.size(), b.critical_speeds.size());
  for (std::size_t k = 0; k < a.critical_speeds.size(); ++k) {
    const CriticalSpeed &p = a.critical_speeds[k], &q = b.critical_speeds[k];
    EXPECT_TRUE(p.mode == q.mode && p.line == q.line && p.refined == q.refined) << k;
    EXPECT_TRUE(same(p.speed, q.speed) && same(p.frequency_hz, q.frequency_hz) &&
                same(p.damping_ratio, q.damping_ratio))
        << k;
  }
  ASSERT_EQ(a.onsets.size(), b.onsets.size());
  for (std::size_t k = 0; k < a.onsets.size(); ++k) {
    const InstabilityOnset &p = a.onsets[k], &q = b.onsets[k];
    EXPECT_TRUE(p.mode == q.mode && p.refined == q.refined && p.whirl == q.whirl) << k;
    EXPECT_TRUE(same(p.speed, q.speed) && same(p.frequency_hz, q.frequency_hz) &&
                same(p.min_damping_ratio, q.min_damping_ratio))
        << k;
  }
}

// 1, 2 and 3 threads agree bit for bit; returns the one-thread result.
CampbellResult expect_any_thread_count_agrees(const Case& k, bool uses_system_blas) {
  const CampbellResult one = run(k, 1);
  EXPECT_EQ(one.threads_used, 1);
  // A sequential OpenBLAS is not safe from several threads: the solves that call it then run on
  // one thread, with a note (sweep_threads); the dense path never calls it.
  const bool safe = !uses_system_blas || linalg::safe_for_concurrent_calls(linalg::loaded_blas());
  for (int threads : {2, 3}) {
    SCOPED_TRACE(threads);
    const CampbellResult many = run(k, threads);
    EXPECT_EQ(many.threads_used, safe ? threads : 1);
    EXPECT_EQ(many.thread_note.empty(), safe);
    expect_identical(one, many);
  }
  return one;
}

TEST(CampbellThreads, ProjectionPathIsBitIdenticalForAnyThreadCount) {
  // Friswell's rotor in 24 elements (150 DOFs), 40 speeds: three chunks of speeds.
  Case k;
  k.model = test::friswell_591(24);
  k.system = assembly::build_system(k.model);
  k.settings.n_modes = 6;
  for (int i = 0; i < 40; ++i) k.settings.speeds.push_back(100.0 * i * kRadPerRpm);
  const CampbellResult r = expect_any_thread_count_agrees(k, true);
  ASSERT_EQ(r.status, Status::Ok) << r.message;
  EXPECT_EQ(r.method, "projected");
  EXPECT_FALSE(r.critical_speeds.empty());
}

TEST(CampbellThreads, FreeRotorWithRigidBodyRootsIsBitIdentical) {
  // The ROSS comparison rotor in 6 elements (42 DOFs: projection path), undamped as in the
  // benchmark, 100 speeds (7 chunks); axial and torsional rigid-body roots are found at the seed
  // and left out of the tracking the same way in every chunk.
  const Case k = ross_case(6, 0.0);
  const CampbellResult r = expect_any_thread_count_agrees(k, true);
  ASSERT_EQ(r.status, Status::Ok) << r.message;
  EXPECT_EQ(r.method, "projected");
  EXPECT_GT(r.rigid_body_roots, 0);
  EXPECT_FALSE(r.critical_speeds.empty());
}

TEST(CampbellThreads, DensePathIsBitIdenticalAndOnsetsToo) {
  // 3 elements (24 DOFs: the dense path, no system BLAS), damped bearings with cross-coupling
  // growing linearly with speed (a tabulated bearing, so the rigid-body test is built per speed):
  // the forward mode becomes unstable inside the range and its onset is refined by extra solves.
  Case k = ross_case(3, 100.0);
  for (model::Bearing& b : k.model.bearings) {
    b.speeds = {0.0, 4000.0 * kRadPerRpm};
    b.stiffness = {b.stiffness[0], b.stiffness[0]};
    b.stiffness[1][0 * 6 + 1] = 1e5;
    b.stiffness[1][1 * 6 + 0] = -1e5;
    b.damping = {b.damping[0], b.damping[0]};
  }
  k.system = assembly::build_system(k.model);
  ASSERT_FALSE(k.system.speed_bearings.empty());
  const CampbellResult r = expect_any_thread_count_agrees(k, false);
  ASSERT_EQ(r.status, Status::Ok) << r.message;
  EXPECT_EQ(r.method, "dense");
  ASSERT_FALSE(r.onsets.empty());
  EXPECT_TRUE(r.onsets[0].refined);
  EXPECT_FALSE(r.onsets[0].at_first_speed);
}

TEST(CampbellThreads, WarmAndColdStartAgreeWithRigidBodyRoots) {
  // The ROSS rotor in 48 elements (294 DOFs), 40 speeds. Warm (one basis per chunk, enriched
  // from speed to speed) and cold (every speed from scratch) hold every mode to the same
  // full-size checks (backward error <= 1e-8, preconditioned residual <= 1e-6); both are within
  // about 1e-10 of the dense solver (campbell_projection_test.cpp), hence 1e-10 between them
  // is the requirement, and the tracking must be the same.
  Case k = ross_case(48, 0.0);
  k.settings.speeds.resize(40);
  const CampbellResult warm = run(k, 2, true), cold = run(k, 1, false);
  ASSERT_EQ(warm.status, Status::Ok) << warm.message;
  ASSERT_EQ(cold.status, Status::Ok) << cold.message;
  EXPECT_EQ(warm.rigid_body_roots, cold.rigid_body_roots);
  ASSERT_EQ(warm.tracks.size(), cold.tracks.size());
  for (std::size_t t = 0; t < warm.tracks.size(); ++t)
    for (std::size_t i = 0; i < warm.tracks[t].size(); ++i) {
      const TrackPoint &p = warm.tracks[t][i], &q = cold.tracks[t][i];
      EXPECT_NEAR(p.frequency_hz, q.frequency_hz, 1e-10 * q.frequency_hz)
          << "track " << t << " speed " << i;
      EXPECT_EQ(p.kind, q.kind);
      EXPECT_EQ(p.ambiguous, q.ambiguous);
      // At rest the whirl directions are one double eigenvalue: the labels are the solver's.
      if (i > 0) {
        EXPECT_EQ(p.whirl, q.whirl) << "track " << t << " speed " << i;
      }
    }
}

TEST(CampbellThreads, ChunksDependOnSpeedsAndModelSizeOnly) {
  // A sixteenth of the speeds, at least 16, and at most 64 MiB of shapes per chunk: 9 candidate
  // shapes of 60006 complex entries (the 10000-element benchmark rotor) are 8.64 MB per speed,
  // so 7 speeds fit, below the minimum of 16; 6006 entries (1000 elements) give 77 speeds.
  EXPECT_EQ(campbell_chunk_speeds(100, 42, 9), 16u);
  EXPECT_EQ(campbell_chunk_speeds(1000, 42, 9), 63u);
  EXPECT_EQ(campbell_chunk_speeds(10000, 6006, 9), 77u);
  EXPECT_EQ(campbell_chunk_speeds(10000, 60006, 9), 16u);
  EXPECT_EQ(campbell_chunk_speeds(1, 42, 9), 16u);
}

// Records what run_campbell reports.
class RecordingProgress final : public Progress {
 public:
  void start(const std::string&, std::size_t total) override { total_ = total; }
  void update(std::size_t done) override { done_.push_back(done); }
  void finish() override { finished_ = true; }
  std::size_t total_ = 0;
  std::vector<std::size_t> done_;
  bool finished_ = false;
};

TEST(CampbellThreads, ProgressCountsEverySpeedOnThreads) {
  const Case k = ross_case(3, 100.0);
  CampbellSettings s = k.settings;
  s.threads = 2;
  RecordingProgress progress;
  run_campbell(k.model, s, Context("campbell").with_system(&k.system).with_progress(&progress));
  EXPECT_EQ(progress.total_, s.speeds.size());
  ASSERT_FALSE(progress.done_.empty());
  EXPECT_TRUE(std::is_sorted(progress.done_.begin(), progress.done_.end()));
  EXPECT_EQ(progress.done_.back(), s.speeds.size());
  EXPECT_TRUE(progress.finished_);
}

TEST(CampbellThreads, ThreadsKeyIsReadAndCheckedAtItsLine) {
  const model::Model m = parse_model(ross_rotor(3, 0.0, "threads = 2\n"), "ross.toml");
  EXPECT_EQ(m.analyses[0].settings_of<CampbellSettings>().threads, 2);
  EXPECT_EQ(parse_model(ross_rotor(3, 0.0), "ross.toml")
                .analyses[0]
                .settings_of<CampbellSettings>()
                .threads,
            1);
  const std::string text = ross_rotor(3, 0.0, "threads = \"x\"\n");
  const int line = static_cast<int>(std::count(text.begin(), text.end(), '\n'));
  try {
    (void)parse_model(text, "ross.toml");
    ADD_FAILURE() << "no InputError for threads = \"x\"";
  } catch (const InputError& e) {
    EXPECT_EQ(e.key_path(), "analyses[0].threads") << e.what();
    EXPECT_EQ(e.where().file, "ross.toml");
    EXPECT_EQ(e.where().line, line) << e.what();
    EXPECT_NE(e.expected().find("integer"), std::string::npos) << e.what();
    EXPECT_NE(e.found().find("x"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace geardyn::analyses
