// Damper ring in a gear-web groove (damper/damper_ring.hpp) on a generated gear sector with its
// ring (meshgen::gear_sector, 10 sectors, 40 teeth, tet4), nodal diameter 2, engine order 2.
//
// References and tolerances:
//  * Stuck limit against a direct solve (A. Durastante, "Simulation of the Dynamic Response of
//    Aeronautical Gears Equipped with Damper Rings", MSc thesis, Politecnico di Torino, 2018,
//    sec. 4.4: a ring that never slips only stiffens): the contacts as linear springs assembled
//    into the sector stiffness between each pair's nodes, reduced to nodal diameter 2 and solved
//    directly with a sparse LU, against the condensed stuck response (40 modes + residual
//    flexibility) at 0.25 to 0.7 of the resonance speed. The residual is the static flexibility of
//    the modes left out, so the error is of order (w / w_41)^2 times their share of the response:
//    measured 8.6e-4 relative, 2e-3 asserted.
//  * mu -> infinity: the friction-damped harmonic balance equals the stuck linear response;
//    mu = 0: it equals the gear without ring (the limits). The only difference left is
//    the Newton tolerance (1e-10 relative): 1e-7 asserted.
//  * In between, the ring dissipates energy (positive energy per cycle with slip) and the damped
//    peak lies at least 10 % below the stuck ring's peak.
//  * Bad input: a ring contact node moved off its gear twin is reported with the worst pair.
#include "geardyn/damper/damper_ring.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <numbers>
#include <set>
#include <tuple>

#include "geardyn/core/error.hpp"
#include "geardyn/cyclic/cyclic_symmetry.hpp"
#include "geardyn/linalg/sparse_factorization.hpp"
#include "geardyn/meshgen/gear_sector.hpp"
#include "geardyn/solid/assembly.hpp"
#include "meshgen/damper_gear.hpp"

