// The gear tooth-contact element (elements/gear_mesh_contact.hpp, docs/theory.md §16.6):
//   * its force-approach law reproduces the map's points exactly and a one-force map is the
//     linear mesh F = k(theta) (delta - e_g(theta)) (the STE relation k = F_s / (e - e_g) of
//     A. Durastante, "Simulation of the Dynamic Response of Aeronautical Gears Equipped with
//     Damper Rings", MSc thesis, Politecnico di Torino, 2018, sec. 3.1-3.2);
//   * analytic tangents (2 x 2, including the pinion-angle column) against central differences
//     with every law, on both flanks and in the dead zone; periodicity in the pinion angle;
//   * backlash: no force inside the play on either flank, and a free rattle of two inertias
//     through it with an undamped linear law conserves the energy (the backlash oscillator of
//     A. Kahraman, R. Singh, "Non-linear dynamics of a spur gear pair", J. Sound Vib. 142, 1990,
//     without excitation).
#include "geardyn/elements/gear_mesh_contact.hpp"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <memory>
#include <numbers>
#include <vector>

namespace {

using namespace geardyn::elements;
using geardyn::InputError;
constexpr double kPi = std::numbers::pi;

// A map of z1 = 20 (period 2 pi / 20) on N = 16 angles: e_g = 2 um sin(theta z1) + 1 um,
// k_i = 4e8 (1 + 0.3 cos(theta z1)) N/m, three forces with a stiffening law
// a_j = F_j / (k_i (1 + 0.2 j)) (a concave approach-force curve, as the LTCA's).
std::shared_ptr<MeshForceMap> test_map(int forces = 3) {
  auto m = std::make_shared<MeshForceMap>();
  const int n = 16, z1 = 20;
  m->period_rad = 2.0 * kPi / z1;
  m->source = "test map";
  const std::array<double, 3> f{1000.0, 2000.0, 4000.0};
  for (int j = 0; j < forces; ++j) m->forces_n.push_back(f[static_cast<std::size_t>(j)]);
  m->approach_m.assign(static_cast<std::size_t>(forces), std::vector<double>(n));
  for (int i = 0; i < n; ++i) {
    const double phase = 2.0 * kPi * i / n;
    const double eg = 2e-6 * std::sin(phase) + 1e-6;
    const double k = 4e8 * (1.0 + 0.3 * std::cos(phase));
    m->unloaded_te_m.push_back(eg);
    for (int j = 0; j < forces; ++j)
      m->approach_m[static_cast<std::size_t>(j)][static_cast<std::size_t>(i)] =
          eg + m->forces_n[static_cast<std::size_t>(j)] / (k * (1.0 + 0.2 * j));
  }
  m->reference = forces > 1 ? 1 : 0;
  return m;
}

Eigen::VectorXd vec(double a, double b) {
  Eigen::VectorXd x(2);
  x << a, b;
  return x;
}

double force(const GearMeshContact& c, double delta, double theta, double v = 0.0, double w = 0.0) {
  ElementForce out;
  c.evaluate(vec(delta, theta), vec(v, w), 0.0, out);
  return out.force(0);
}

// Newton on F(delta, theta) = target from delta = e_g + target / k_mean.
double solve_approach(const GearMeshContact& c, double theta, double target) {
  double delta = c.unloaded_te(theta) + target / c.map().mean_stiffness();
  ElementForce out;
  for (int it = 0; it < 50; ++it) {
    c.evaluate(vec(delta, theta), vec(0.0, 0.0), 0.0, out);
    const double r = out.force(0) - target;
    if (std::abs(r) < 1e-13 * target) return delta;
    delta -= r / out.stiffness(0, 0);
  }
  ADD_FAILURE() << "Newton did not converge";
  return delta;
}

// At the grid angles the law passes through the map's points: F(d_j) = F_j, so the static
// solution for F_j is d_j; the law is piecewise linear, so Newton converges to rounding
// (1e-12 relative on the approach, ~1e-17 m of ~1e-5 m).
TEST(GearMeshContact, StaticSolutionReproducesTheMapAtItsForces) {
  const auto map = test_map();
  const GearMeshContact c("mesh", map, {});
  for (int i = 0; i < map->angles(); ++i) {
    const double theta = map->angle(i) + 7.0 * map->period_rad;
    for (std::size_t j = 0; j < map->forces_n.size(); ++j) {
      const double d = map->approach_m[j][static_cast<std::size_t>(i)];
      EXPECT_NEAR(force(c, d, theta) / map->forces_n[j], 1.0, 1e-12) << i << " " << j;
      EXPECT_NEAR(solve_approach(c, theta, map->forces_n[j]) / d, 1.0, 1e-12) << i << " " << j;
    }
    // Beyond the last force: the last slope extrapolated (linear, exact to rounding).
    const double d2 = map->approach_m[2][static_cast<std::size_t>(i)];
    const double d1 = map->approach_m[1][static_cast<std::size_t>(i)];
    const double slope = (4000.0 - 2000.0) / (d2 - d1);
    EXPECT_NEAR(force(c, d2 + 1e-6, theta) / (4000.0 + slope * 1e-6), 1.0, 1e-12);
  }
}

// One force: F = k(theta) (delta - e_g(theta)) with k = F_1 / (d_1 - e_g), at the nodes and,
// between them, with k and e_g interpolated linearly (the equal-penetration interpolation).
TEST(GearMeshContact, OneForceMapIsTheLinearMeshOfTheSte) {
  const auto map = test_map(1);
  const GearMeshContact c("mesh", map, {});
  for (int i = 0; i < map->angles(); ++i) {
    for (double frac : {0.0, 0.37}) {
      const double theta = map->angle(i) + frac * map->period_rad / map->angles();
      const auto i1 = static_cast<std::size_t>((i + 1) % map->angles());
      const auto i0 = static_cast<std::size_t>(i);
      const double k = (1.0 - frac) * map->stiffness_at_node(i) +
                       frac * map->stiffness_at_node(static_cast<int>(i1));
      const double eg = (1.0 - frac) * map->unloaded_te_m[i0] + frac * map->unloaded_te_m[i1];
      EXPECT_NEAR(c.unloaded_te(theta), eg, 1e-12 * 3e-6);
      for (double p : {1e-7, 3e-6, 2e-5})
        EXPECT_NEAR(force(c, eg + p, theta) / (k * p), 1.0, 1e-9) << i << " " << p;
      // Inverse: 1e-9 is the rounding of e_g + p against p for p = 1e-7 (e_g ~ 3e-6: 3e-9
      // absolute digits of 1e-7 lost ~ 1e-16 * 3e-6 / 1e-7 = 3e-15), comfortably above it.
    }
  }
  // The constant-stiffness map (no gear pair): F = k delta at any angle.
  const auto constant =
      std::make_shared<MeshForceMap>(MeshForceMap::constant_stiffness(3e8, 2.0 * kPi / 17));
  const GearMeshContact lin("mesh", constant, {});
  for (double theta : {0.0, 0.1, 5.3, -2.0})
    EXPECT_NEAR(force(lin, 2e-5, theta) / (3e8 * 2e-5), 1.0, 1e-12);
}

// Reducing theta1 modulo the period: angles of 1e4 rad and 1e4 periods on. The reduction
// x - floor(x) of x = theta / period ~ 3e5 loses ~ 1e-16 x = 3e-11 of a period (2e-12 rad);
// with dF/dtheta ~ k e_g' ~ 4e8 * 2e-6 * 20 ~ 2e4 N/rad that is 4e-8 N of F ~ 1e3 N: 1e-9.
TEST(GearMeshContact, PeriodicInThePinionAngleForLargeAngles) {
  const auto map = test_map();
  const GearMeshContact c("mesh", map, {});
  for (double theta : {0.0123, 0.2, 1.0}) {
    const double d = c.unloaded_te(theta) + 4e-6;
    const double f0 = force(c, d, theta);
    for (double turns : {1.0, 1e4, std::round(1e4 / map->period_rad), -1e4})
      EXPECT_NEAR(force(c, d, theta + turns * map->period_rad) / f0, 1.0, 1e-9)
          << theta << " " << turns;
  }
  EXPECT_NEAR(force(c, 1e-5, 1e4) / force(c, 1e-5, 1e4 - 1e3 * map->period_rad), 1.0, 1e-9);
}

// Tangents vs central differences (h = 1e-11 on delta and theta, both within one segment of
// the piecewise law: p is at least 2e-7 m from every knot and theta 0.3 of a grid spacing from
// its nodes, so the differences of the bilinear parts are exact to round-off ~ 1e-16 F / h
// ~ 1e-2 N/m against stiffnesses ~ 1e8 N/m; the Hertz and IMPACT powers add a truncation
// (h / p)^2 ~ 1e-8). Rates differenced with 1e-6 m/s (linear in the rate but for the
// penalty law's |v|^m2, exact to (h_v / v)^2 = 1e-8 with v ~ 1e-2).
TEST(GearMeshContact, TangentsMatchCentralDifferencesWithEveryLaw) {
  const auto map = test_map();
  const double b = 5e-5;
  const double theta =
      map->angle(3) + 0.3 * map->period_rad / map->angles() + 11.0 * map->period_rad;
  std::vector<std::pair<std::string, std::shared_ptr<const ContactLaw>>> laws = {
      {"map", nullptr},
      {"linear", std::make_shared<LinearContactLaw>(LinearLawParameters{4e8, 2e3})},
      {"hertz", std::make_shared<HertzContactLaw>(HertzLawParameters{1e11, 1.5, 0.2})},
      {"impact", std::make_shared<ImpactContactLaw>(ImpactLawParameters{1e11, 1.5, 3e3, 1e-5})},
      {"penalty", std::make_shared<PenaltyContactLaw>(
                      PenaltyLawParameters{1e10, 1.2, 5e4, 0.8, 0.5, 1e-9, 1e-6})}};
  for (const auto& [name, law] : laws) {
    for (bool vary : {true, false}) {
      GearMeshContactOptions o;
      o.backlash = b;
      o.law = law;
      o.vary_stiffness = vary;
      o.damping = law ? 0.0 : 1.5e3;
      const GearMeshContact c("mesh", map, o);
      const double eg = c.unloaded_te(theta);
      // drive: p between the first two knots (a_1 ~ 2.5e-6, a_2 ~ 4e-6 here) and beyond;
      // back: p_b the same; dead zone: the middle of the play.
      for (double delta : {eg + 1.3e-6, eg + 3.3e-6, eg + 1.1e-5, eg - b - 1.3e-6, eg - b - 1.1e-5,
                           eg - 0.5 * b}) {
        const Eigen::VectorXd u = vec(delta, theta), v = vec(0.013, 37.0);
        const TangentCheck t = check_tangents(c, u, v, 0.0, 1e-11, 1e-6, 1.0);
        EXPECT_LT(t.stiffness_error, 1e-6) << name << " vary " << vary << " delta " << delta;
        EXPECT_LT(t.damping_error, 1e-6) << name << " vary " << vary << " delta " << delta;
        // The theta column alone (it is ~1e-6 of the delta column, so check it on its own
        // scale; its terms partly cancel, down to ~ 300 N/rad): h = 1e-7 rad, inside the grid
        // interval (0.3 of a spacing of 0.02 rad from its node), where the map's law is linear
        // in theta (exact differences) and the powers' truncation is (h e_g' / p)^2 < 1e-11;
        // round-off 1e-16 F / h ~ 5e-6 N/rad with F ~ 5e3 N: 2e-8 of 300 N/rad.
        ElementForce at, plus, minus;
        c.evaluate(u, v, 0.0, at);
        c.evaluate(vec(delta, theta + 1e-7), v, 0.0, plus);
        c.evaluate(vec(delta, theta - 1e-7), v, 0.0, minus);
        const double fd = (plus.force(0) - minus.force(0)) / 2e-7;
        EXPECT_NEAR(at.stiffness(0, 1), fd, 1e-6 * std::max(std::abs(fd), 1.0))
            << name << " vary " << vary << " delta " << delta;
      }
      // The pinion-angle column is there in contact (the map's angle dependence) ...
      ElementForce out;
      c.evaluate(vec(eg + 3.3e-6, theta), vec(0.0, 0.0), 0.0, out);
      if (law == nullptr || vary) {
        EXPECT_GT(std::abs(out.stiffness(0, 1)), 1e3) << name;
      }
      EXPECT_EQ(out.force(1), 0.0);
      EXPECT_EQ(out.stiffness(1, 0), 0.0);
      // ... and everything is zero in the dead zone.
      c.evaluate(vec(eg - 0.5 * b, theta), vec(0.1, 37.0), 0.0, out);
      EXPECT_EQ(out.force.cwiseAbs().maxCoeff(), 0.0);
      EXPECT_EQ(out.stiffness.cwiseAbs().maxCoeff(), 0.0);
      EXPECT_EQ(out.damping.cwiseAbs().maxCoeff(), 0.0);
    }
  }
}

// The elastic part of a law scaled by s = k(theta) / mean k: a linear law gives
// F = s k p + c p_dot; with a constant map s = 1 and nothing changes.
TEST(GearMeshContact, VaryStiffnessScalesTheElasticPartOnly) {
  const auto map = test_map();
  GearMeshContactOptions o;
  o.law = std::make_shared<LinearContactLaw>(LinearLawParameters{4e8, 2e3});
  const GearMeshContact c("mesh", map, o);
  double mean = 0.0;
  for (int i = 0; i < map->angles(); ++i) {
    const double s = c.stiffness_ratio(map->angle(i));
    EXPECT_NEAR(s, map->stiffness_at_node(i) / map->mean_stiffness(), 1e-14);
    mean += s / map->angles();
    const double eg = map->unloaded_te_m[static_cast<std::size_t>(i)];
    EXPECT_NEAR(force(c, eg + 2e-6, map->angle(i), 0.01, 0.0), s * 4e8 * 2e-6 + 2e3 * 0.01,
                1e-12 * 1e3);
  }
  EXPECT_NEAR(mean, 1.0, 1e-14);
}

// Backlash b: no force for -b < p < 0 (drive flank open and back flank open), drive contact
// pushes delta back (+), back-flank contact pulls (-), and state() says which.
TEST(GearMeshContact, BacklashDeadZoneOnBothFlanks) {
  const auto map = test_map();
  const double b = 4e-5;
  for (bool map_law : {true, false}) {
    GearMeshContactOptions o;
    o.backlash = b;
    if (!map_law) o.law = std::make_shared<HertzContactLaw>(HertzLawParameters{1e11, 1.5, 0.0});
    const GearMeshContact c("mesh", map, o);
    for (double theta : {0.0, 0.05, 0.31, 100.0}) {
      const double eg = c.unloaded_te(theta);
      for (double p = -b + 1e-9; p < 0.0; p += b / 37.0) {
        EXPECT_EQ(force(c, eg + p, theta, 0.3, 10.0), 0.0) << p;
        EXPECT_EQ(c.state(vec(eg + p, theta)), MeshContactState::separated);
      }
      EXPECT_GT(force(c, eg + 1e-7, theta), 0.0);
      EXPECT_EQ(c.state(vec(eg + 1e-7, theta)), MeshContactState::drive);
      EXPECT_LT(force(c, eg - b - 1e-7, theta), 0.0);
      EXPECT_EQ(c.state(vec(eg - b - 1e-7, theta)), MeshContactState::back);
      // mirror: the back flank's force at p_b is minus the drive flank's at p
      EXPECT_NEAR(force(c, eg - b - 3e-6, theta), -force(c, eg + 3e-6, theta), 1e-9);
    }
  }
  // Without a backlash the back flank never touches.
  const GearMeshContact open("mesh", map, {});
  EXPECT_EQ(force(open, -1.0, 0.1), 0.0);
  EXPECT_EQ(open.state(vec(-1.0, 0.1)), MeshContactState::separated);
}

// A free rattle of two inertias through the backlash (J1 = 0.01, J2 = 0.03 kg m^2, r1 = 30,
// r2 = 60 mm, common speed 100 rad/s, relative speed 0.1 m/s along the line of action), an
// undamped linear mesh k = 1e8 N/m of constant stiffness and b = 0.1 mm: the energy
// (1/2) J1 w1^2 + (1/2) J2 w2^2 + (1/2) k p^2 (either flank) is conserved. RK4 with
// h = t_c / 2000 (t_c = pi sqrt(m_e / k) the contact time): away from the contact kinks the
// error is O((omega h)^4) = 6e-12 per contact; a step that crosses a kink of the force's slope
// is only first-order accurate in that slope, an energy error O((omega h)^3) = 4e-9 per crossing,
// two per impact: 30 impacts stay below 2.4e-7. Tolerance 1e-6; the check with h / 2 shows the
// error falls (the bound is not a floor).
struct RattleResult {
  double energy_error = 0.0;
  int drive_impacts = 0, back_impacts = 0;
};

RattleResult rattle(const GearMeshContact& c, double h, double t_end) {
  const double j1 = 0.01, j2 = 0.03, r1 = 0.03, r2 = 0.06, k = 1e8, b = 1e-4;
  using State = std::array<double, 4>;  // phi1, phi2, w1, w2
  auto rhs = [&](const State& s) {
    ElementForce out;
    c.evaluate(vec(r1 * s[0] - r2 * s[1], s[0]), vec(r1 * s[2] - r2 * s[3], s[2]), 0.0, out);
    const double f = out.force(0);
    return State{s[2], s[3], (-r1 * f - out.force(1)) / j1, r2 * f / j2};
  };
  auto energy = [&](const State& s) {
    const double delta = r1 * s[0] - r2 * s[1];
    const double p = std::max(delta, 0.0), pb = std::max(-delta - b, 0.0);
    return 0.5 * j1 * s[2] * s[2] + 0.5 * j2 * s[3] * s[3] + 0.5 * k * (p * p + pb * pb);
  };
  // Start in the middle of the play, pinion ahead at 0.1 m/s relative.
  const double w = 100.0, v_rel = 0.1;
  State s{-0.5 * b / r1, 0.0, w + v_rel / (2.0 * r1), w * r1 / r2 - v_rel / (2.0 * r2)};
  const double e0 = energy(s);
  RattleResult r;
  MeshContactState last = MeshContactState::separated;
  for (double t = 0.0; t < t_end; t += h) {
    const State k1 = rhs(s);
    State a;
    for (int i = 0; i < 4; ++i) a[i] = s[i] + 0.5 * h * k1[i];
    const State k2 = rhs(a);
    for (int i = 0; i < 4; ++i) a[i] = s[i] + 0.5 * h * k2[i];
    const State k3 = rhs(a);
    for (int i = 0; i < 4; ++i) a[i] = s[i] + h * k3[i];
    const State k4 = rhs(a);
    for (int i = 0; i < 4; ++i) s[i] += h / 6.0 * (k1[i] + 2.0 * k2[i] + 2.0 * k3[i] + k4[i]);
    const MeshContactState now = c.state(vec(r1 * s[0] - r2 * s[1], s[0]));
    if (now != last && now == MeshContactState::drive) ++r.drive_impacts;
    if (now != last && now == MeshContactState::back) ++r.back_impacts;
    last = now;
    r.energy_error = std::max(r.energy_error, std::abs(energy(s) - e0) / e0);
  }
  // relative to the kinetic energy of the relative motion, the part the contact exchanges
  r.energy_error *= e0 / (0.5 * (j1 * j2 / (j1 * r2 * r2 + j2 * r1 * r1)) * v_rel * v_rel);
  return r;
}

TEST(GearMeshContact, UndampedRattleThroughTheBacklashConservesEnergy) {
  const double k = 1e8, b = 1e-4;
  const double j1 = 0.01, j2 = 0.03, r1 = 0.03, r2 = 0.06;
  const double m_e = j1 * j2 / (j1 * r2 * r2 + j2 * r1 * r1);
  const double t_c = kPi * std::sqrt(m_e / k);
  const double t_end = 30.0 * (t_c + b / 0.1);  // 30 impacts, one per crossing of the play
  const auto constant =
      std::make_shared<MeshForceMap>(MeshForceMap::constant_stiffness(k, 2.0 * kPi / 20));
  for (bool map_law : {true, false}) {
    GearMeshContactOptions o;
    o.backlash = b;
    if (!map_law) o.law = std::make_shared<LinearContactLaw>(LinearLawParameters{k, 0.0});
    const GearMeshContact c("mesh", constant, o);
    const RattleResult r = rattle(c, t_c / 2000.0, t_end);
    EXPECT_GE(r.drive_impacts, 10);
    EXPECT_GE(r.back_impacts, 10);
    EXPECT_LT(r.energy_error, 1e-6) << "map law " << map_law;
    if (map_law) {
      const RattleResult finer = rattle(c, t_c / 4000.0, t_end);
      EXPECT_LT(finer.energy_error, r.energy_error);
    }
  }
}

TEST(GearMeshContact, BadMapsAndOptionsNameTheirKey) {
  auto key_of = [](auto edit, GearMeshContactOptions o = {}) {
    auto m = test_map();
    edit(*m);
    LawSource source;
    source.location = {"model.toml", 9, 1};
    source.key_path = "gear_meshes[1].contact";
    try {
      const GearMeshContact c("mesh", m, o, source);
    } catch (const InputError& e) {
      EXPECT_EQ(e.where().line, 9);
      return e.key_path();
    }
    return std::string("no error");
  };
  EXPECT_EQ(key_of([](MeshForceMap&) {}), "no error");
  EXPECT_EQ(key_of([](MeshForceMap& m) { m.forces_n[1] = 500.0; }),
            "gear_meshes[1].contact.gear_pair");
  EXPECT_EQ(key_of([](MeshForceMap& m) { m.approach_m[2][4] = m.approach_m[1][4]; }),
            "gear_meshes[1].contact.gear_pair");
  EXPECT_EQ(key_of([](MeshForceMap& m) { m.approach_m[0][4] = m.unloaded_te_m[4]; }),
            "gear_meshes[1].contact.gear_pair");
  EXPECT_EQ(key_of([](MeshForceMap& m) { m.approach_m[1].pop_back(); }),
            "gear_meshes[1].contact.gear_pair");
  EXPECT_EQ(key_of([](MeshForceMap& m) { m.period_rad = 0.0; }),
            "gear_meshes[1].contact.gear_pair");
  GearMeshContactOptions bad;
  bad.backlash = -1e-5;
  EXPECT_EQ(key_of([](MeshForceMap&) {}, bad), "gear_meshes[1].contact.backlash");
}

}  // namespace
