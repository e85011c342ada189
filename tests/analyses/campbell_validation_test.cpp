// Validation of the Campbell analysis: critical speeds of a Jeffcott rotor and of a gyroscopic
// disk, and shape tracking through a crossing, against closed-form results.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "geardyn/analyses/campbell.hpp"
#include "geardyn/assembly/system_builder.hpp"
#include "geardyn/core/error.hpp"
#include "support/rotor_models.hpp"

namespace geardyn::analyses {
namespace {

using C = model::Component;
constexpr double kPi = std::numbers::pi;

// Jeffcott rotor (see modal_test): omega_n = sqrt(k/m) = 316.227766 rad/s at every speed, so the
// synchronous line f = Omega / 2pi meets both lateral modes at Omega = omega_n, i.e.
// 3019.7527 rpm. f(Omega) is constant and the line is linear, so the interpolated crossing is
// exact up to rounding (1e-9).
TEST(Campbell, JeffcottCriticalSpeedEqualsNaturalFrequency) {
  const double m = 10.0, k = 1e6, zeta = 0.02;
  const auto model = test::jeffcott(m, k, 2.0 * zeta * std::sqrt(k * m));
  const auto system = assembly::build_system(model);
  analyses::CampbellSettings settings;
  settings.n_modes = 2;
  for (int i = 0; i <= 24; ++i) settings.speeds.push_back(i * 250.0 * 2 * kPi / 60.0);
  const CampbellResult r = run_campbell(model, settings, Context("campbell").with_system(&system));
  ASSERT_EQ(r.status, Status::Ok) << r.message;
  ASSERT_EQ(r.lines.size(), 1u);  // EO 1; no shafts, no meshes
  ASSERT_EQ(r.critical_speeds.size(), 2u);
  const double wn = 316.227766016838;
  for (const auto& cs : r.critical_speeds) {
    EXPECT_NEAR(cs.speed, wn, 1e-9 * wn);
    EXPECT_NEAR(cs.frequency_hz, wn / (2 * kPi), 1e-9 * wn);
    EXPECT_NEAR(cs.damping_ratio, zeta, 1e-10);
    EXPECT_EQ(cs.order, 1.0);
  }
  const AnalysisOutput out =
      campbell_output(model, settings, r, Context("campbell").with_system(&system));
  const Table* critical = nullptr;
  const Table* campbell = nullptr;
  for (const auto& t : out.tables) {
    if (t.name == "critical_speeds") critical = &t;
    if (t.name == "campbell") campbell = &t;
  }
  ASSERT_NE(critical, nullptr);
  ASSERT_NE(campbell, nullptr);
  EXPECT_NO_THROW(critical->validate());
  EXPECT_NO_THROW(campbell->validate());
  EXPECT_NEAR(critical->column("speed_rpm").numbers[0], wn * 60 / (2 * kPi), 1e-6);
  for (const char* name : {"mode", "order", "speed_rpm", "frequency_hz", "whirl", "damping_ratio"})
    EXPECT_TRUE(critical->has_column(name)) << name;
  for (const char* name :
       {"speed_rpm", "mode", "frequency_hz", "damping_ratio", "whirl", "mac", "ambiguous"})
    EXPECT_TRUE(campbell->has_column(name)) << name;
  EXPECT_EQ(campbell->rows(), 25u * 2u);
  ASSERT_GE(out.plots.size(), 2u);
  EXPECT_EQ(out.plots[0].name, "campbell");
}

// A spinning disk that tilts on an angular spring kt and twists on a torsional spring kr
// (translations fixed), Friswell et al. 2010, sec. 3.5, derivation in the eig tests:
//   tilt, forward / backward:  w = (+-Ip Omega + sqrt((Ip Omega)^2 + 4 Id kt)) / (2 Id)
//   torsion:                   w_t = sqrt(kr / Ip), independent of speed.
// Id = 0.02, Ip = 0.04, kt = 2e4, kr = 9e4: the tilt pair starts at 1000 rad/s, torsion sits at
// 1500 rad/s, and the forward mode crosses it at Omega = (Id w_t^2 - kt) / (Ip w_t) = 416.7
// rad/s. Sorting by frequency would swap identities there; shape tracking must not.
model::Model tilting_disk() {
  model::Model model;
  model.nodes.push_back(test::spinning_node("disk", 1.0));
  model::Disk d;
  d.node = "disk";
  d.mass = 3.0;
  d.diametral_inertia = 0.02;
  d.polar_inertia = 0.04;
  model.disks.push_back(d);
  model::Bearing b;
  b.node = "disk";
  b.stiffness = {test::diagonal6(0, 0, 0, 2e4, 2e4, 9e4)};
  model.bearings.push_back(b);
  model.constraints.push_back(test::fix("disk", {C::Ux, C::Uy, C::Uz}));
  return model;
}

TEST(Campbell, TrackingKeepsIdentityThroughACrossing) {
  const auto model = tilting_disk();
  const auto system = assembly::build_system(model);
  analyses::CampbellSettings settings;
  settings.n_modes = 3;
  for (int i = 0; i <= 20; ++i) settings.speeds.push_back(50.0 * i);  // 0..1000 rad/s
  const CampbellResult r = run_campbell(model, settings, Context("campbell").with_system(&system));
  ASSERT_EQ(r.status, Status::Ok) << r.message;
  ASSERT_EQ(r.tracks.size(), 3u);
  EXPECT_EQ(r.ambiguous_points, 0);

  const double Id = 0.02, Ip = 0.04, kt = 2e4, wt = 1500.0;
  int torsion_track = -1, forward_track = -1;
  for (int t = 0; t < 3; ++t) {
    const auto& last = r.tracks[static_cast<std::size_t>(t)].back();
    if (last.kind == ModeKind::Torsional) torsion_track = t;
    if (last.whirl == Whirl::Forward) forward_track = t;
  }
  ASSERT_GE(torsion_track, 0);
  ASSERT_GE(forward_track, 0);
  for (std::size_t i = 0; i < settings.speeds.size(); ++i) {
    const double Omega = settings.speeds[i];
    const auto& tor = r.tracks[static_cast<std::size_t>(torsion_track)][i];
    EXPECT_EQ(tor.kind, ModeKind::Torsional) << "speed " << Omega;
    EXPECT_NEAR(tor.frequency_hz * 2 * kPi, wt, 1e-9 * wt) << "speed " << Omega;
    EXPECT_NEAR(tor.mac, 1.0, 1e-12);
    const auto& fw = r.tracks[static_cast<std::size_t>(forward_track)][i];
    EXPECT_EQ(fw.kind, ModeKind::Lateral);
    const double a = Ip * Omega;
    const double w_fwd = (a + std::sqrt(a * a + 4 * Id * kt)) / (2 * Id);
    EXPECT_NEAR(fw.frequency_hz * 2 * kPi, w_fwd, 1e-9 * w_fwd) << "speed " << Omega;
    if (Omega > 0.0) {
      EXPECT_EQ(fw.whirl, Whirl::Forward) << "speed " << Omega;
    }
  }
  // Before the crossing the forward mode is below torsion, after it above: the track crossed.
  EXPECT_LT(r.tracks[static_cast<std::size_t>(forward_track)][8].frequency_hz,
            r.tracks[static_cast<std::size_t>(torsion_track)][8].frequency_hz);
  EXPECT_GT(r.tracks[static_cast<std::size_t>(forward_track)][9].frequency_hz,
            r.tracks[static_cast<std::size_t>(torsion_track)][9].frequency_hz);
}

// Critical speed of the backward tilt mode with EO 1: w_b(Omega) = Omega gives
// (Id + Ip) Omega^2 = kt, Omega = sqrt(kt / (Id + Ip)) = 577.35 rad/s. The forward mode never
// meets EO 1 (Ip > Id: a disk), torsion would at 1500 rad/s, outside the range. The tabulated
// speed is the linear interpolation between the bracketing speeds, checked exactly against the
// same interpolation of the closed-form w_b, and within 0.5 % of the true crossing (curvature
// of w_b over one 50 rad/s step).
TEST(Campbell, BackwardCriticalSpeedOfAGyroscopicDisk) {
  const auto model = tilting_disk();
  const auto system = assembly::build_system(model);
  analyses::CampbellSettings settings;
  settings.n_modes = 3;
  for (int i = 0; i <= 20; ++i) settings.speeds.push_back(50.0 * i);
  const CampbellResult r = run_campbell(model, settings, Context("campbell").with_system(&system));
  ASSERT_EQ(r.status, Status::Ok) << r.message;
  ASSERT_EQ(r.critical_speeds.size(), 1u);
  const auto& cs = r.critical_speeds[0];
  EXPECT_EQ(cs.whirl, Whirl::Backward);
  const double Id = 0.02, Ip = 0.04, kt = 2e4;
  auto w_b = [&](double Omega) {
    const double a = Ip * Omega;
    return (-a + std::sqrt(a * a + 4 * Id * kt)) / (2 * Id);
  };
  // The crossing is refined on the eigenvalue curve between the grid speeds 550 and 600 rad/s
  // (linear interpolation there was 2.3e-4 off): the closed form to 1e-10 relative (rounding of
  // a 3 x 3 problem and the 1e-13 stopping rule of the root-finder).
  const double exact = std::sqrt(kt / (Id + Ip));
  EXPECT_TRUE(cs.refined);
  EXPECT_NEAR(cs.speed, exact, 1e-10 * exact);
  EXPECT_NEAR(w_b(cs.speed), cs.speed, 1e-10 * exact);
}

}  // namespace
}  // namespace geardyn::analyses