namespace geardyn::damper {
namespace {

using cd = std::complex<double>;

// The tests' damper gear (tests/meshgen/damper_gear.hpp), coarser and linear: ~1 s to mesh,
// assemble and solve.
meshgen::GearSectorParams damper_gear() {
  meshgen::GearSectorParams p = test::damper_gear(1);
  p.mesh.global = 0.012;
  p.mesh.tooth = 0.006;
  p.mesh.groove = 0.003;
  return p;
}

std::vector<long> ids(const solid::Mesh& mesh, const std::string& set) {
  std::vector<long> out;
  for (int n : mesh.node_sets.at(set)) out.push_back(mesh.node_ids[static_cast<std::size_t>(n)]);
  return out;
}

struct Fixture {
  solid::Mesh mesh;
  solid::SolidSystem system;
  DamperRingProblem problem;
  ContactPairing pairing;
};

cyclic::SectorInterfaces interfaces(const solid::Mesh& mesh, const std::vector<solid::DofInfo>& d) {
  cyclic::InterfaceOptions o;
  o.n_sectors = 10;
  return two_body_interfaces(d, o, ids(mesh, "left"), ids(mesh, "right"), ids(mesh, "ring_left"),
                             ids(mesh, "ring_right"));
}

const Fixture& fixture() {
  static const Fixture f = [] {
    Fixture x;
    x.mesh = meshgen::gear_sector(damper_gear());
    for (int n : x.mesh.node_sets.at("bore")) x.mesh.constraints.push_back({n});
    x.system = solid::assemble(x.mesh);
    const cyclic::SectorInterfaces itf = interfaces(x.mesh, x.system.dofs);
    x.pairing = pair_contact_nodes(x.system.dofs, ids(x.mesh, "groove_contact"),
                                   ids(x.mesh, "ring_contact"), itf, 1e-9, "contact");
    DamperRingProblem& p = x.problem;
    p.K = x.system.K;
    p.M = x.system.M;
    p.sector = cyclic::CyclicSector(x.system.dofs, itf);
    p.pairs = x.pairing.pairs;
    p.contact.normal_stiffness = 2e7;
    p.contact.tangential_stiffness = 1.5e7;
    p.contact.friction_coefficient = 0.3;
    p.ring_mass = 0.09;
    p.ring_radius = 0.0715;
    p.nodal_diameter = 2;
    p.engine_order = 2;
    const long exc = ids(x.mesh, "excitation").front();
    // Tangential load at the excitation node (e_theta at theta_0 = pi / 40).
    const double t0 = std::numbers::pi / 40;
    p.loads = {{response::tooth_load(exc, cd(200.0, 0.0),
                                     Eigen::Vector3d(std::sin(t0), -std::cos(t0), 0))}};
    p.sensors = {{"exc_x", exc, 0}, {"exc_y", exc, 1}};
    p.damping.damping_ratio = 0.002;
    p.n_modes = 12;
    p.harmonics = 1;
    return x;
  }();
  return f;
}

// Speeds around the mode of nodal diameter 2 the load excites most (largest |p_r| / w_r^2; the
// lowest modes are the ring's, which the gear's load does not reach while the ring is free).
std::pair<double, double> speed_band(const DamperRingModel& m) {
  const hbm::ModalReceptance& r = m.receptances[1];
  Eigen::Index best = 0;
  double most = 0.0;
  for (Eigen::Index i = 0; i < r.modes(); ++i) {
    const double w = r.natural_frequency[i];
    const double e = std::abs(r.modal_excitation[i]) / (w * w);
    if (e > most) {
      most = e;
      best = i;
    }
  }
  const double w = r.natural_frequency[best];
  return {0.85 * w / m.engine_order, 1.25 * w / m.engine_order};
}

TEST(DamperRing, PairsTheContactTwinsAndDropsTheRightInterface) {
  const Fixture& f = fixture();
  EXPECT_GT(f.pairing.pairs.size(), 4u);
  EXPECT_GT(f.pairing.dropped_on_right_interface, 0);
  EXPECT_LT(f.pairing.worst_gap, 1e-12);
  const DamperRingModel m = build_damper_ring_model(f.problem);
  EXPECT_NEAR(m.preload(1000.0),
              0.09 * 1e6 * 0.0715 / (10.0 * static_cast<double>(f.pairing.pairs.size())), 1e-12);
}

TEST(DamperRing, StuckResponseAgreesWithADirectSolveOfTheSpringCoupledSector) {
  const Fixture& f = fixture();
  const DamperRingProblem& p = f.problem;
  DamperRingProblem undamped = p;
  undamped.damping.damping_ratio = 1e-12;
  undamped.n_modes = 40;
  const DamperRingModel m = build_damper_ring_model(undamped);
  // Springs k_n e_r e_r^T + k_t e_theta e_theta^T between ring and gear nodes of each pair.
  std::map<std::pair<long, int>, int> index;
  for (std::size_t i = 0; i < p.sector->dofs().size(); ++i)
    index[{p.sector->dofs()[i].node_id, p.sector->dofs()[i].component}] = static_cast<int>(i);
  std::vector<Eigen::Triplet<double>> t;
  for (const auto& pr : p.pairs) {
    Eigen::Vector3d er(pr.position[0], pr.position[1], 0.0);
    er.normalize();
    const Eigen::Vector3d et = Eigen::Vector3d::UnitZ().cross(er);
    const Eigen::Matrix3d k = p.contact.normal_stiffness * er * er.transpose() +
                              p.contact.tangential_stiffness * et * et.transpose();
    for (int a = 0; a < 3; ++a)
      for (int b = 0; b < 3; ++b)
        for (const auto& [na, sa] : {std::pair{pr.ring_node, 1.0}, std::pair{pr.gear_node, -1.0}})
          for (const auto& [nb, sb] : {std::pair{pr.ring_node, 1.0}, std::pair{pr.gear_node, -1.0}})
            t.emplace_back(index.at({na, a}), index.at({nb, b}), sa * sb * k(a, b));
  }
  Eigen::SparseMatrix<double> Kc(p.K.rows(), p.K.cols());
  Kc.setFromTriplets(t.begin(), t.end());
  const Eigen::SparseMatrix<cd> Kh = p.sector->reduce(Eigen::SparseMatrix<double>(p.K + Kc), 2);
  const Eigen::SparseMatrix<cd> Mh = p.sector->reduce(p.M, 2);
  const Eigen::SparseMatrix<cd> T = p.sector->transformation(2);
  Eigen::VectorXcd f0 = Eigen::VectorXcd::Zero(p.sector->num_dofs());
  for (int c = 0; c < 3; ++c) f0[index.at({p.loads[0][0].node_id, c})] = p.loads[0][0].force[c];
  const auto [lo, hi] = speed_band(m);
  double worst = 0.0;
  for (double speed : {0.3 * lo, 0.6 * lo, 0.8 * lo}) {
    const double w = 2.0 * speed;
    linalg::SparseLU<cd> lu;
    ASSERT_EQ(lu.compute(Eigen::SparseMatrix<cd>(Kh - cd(w * w, 0.0) * Mh)), Status::Ok);
    const Eigen::VectorXcd u = T * lu.solve(Eigen::VectorXcd(T.adjoint() * f0));
    const Eigen::VectorXcd stuck = m.stuck_response(speed);
    for (int s = 0; s < 2; ++s) {
      const cd exact = u[index.at({p.sensors[static_cast<std::size_t>(s)].node_id, s})];
      worst = std::max(worst, std::abs(stuck[s] - exact) / std::abs(exact));
    }
  }
  EXPECT_LT(worst, 2e-3);
  RecordProperty("stuck_vs_direct_relative_error", std::to_string(worst));
}

DamperRingResult sweep(const DamperRingProblem& p, double mu, double normal_stiffness) {
  DamperRingProblem q = p;
  q.contact.friction_coefficient = mu;
  q.contact.normal_stiffness = normal_stiffness;
  const DamperRingModel m = build_damper_ring_model(q);
  DamperRingOptions o;
  std::tie(o.speed_min, o.speed_max) = speed_band(m);
  o.max_step = 0.05;
  o.tolerance = 1e-11;
  o.linear_points = 50;
  o.hysteresis_pairs = {0};
  DamperRingResult r = run_damper_ring(m, o);
  // The linear references at the continuation's own speeds.
  for (auto& d : r.damped) {
    d.peak = (mu > 1.0 ? m.stuck_response(d.speed) : m.free_response(d.speed)).cwiseAbs();
  }
  return r;
}

TEST(DamperRing, LargeFrictionIsTheStuckRingAndZeroFrictionTheGearAlone) {
  const Fixture& f = fixture();
  // mu = 0 with k_n = 0: no contact force at all (with k_n > 0 the normal springs would still
  // couple ring and gear radially).
  for (const auto& [mu, kn] : {std::pair{1e9, 2e7}, std::pair{0.0, 0.0}}) {
    const DamperRingResult r = sweep(f.problem, mu, kn);
    ASSERT_EQ(r.status, Status::Ok) << r.message;
    ASSERT_GT(r.damped.size(), 10u);
    double worst = 0.0;
    for (const auto& d : r.damped)
      worst = std::max(worst, (d.amplitude - d.peak).norm() / d.peak.norm());
    EXPECT_LT(worst, 1e-7) << "mu = " << mu;
  }
}

TEST(DamperRing, FrictionDissipatesAndLowersThePeak) {
  const Fixture& f = fixture();
  // This small, stiff gear meets its nodal-diameter-2 mode at ~3.4e5 rpm, where a real ring's
  // preload would hold every contact stuck: a ring of 0.01 g puts them into stick-slip there.
  DamperRingProblem light = f.problem;
  light.ring_mass = 1e-4;
  const DamperRingResult r = sweep(light, 0.3, 2e6);
  ASSERT_EQ(r.status, Status::Ok) << r.message;
  ASSERT_GE(r.peak_point, 0);
  const DampedPoint& peak = r.damped[static_cast<std::size_t>(r.peak_point)];
  EXPECT_GT(peak.energy_per_cycle, 0.0);
  EXPECT_GT(peak.slip, 0.0);
  EXPECT_TRUE(peak.loops_closed);
  EXPECT_LT(peak.amplitude[0], 0.9 * r.stuck_amplitude.col(0).maxCoeff());
  ASSERT_EQ(r.loops.size(), 1u);
  EXPECT_EQ(r.pair_states.rows(), static_cast<Eigen::Index>(f.pairing.pairs.size()));
}

TEST(DamperRing, EngineOrderTwoKLoadsTheSecondHarmonicOnItsNodalDiameter) {
  // Engine order 2k = 4 on harmonic 2, which carries nodal diameter 4 (N = 10), with the contacts
  // transmitting nothing (mu = 0, k_n = 0): harmonic 2 at every sensor is the linear response of
  // the sector at nodal diameter 4 and frequency 2 k W, solved directly (sparse LU of the reduced
  // K - w^2 M). Same truncation argument as the stuck test (40 modes + residual): 2e-3.
  const Fixture& f = fixture();
  DamperRingProblem q = f.problem;
  q.harmonics = 2;
  q.n_modes = 40;
  q.damping.damping_ratio = 1e-9;
  q.contact.friction_coefficient = 0.0;
  q.contact.normal_stiffness = 0.0;
  const response::ToothLoad load1 = q.loads[0][0];
  const response::ToothLoad load2{load1.node_id, 0.75 * load1.force};
  q.loads = {{}, {load2}};
  const DamperRingModel m = build_damper_ring_model(q);
  EXPECT_EQ(m.harmonic_diameter[2], 4);
  DamperRingOptions o;
  const double lo = speed_band(m).first;
  o.speed_min = 0.2 * lo;
  o.speed_max = 0.4 * lo;
  o.max_step = 0.2;
  o.linear_points = 3;
  const DamperRingResult r = run_damper_ring(m, o);
  ASSERT_EQ(r.status, Status::Ok) << r.message;
  ASSERT_GE(r.damped.size(), 3u);

  const cyclic::CyclicSector& sector = *q.sector;
  std::map<std::pair<long, int>, int> index;
  for (std::size_t i = 0; i < sector.dofs().size(); ++i)
    index[{sector.dofs()[i].node_id, sector.dofs()[i].component}] = static_cast<int>(i);
  const Eigen::SparseMatrix<cd> Kh = sector.reduce(q.K, 4), Mh = sector.reduce(q.M, 4);
  const Eigen::SparseMatrix<cd> T = sector.transformation(4);
  Eigen::VectorXcd f0 = Eigen::VectorXcd::Zero(sector.num_dofs());
  for (int c = 0; c < 3; ++c) f0[index.at({load2.node_id, c})] = load2.force[c];
  double worst = 0.0;
  for (const DampedPoint& d : r.damped) {
    const double w = 2.0 * q.engine_order * d.speed;
    linalg::SparseLU<cd> lu;
    ASSERT_EQ(lu.compute(Eigen::SparseMatrix<cd>(Kh - cd(w * w, 0.0) * Mh)), Status::Ok);
    const Eigen::VectorXcd u = T * lu.solve(Eigen::VectorXcd(T.adjoint() * f0));
    EXPECT_LT(d.amplitude.norm(), 1e-12 * d.harmonics.row(1).norm());  // harmonic 1 unloaded
    for (int s = 0; s < 2; ++s) {
      const double exact =
          std::abs(u[index.at({q.sensors[static_cast<std::size_t>(s)].node_id, s})]);
      worst = std::max(worst, std::abs(d.harmonics(1, s) - exact) / exact);
    }
  }
  EXPECT_LT(worst, 2e-3);
  RecordProperty("harmonic2_vs_direct_relative_error", std::to_string(worst));
}

TEST(DamperRing, RingMassAndRadiusFromTheMassMatrix) {
  // The ring of tests/meshgen/damper_gear.hpp: r 0.069 .. 0.074 m, 6 mm wide, rho 7800, whole
  // ring mass rho pi (r2^2 - r1^2) w and r_G = (2/3) (r2^3 - r1^3) / (r2^2 - r1^2) (the mass-
  // weighted mean radius of a rectangular section). The tet4 mesh facets the curved faces with
  // chords of about 3 mm on r = 0.07 m: a volume deficit of order (h / r)^2 / 12 = 1.5e-4, so
  // 1e-3 relative on the mass and 2e-4 on r_G.
  const Fixture& f = fixture();
  std::vector<long> ring;
  std::set<int> nodes;
  for (int e : f.mesh.element_sets.at("ring"))
    for (int n : f.mesh.elements[static_cast<std::size_t>(e)].nodes) nodes.insert(n);
  for (int n : nodes) ring.push_back(f.mesh.node_ids[static_cast<std::size_t>(n)]);
  const BodyMass b = body_mass(f.system.M, f.system.dofs, ring, 10, "ring");
  const double r1 = 0.069, r2 = 0.074, w = 0.006, rho = 7800.0;
  const double mass = rho * std::numbers::pi * (r2 * r2 - r1 * r1) * w;
  const double rg = 2.0 / 3.0 * (r2 * r2 * r2 - r1 * r1 * r1) / (r2 * r2 - r1 * r1);
  EXPECT_NEAR(b.mass / mass, 1.0, 1e-3);
  EXPECT_NEAR(b.radius / rg, 1.0, 2e-4);
  RecordProperty("ring_mass_relative_error", std::to_string(b.mass / mass - 1.0));
}

TEST(DamperRing, MindlinRatio) {
  // Equal materials: k_t / k_n = 2 (1 - nu) / (2 - nu) (Johnson, Contact Mechanics, eq. 7.41);
  // the general form is symmetric in the two bodies.
  EXPECT_NEAR(mindlin_ratio(210e9, 0.3, 210e9, 0.3), 2.0 * 0.7 / 1.7, 1e-15);
  EXPECT_NEAR(mindlin_ratio(210e9, 0.3, 70e9, 0.33), mindlin_ratio(70e9, 0.33, 210e9, 0.3), 1e-15);
}

TEST(DamperRing, ZeroFrictionWithZeroPreloadIsRefused) {
  DamperRingProblem q = fixture().problem;
  q.contact.friction_coefficient = 0.0;
  q.ring_mass = 0.0;
  try {
    (void)build_damper_ring_model(q);
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("zero friction together with zero preload"),
              std::string::npos)
        << e.what();
  }
}

TEST(DamperRing, AContactNodeOffItsTwinIsReported) {
  const Fixture& f = fixture();
  std::vector<solid::DofInfo> dofs = f.system.dofs;
  const long moved = ids(f.mesh, "ring_contact").front();
  for (auto& d : dofs)
    if (d.node_id == moved) d.x[2] += 1e-4;
  try {
    pair_contact_nodes(dofs, ids(f.mesh, "groove_contact"), ids(f.mesh, "ring_contact"),
                       f.problem.sector->interfaces(), 1e-6, "analyses[0].contact");
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    EXPECT_EQ(e.key_path(), "analyses[0].contact");
    EXPECT_NE(std::string(e.what()).find("gear node"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace geardyn::damper
