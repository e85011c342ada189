// Campbell sweeps through the projected solver (issue 19): warm start (one basis kept and
// enriched over the sweep) against cold start (every speed from scratch) and against the full
// solver, on the rotor of Friswell et al., "Dynamics of Rotating Machines", CUP 2010,
// Example 5.9.1 (tests/support/rotor_models.hpp).
#include <gtest/gtest.h>

#include "geardyn/analyses/campbell.hpp"
#include "geardyn/assembly/system_builder.hpp"
#include "support/rotor_models.hpp"

namespace geardyn::analyses {
namespace {

constexpr double kRadPerRpm = 2.0 * 3.14159265358979323846 / 60.0;

CampbellResult sweep(const fe::LinearSystem& system, bool warm, EigenMethod method) {
  CampbellSettings settings;
  settings.n_modes = 6;
  for (int i = 0; i <= 20; ++i) settings.speeds.push_back(200.0 * i * kRadPerRpm);
  settings.warm_start = warm;
  settings.method = method;
  model::Model none;
  return run_campbell(none, settings, Context("campbell").with_system(&system));
}

// Same number of tracks, the same kind and whirl at every point, frequencies within `tol`
// relative; returns the largest difference.
double same_tracks(const CampbellResult& a, const CampbellResult& b, double tol) {
  EXPECT_EQ(a.tracks.size(), b.tracks.size());
  double worst = 0.0;
  for (std::size_t t = 0; t < std::min(a.tracks.size(), b.tracks.size()); ++t)
    for (std::size_t i = 0; i < a.tracks[t].size(); ++i) {
      const TrackPoint &p = a.tracks[t][i], &q = b.tracks[t][i];
      worst = std::max(worst, std::abs(p.frequency_hz - q.frequency_hz) / q.frequency_hz);
      EXPECT_EQ(p.kind, q.kind) << "track " << t << " speed " << i;
      // At rest an isotropic rotor's whirl directions are one double eigenvalue: any basis of
      // it is as good, so the labels there are the solver's choice.
      if (i > 0) {
        EXPECT_EQ(p.whirl, q.whirl) << "track " << t << " speed " << i;
      }
      EXPECT_EQ(p.ambiguous, q.ambiguous) << "track " << t << " speed " << i;
    }
  EXPECT_LT(worst, tol);
  return worst;
}

TEST(CampbellProjection, WarmAndColdStartAgree) {
  // 48 elements (294 DOFs). Warm and cold runs hold every mode to the same full-size tests
  // (backward error <= 1e-8, preconditioned residual rho <= 1e-6, so frequency errors of about
  // rho^2 = 1e-12): 1e-10 relative leaves a factor 100.
  const auto system = assembly::build_system(test::friswell_591(48));
  const CampbellResult warm = sweep(system, true, EigenMethod::Auto);
  const CampbellResult cold = sweep(system, false, EigenMethod::Auto);
  ASSERT_EQ(warm.status, Status::Ok) << warm.message;
  ASSERT_EQ(cold.status, Status::Ok) << cold.message;
  EXPECT_EQ(warm.method, "projected");
  EXPECT_EQ(warm.projection_fallbacks, 0) << warm.first_fallback;
  same_tracks(warm, cold, 1e-10);
  ASSERT_EQ(warm.critical_speeds.size(), cold.critical_speeds.size());
  for (std::size_t k = 0; k < warm.critical_speeds.size(); ++k)
    EXPECT_NEAR(warm.critical_speeds[k].speed, cold.critical_speeds[k].speed,
                1e-9 * cold.critical_speeds[k].speed);  // roots of curves known to 1e-12
}

TEST(CampbellProjection, SameAsTheFullSolver) {
  // The reference path (shift-invert Arnoldi on the full pencil, method sparse): the same tracks
  // and frequencies within 1e-8 relative (Arnoldi's own accuracy on this mesh is ~1e-9, measured
  // against the dense solver in docs/performance.md).
  const auto system = assembly::build_system(test::friswell_591(48));
  const CampbellResult projected = sweep(system, true, EigenMethod::Auto);
  const CampbellResult full = sweep(system, true, EigenMethod::Sparse);
  ASSERT_EQ(full.status, Status::Ok) << full.message;
  EXPECT_EQ(full.method, "sparse");
  EXPECT_EQ(full.projection_basis, 0);
  same_tracks(projected, full, 1e-8);
}

}  // namespace
}  // namespace geardyn::analyses
