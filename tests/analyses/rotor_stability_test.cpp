// Robustness of the rotor modal family (issue 14): rigid-body modes decided by shape on any mesh,
// instability reported (logarithmic decrement, onset speed), critical speeds refined on the
// eigenvalue curve, n_modes above the number of DOFs.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <complex>
#include <numbers>
#include <string>
#include <vector>

#include "geardyn/analyses/campbell.hpp"
#include "geardyn/analyses/modal.hpp"
#include "geardyn/assembly/system_builder.hpp"
#include "support/output_tables.hpp"
#include "support/rotor_models.hpp"

namespace geardyn::analyses {
namespace {

constexpr double kPi = std::numbers::pi;

using test::friswell_591;

std::vector<const Mode*> elastic(const std::vector<Mode>& modes) {
  std::vector<const Mode*> out;
  for (const Mode& m : modes)
    if (!m.rigid_body) out.push_back(&m);
  return out;
}

// The rigid-body limit used to be 1e-10 max K_ii / M_ii, which grows as 1/h^2 .. 1/h^4: at about
// 1500 elements the first lateral pair (86.66 rad/s) was reported as a 0 Hz rigid-body mode.
// Now the same rotor at 6, 60, 600 and 6000 elements has the same first modes, none rigid, and
// exactly its true rigid-body roots (axial translation and torsional spin: nothing holds them)
// labelled rigid at 0 Hz.
//
// Tolerances: Timoshenko elements converge fast; the 6-element model is 1.2e-6 (relative) from
// the 600-element one on the first pair and 2.1e-5 on the second (the book's own table is the
// 6-element model). The 6000-element model carries the rounding of a stiffness matrix whose
// condition grows as N^4 (about 1e16 here): 3e-7 relative, measured. Hence 3e-5 against 6
// elements, 1e-6 between 60, 600 and 6000 elements.
TEST(RigidBody, RefinedRotorKeepsItsFirstModesElastic) {
  std::vector<std::vector<double>> first;  // undamped frequencies of the first four elastic modes
  std::vector<std::vector<double>> complex_first;
  for (int elements : {6, 60, 600, 6000}) {
    SCOPED_TRACE(elements);
    const auto model = friswell_591(elements);
    const auto system = assembly::build_system(model);
    ModalSettings settings;
    settings.n_modes = 8;
    settings.speed = 4000.0 * 2 * kPi / 60;
    const ModalResult r = run_modal(model, settings, Context("modal").with_system(&system));
    ASSERT_EQ(r.status, Status::Ok) << r.message;
    // Two rigid-body motions (axial translation, torsional spin): two zero eigenvalues of the
    // undamped problem, each a double root lambda = 0 of the quadratic one.
    int rigid_undamped = 0;
    for (const Mode& m : r.undamped) {
      if (!m.rigid_body) continue;
      ++rigid_undamped;
      EXPECT_EQ(m.kind, ModeKind::Rigid);
      EXPECT_EQ(m.frequency_hz, 0.0);
    }
    EXPECT_EQ(rigid_undamped, 2);
    for (const Mode& m : r.complex) {
      if (m.rigid_body) {
        EXPECT_EQ(m.kind, ModeKind::Rigid);
        EXPECT_EQ(m.frequency_hz, 0.0);
        EXPECT_EQ(m.whirl, Whirl::None);
      } else {
        EXPECT_EQ(m.kind, ModeKind::Lateral) << m.frequency_hz;
        EXPECT_GT(m.frequency_hz, 13.0);
      }
    }
    const auto u = elastic(r.undamped), c = elastic(r.complex);
    ASSERT_GE(u.size(), 4u);
    ASSERT_GE(c.size(), 4u);
    first.push_back({});
    complex_first.push_back({});
    for (std::size_t i = 0; i < 4; ++i) {
      first.back().push_back(u[i]->frequency_hz);
      complex_first.back().push_back(c[i]->frequency_hz);
    }
  }
  // Friswell et al. 2010, Example 5.9.1, 4000 rpm: |lambda| = 85.389, 87.796, 251.785, 294.713.
  const double published[] = {85.389, 87.796, 251.785, 294.713};
  for (std::size_t i = 0; i < 4; ++i) {
    EXPECT_NEAR(complex_first[0][i] * 2 * kPi, published[i], 2e-5 * published[i]);
    for (std::size_t mesh = 0; mesh < 4; ++mesh) {
      const double tol = mesh == 0 ? 3e-5 : 1e-6;
      EXPECT_NEAR(first[mesh][i], first[3][i], tol * first[3][i])
          << "mode " << i << " mesh " << mesh;
      EXPECT_NEAR(complex_first[mesh][i], complex_first[3][i], tol * complex_first[3][i])
          << "mode " << i << " mesh " << mesh;
    }
  }
}

// The Campbell analysis on the 6000-element rotor tracks the same lowest modes as on the
// 6-element one (it used to drop the four lowest at 1e4 elements and say ok). Same tolerances.
TEST(RigidBody, RefinedRotorCampbellTracksTheLowestModes) {
  std::vector<double> lowest;
  for (int elements : {6, 6000}) {
    const auto model = friswell_591(elements);
    const auto system = assembly::build_system(model);
    CampbellSettings settings;
    settings.speeds = {0.0, 4000.0 * 2 * kPi / 60};
    settings.n_modes = 4;
    // Tracking only: no engine-order line crosses a mode here (each crossing would cost about
    // ten eigen-solves of the 36000-DOF model to refine).
    settings.engine_orders = {1e-3};
    settings.shaft_orders = false;
    const CampbellResult r = run_campbell(model, settings, Context("c").with_system(&system));
    ASSERT_EQ(r.status, Status::Ok) << r.message;
    EXPECT_GE(r.rigid_body_roots, 2) << elements;  // roots of the two double roots lambda = 0
    // The first pair starts as a double root at rest; at 4000 rpm it has split into backward
    // 85.389 and forward 87.796 rad/s (Friswell et al. 2010), in either track.
    const double a = r.tracks[0][1].frequency_hz, b = r.tracks[1][1].frequency_hz;
    lowest.push_back(std::min(a, b));
    EXPECT_NEAR(std::min(a, b) * 2 * kPi, 85.389, 3e-5 * 85.389) << elements;
    EXPECT_NEAR(std::max(a, b) * 2 * kPi, 87.796, 3e-5 * 87.796) << elements;
    for (const auto& track : r.tracks)
      for (const TrackPoint& p : track) EXPECT_GT(p.frequency_hz, 13.0) << elements;
  }
  EXPECT_NEAR(lowest[0], lowest[1], 3e-5 * lowest[1]);
}

// A free-free shaft (no bearing, no constraint): the six rigid-body motions of a free body are
// recognised on a coarse and on a fine mesh, and the first bending pair is elastic.
// Euler-Bernoulli free-free beam without rotary inertia (Blevins, "Formulas for Natural Frequency
// and Mode Shape", 1979, table 8-1): omega_1 = 4.730041^2 sqrt(EI / (rho A L^4)) (the constant
// to 7 digits: 1e-7 relative on omega). The 20-element model is 2.0e-6 above it (discretisation,
// O(h^4)): 5e-6; the 600-element model is within rounding of the N^4-conditioned stiffness
// (3e-7 measured on the rotor above): 2e-6. Finer free-free meshes are not tested: the quadratic
// eigen-solver then mixes the twelve zero roots (six Jordan pairs, whose rounding grows like the
// square root of eps ||K|| / ||M||) into spurious elastic-looking roots, a solver limitation.
TEST(RigidBody, FreeFreeShaftHasSixRigidBodyModes) {
  for (int elements : {20, 600}) {
    SCOPED_TRACE(elements);
    model::Model model;
    model.materials.push_back(test::friswell_steel());
    model::Shaft s;
    s.name = "shaft";
    s.material = "steel";
    s.theory = model::BeamTheory::EulerBernoulli;
    s.rotary_inertia = false;
    s.gyroscopic = false;
    for (int piece = 0; piece < 2; ++piece) {
      model::ShaftElement e;
      e.length = 0.75;
      e.outer_diameter = 0.05;
      e.divisions = elements / 2;
      s.elements.push_back(e);
    }
    model.shafts.push_back(s);
    const auto system = assembly::build_system(model);
    ModalSettings settings;
    settings.n_modes = 8;
    const ModalResult r = run_modal(model, settings, Context("modal").with_system(&system));
    ASSERT_EQ(r.status, Status::Ok) << r.message;
    int rigid = 0;
    for (const Mode& m : r.undamped) rigid += m.rigid_body ? 1 : 0;
    EXPECT_EQ(rigid, 6);
    const double EI = 211e9 * kPi * std::pow(0.05, 4) / 64, rhoA = 7810 * kPi * 0.05 * 0.05 / 4;
    const double w1 = 4.730041 * 4.730041 * std::sqrt(EI / (rhoA * std::pow(1.5, 4)));
    ASSERT_GE(r.undamped.size(), 8u);
    EXPECT_FALSE(r.undamped[6].rigid_body);
    const double tol = elements == 20 ? 5e-6 : 2e-6;
    EXPECT_NEAR(r.undamped[6].frequency_hz * 2 * kPi, w1, tol * w1);
    EXPECT_NEAR(r.undamped[7].frequency_hz * 2 * kPi, w1, tol * w1);
    // The complex modes: the rigid-body roots (double roots lambda = 0) are labelled rigid, the
    // bending pair is not.
    for (const Mode& m : r.complex) {
      if (m.rigid_body) {
        EXPECT_EQ(m.kind, ModeKind::Rigid);
      } else {
        EXPECT_NEAR(std::abs(m.eigenvalue), w1, tol * w1);
      }
    }
  }
}

}  // namespace
}  // namespace geardyn::analyses

namespace geardyn::analyses {
namespace {

// Jeffcott rotor with cross-coupled support stiffness q (kxy = q, kyx = -q), as a fluid-film
// bearing or seal gives: with z = x + i y the motion is m z'' + c z' + (k - i q) z = 0 and its
// conjugate, so the roots are those of m s^2 + c s + k -+ i q = 0 (Friswell et al., "Dynamics of
// Rotating Machines", 2010, sec. 3.6; J. M. Vance, "Rotordynamics of Turbomachinery", 1988,
// ch. 6). s = i w is a root when k = m w^2 and c w = q: the forward mode loses its damping at
// q = c w_n, w_n = sqrt(k / m).
model::Model cross_coupled_jeffcott(double m, double k, double c, double q) {
  auto model = test::jeffcott(m, k, c);
  model.bearings[0].stiffness[0][0 * 6 + 1] = q;
  model.bearings[0].stiffness[0][1 * 6 + 0] = -q;
  return model;
}

// The roots with Im s > 0 of m s^2 + c s + k -+ i q = 0, ascending |s|.
std::vector<std::complex<double>> cross_coupled_roots(double m, double k, double c, double q) {
  std::vector<std::complex<double>> roots;
  for (double sign : {1.0, -1.0}) {
    const std::complex<double> k_eff(k, -sign * q);
    const std::complex<double> root = std::sqrt(c * c - 4.0 * m * k_eff);
    for (const std::complex<double> s : {(-c + root) / (2 * m), (-c - root) / (2 * m)})
      if (s.imag() > 0) roots.push_back(s);
  }
  std::sort(roots.begin(), roots.end(), [](auto a, auto b) { return std::abs(a) < std::abs(b); });
  return roots;
}

double zeta_of(std::complex<double> s) { return -s.real() / std::abs(s); }

// q = 2 c w_n: one mode unstable. Its damping ratio and logarithmic decrement match the closed
// form to rounding of a 2 x 2 problem (1e-10), it is flagged in the table and in a note.
TEST(Instability, CrossCoupledJeffcottModesMatchClosedForm) {
  const double m = 10.0, k = 1e6, c = 200.0, wn = std::sqrt(k / m), q = 2.0 * c * wn;
  const auto model = cross_coupled_jeffcott(m, k, c, q);
  const auto system = assembly::build_system(model);
  ModalSettings settings;
  settings.n_modes = 2;
  settings.speed = 300.0;
  const ModalResult r = run_modal(model, settings, Context("modal").with_system(&system));
  ASSERT_EQ(r.status, Status::Ok) << r.message;
  ASSERT_EQ(r.complex.size(), 2u);
  const auto exact = cross_coupled_roots(m, k, c, q);
  ASSERT_EQ(exact.size(), 2u);
  std::vector<Mode> modes = r.complex;
  std::sort(modes.begin(), modes.end(), [](const Mode& a, const Mode& b) {
    return std::abs(a.eigenvalue) < std::abs(b.eigenvalue);
  });
  int unstable = 0;
  for (std::size_t i = 0; i < 2; ++i) {
    const double z = zeta_of(exact[i]);
    EXPECT_NEAR(modes[i].damping_ratio, z, 1e-10);
    EXPECT_NEAR(log_decrement(modes[i].damping_ratio), 2 * kPi * z / std::sqrt(1 - z * z), 1e-9);
    EXPECT_EQ(is_unstable(modes[i]), z < 0.0);
    unstable += z < 0.0 ? 1 : 0;
  }
  EXPECT_EQ(unstable, 1);
  const AnalysisOutput out =
      modal_output(model, settings, r, Context("modes").with_system(&system));
  const Table& t = test::table(out, "modes");
  int no = 0;
  for (std::size_t i = 0; i < t.rows(); ++i) {
    const bool is_no = t.column("stable").texts[i] == "no";
    no += is_no ? 1 : 0;
    EXPECT_EQ(is_no, t.column("damping_ratio").numbers[i] < 0.0);
    EXPECT_NEAR(t.column("log_decrement").numbers[i],
                log_decrement(t.column("damping_ratio").numbers[i]), 1e-15);
  }
  EXPECT_EQ(no, 1);
  ASSERT_FALSE(out.notes.empty());
  EXPECT_NE(out.notes[0].find("UNSTABLE"), std::string::npos) << out.notes[0];
  EXPECT_NE(out.notes[0].find("damping ratio"), std::string::npos) << out.notes[0];
}

// Cross-coupling growing with speed, q = a Omega (a tabulated bearing, linear between 0 and
// 2000 rad/s, so exact): the forward mode becomes unstable where a Omega = c w_n, i.e. at
// Omega* = c w_n / a = 700 rad/s. On a grid of 250 rad/s steps the onset is found between grid
// speeds to 1e-10 relative (the damping ratio is a smooth function of Omega and the roots of the
// 2 x 2 problem are exact to rounding), and the damping ratios on the grid match the closed form.
TEST(Instability, CampbellOnsetSpeedMatchesClosedForm) {
  const double m = 10.0, k = 1e6, c = 200.0, wn = std::sqrt(k / m), onset = 700.0;
  const double a = c * wn / onset;
  auto model = cross_coupled_jeffcott(m, k, c, 0.0);
  model::Bearing& b = model.bearings[0];
  b.speeds = {0.0, 2000.0};
  b.stiffness = {b.stiffness[0], b.stiffness[0]};
  b.stiffness[1][0 * 6 + 1] = a * 2000.0;
  b.stiffness[1][1 * 6 + 0] = -a * 2000.0;
  b.damping = {b.damping[0], b.damping[0]};
  const auto system = assembly::build_system(model);
  CampbellSettings settings;
  settings.n_modes = 2;
  for (int i = 0; i <= 6; ++i) settings.speeds.push_back(250.0 * i);
  const CampbellResult r = run_campbell(model, settings, Context("campbell").with_system(&system));
  ASSERT_EQ(r.status, Status::Ok) << r.message;
  ASSERT_EQ(r.onsets.size(), 1u);
  EXPECT_TRUE(r.onsets[0].refined);
  EXPECT_FALSE(r.onsets[0].at_first_speed);
  EXPECT_NEAR(r.onsets[0].speed, onset, 1e-10 * onset);
  EXPECT_NEAR(r.onsets[0].frequency_hz, wn / (2 * kPi), 1e-9 * wn);
  EXPECT_EQ(r.onsets[0].whirl, Whirl::Forward);
  EXPECT_NEAR(instability_onset_speed(r), onset, 1e-10 * onset);
  for (const auto& track : r.tracks)
    for (const TrackPoint& p : track) {
      const auto exact = cross_coupled_roots(m, k, c, a * p.speed);
      double nearest = 1e300;
      for (auto s : exact) nearest = std::min(nearest, std::abs(zeta_of(s) - p.damping_ratio));
      EXPECT_LT(nearest, 1e-10) << p.speed;
    }
  const AnalysisOutput out =
      campbell_output(model, settings, r, Context("campbell").with_system(&system));
  const Table& onsets = test::table(out, "instability");
  ASSERT_EQ(onsets.rows(), 1u);
  EXPECT_NEAR(onsets.column("onset_speed_rpm").numbers[0], onset * 60 / (2 * kPi), 1e-7);
  EXPECT_NE(out.notes[0].find("UNSTABLE"), std::string::npos) << out.notes[0];
  bool unstable_trace = false;
  for (const auto& t : out.plots[0].traces)
    unstable_trace = unstable_trace || t.name.find("UNSTABLE") != std::string::npos;
  EXPECT_TRUE(unstable_trace);
}

// Critical speeds of a spinning disk tilting on an angular spring kt and twisting on kr
// (Friswell et al. 2010, sec. 3.5): the backward tilt mode w_b = (-Ip W + sqrt((Ip W)^2 +
// 4 Id kt)) / (2 Id) meets the 1x line at W = sqrt(kt / (Id + Ip)); the forward one never does
// (Ip > Id); torsion, w_t = sqrt(kr / Ip), meets it at W = w_t. On a 400 rad/s grid the crossings
// are found on the eigenvalue curve to 1e-10 relative (the linear interpolation was 5e-3 off
// here), with the torsional crossing labelled torsional.
TEST(CriticalSpeeds, RefinedOnACoarseGridToClosedForm) {
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
  model.constraints.push_back(
      test::fix("disk", {model::Component::Ux, model::Component::Uy, model::Component::Uz}));
  const auto system = assembly::build_system(model);
  CampbellSettings settings;
  settings.n_modes = 3;
  for (int i = 0; i <= 5; ++i) settings.speeds.push_back(400.0 * i);
  const CampbellResult r = run_campbell(model, settings, Context("campbell").with_system(&system));
  ASSERT_EQ(r.status, Status::Ok) << r.message;
  ASSERT_EQ(r.critical_speeds.size(), 2u);
  const double backward = std::sqrt(2e4 / 0.06), torsion = std::sqrt(9e4 / 0.04);
  EXPECT_TRUE(r.critical_speeds[0].refined);
  EXPECT_NEAR(r.critical_speeds[0].speed, backward, 1e-10 * backward);
  EXPECT_NEAR(r.critical_speeds[0].frequency_hz, backward / (2 * kPi), 1e-10 * backward);
  EXPECT_EQ(r.critical_speeds[0].whirl, Whirl::Backward);
  EXPECT_EQ(r.critical_speeds[0].kind, ModeKind::Lateral);
  EXPECT_NEAR(r.critical_speeds[1].speed, torsion, 1e-10 * torsion);
  EXPECT_EQ(r.critical_speeds[1].kind, ModeKind::Torsional);
  const AnalysisOutput out =
      campbell_output(model, settings, r, Context("campbell").with_system(&system));
  const Table& cs = test::table(out, "critical_speeds");
  ASSERT_EQ(cs.rows(), 2u);
  EXPECT_EQ(cs.column("kind").texts[0], "lateral_backward");
  EXPECT_EQ(cs.column("kind").texts[1], "torsional");

  // refine_crossings = false: the linear interpolation of g = w_b(W) - W between the grid
  // speeds 400 and 800 rad/s (exact arithmetic on the closed form, to the 1e-12 of the
  // eigenvalues at the grid speeds).
  settings.refine_crossings = false;
  const CampbellResult lin =
      run_campbell(model, settings, Context("campbell").with_system(&system));
  ASSERT_EQ(lin.critical_speeds.size(), 2u);
  EXPECT_EQ(lin.refinement_solves, 0);
  EXPECT_FALSE(lin.critical_speeds[0].refined);
  auto w_b = [](double W) {
    const double a = 0.04 * W;
    return (-a + std::sqrt(a * a + 4 * 0.02 * 2e4)) / (2 * 0.02);
  };
  const double ga = w_b(400.0) - 400.0, gb = w_b(800.0) - 800.0;
  const double linear = 400.0 + 400.0 * ga / (ga - gb);
  EXPECT_NEAR(lin.critical_speeds[0].speed, linear, 1e-9 * linear);
  EXPECT_GT(std::abs(linear - backward), 1e-3 * backward);  // what the refinement gains here
}

// n_modes above what the model has (a 2-DOF Jeffcott rotor, 8 asked): the modes that exist are
// returned, status ok, and a note says how many exist.
TEST(FewerModes, MoreModesThanDofsReturnsThoseThatExist) {
  const auto model = test::jeffcott(10.0, 1e6, 10.0);
  const auto system = assembly::build_system(model);
  ModalSettings settings;
  settings.n_modes = 8;
  const ModalResult r = run_modal(model, settings, Context("modal").with_system(&system));
  EXPECT_EQ(r.status, Status::Ok) << r.message;
  EXPECT_EQ(r.undamped.size(), 2u);
  EXPECT_EQ(r.complex.size(), 2u);
  const AnalysisOutput out = modal_output(model, settings, r, Context("m").with_system(&system));
  EXPECT_EQ(out.status, Status::Ok);
  bool noted = false;
  for (const auto& n : out.notes)
    noted = noted || n.find("2 unconstrained DOFs") != std::string::npos;
  EXPECT_TRUE(noted);

  CampbellSettings cs;
  cs.n_modes = 8;
  cs.speeds = {0.0, 100.0};
  const CampbellResult c = run_campbell(model, cs, Context("c").with_system(&system));
  EXPECT_EQ(c.status, Status::Ok) << c.message;
  EXPECT_EQ(c.tracks.size(), 2u);
  EXPECT_FALSE(c.fewer_modes_note.empty());
}

}  // namespace
}  // namespace geardyn::analyses
