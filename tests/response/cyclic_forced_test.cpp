// Forced response of a cyclic sector to engine-order tooth forces (response/cyclic_forced_response)
// checked against independent computations on the same mesh:
//   (1) the full 360 deg wheel (cyclic::replicate + solid::assemble) driven by the physical
//       tooth forces on all N teeth, eq. (1) of cyclic_forced_response.hpp, solved by a sparse
//       complex LU per speed;
//   (2) a single dominant mode: SDOF peak amplitude and half-power Q;
//   (4) bad input.
//
// The structure (all tests): an annular steel disk, r = 0.05 .. 0.15 m, t = 0.02 m, clamped at
// the inner radius, N = 8 sectors of 45 deg, hex8 with 2 x 2 x 1 cells per sector:
//
//        outer rim  o---o---o   <- tooth load at the outer top mid-sector node (and, in one
//                   |   |   |      case, also at the outer top node on the left interface)
//                   o---o---o
//                   |   |   |
//        inner rim  x---x---x   clamped (ux = uy = uz = 0)
//
// Sector: 27 nodes, 63 free DOFs; full wheel 432 free DOFs (small enough for direct LU).
// Damping: Rayleigh C = a M + b K on sector and full wheel alike; its modal ratios
// zeta_r = a / (2 w_r) + b w_r / 2 make the modal sum over all modes of ND h exact.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <complex>
#include <cstdio>
#include <unordered_map>

#include "geardyn/core/error.hpp"
#include "geardyn/core/units.hpp"
#include "geardyn/cyclic/cyclic_symmetry.hpp"
#include "geardyn/cyclic/replicate.hpp"
#include "geardyn/linalg/sparse_factorization.hpp"
#include "geardyn/reduce/craig_bampton.hpp"
#include "geardyn/response/cyclic_forced_response.hpp"
#include "geardyn/solid/assembly.hpp"
#include "geardyn/solid/structured_mesh.hpp"

namespace geardyn::response {
namespace {

using Complex = std::complex<double>;
constexpr double kPi = units::kPi;
constexpr int kSectors = 8;
constexpr double kRayleighA = 20.0;    // [1/s]
constexpr double kRayleighB = 2.0e-7;  // [s]

solid::Material steel() {
  solid::Material m;
  m.name = "steel";
  m.E = 200e9;
  m.nu = 0.3;
  m.rho = 7850.0;
  return m;
}

solid::Mesh clamped_sector_mesh() {
  solid::Mesh mesh = solid::annular_sector_mesh(0.05, 0.15, 0.02, 2.0 * kPi / kSectors, 2, 2, 1,
                                                solid::ElementType::Hex8, steel());
  for (int node : mesh.node_sets.at("inner")) {
    solid::Constraint c;
    c.node = node;
    mesh.constraints.push_back(c);
  }
  return mesh;
}

// Index of the node nearest `x`.
int nearest_node(const solid::Mesh& mesh, const Eigen::Vector3d& x) {
  int best = 0;
  for (int i = 1; i < mesh.num_nodes(); ++i)
    if ((mesh.coords[static_cast<std::size_t>(i)] - x).norm() <
        (mesh.coords[static_cast<std::size_t>(best)] - x).norm())
      best = i;
  return best;
}

struct Fixture {
  solid::Mesh mesh = clamped_sector_mesh();
  solid::SolidSystem system = solid::assemble(mesh);
  cyclic::CyclicSector sector = make_sector(system);
  int mid_node = nearest_node(mesh, Eigen::Vector3d(0.15 * std::cos(kPi / kSectors),
                                                    0.15 * std::sin(kPi / kSectors), 0.01));
  int left_node = nearest_node(mesh, Eigen::Vector3d(0.15, 0.0, 0.01));
  int sensor_node = nearest_node(mesh, Eigen::Vector3d(0.10 * std::cos(kPi / kSectors),
                                                       0.10 * std::sin(kPi / kSectors), -0.01));

  static cyclic::CyclicSector make_sector(const solid::SolidSystem& s) {
    cyclic::InterfaceOptions io;
    io.n_sectors = kSectors;
    return cyclic::CyclicSector(s.dofs, cyclic::find_interfaces(s.dofs, io));
  }
  long id(int node) const { return mesh.node_ids[static_cast<std::size_t>(node)]; }
  Eigen::SparseMatrix<double> rayleigh() const {
    return Eigen::SparseMatrix<double>(kRayleighA * system.M + kRayleighB * system.K);
  }
  // Every mode of one nodal diameter (dense solver on the 40-60 reduced DOFs).
  cyclic::NodalDiameterModes all_modes(int h) const {
    cyclic::CyclicModesOptions o;
    o.nodal_diameters = {h};
    o.eigen.method = eig::Method::Dense;
    o.eigen.n_modes = static_cast<int>(sector.num_reduced_dofs());
    cyclic::CyclicModesResult r = cyclic::solve_cyclic_modes(system.K, system.M, sector, o);
    EXPECT_EQ(r.status, Status::Ok) << r.brief_report();
    return r.diameters.at(0);
  }
  std::vector<CyclicSensor> sensors() const {
    return {{"sensor_ux", id(sensor_node), 0},
            {"sensor_uz", id(sensor_node), 2},
            {"rim_uy", id(mid_node), 1}};
  }
};

// Tooth force: tangential 1 N with 0.36 radial and 0.2 axial parts (a spur-like split with a
// small axial part) and a phase, so that every component and the phase convention matter.
Eigen::Vector3cd tooth_force(const Eigen::Vector3d& x) {
  const Eigen::Vector3d e_r = Eigen::Vector3d(x.x(), x.y(), 0.0).normalized();
  const Eigen::Vector3d e_t = Eigen::Vector3d::UnitZ().cross(e_r);
  return std::polar(1.0, 0.3) * (e_t + 0.36 * e_r + 0.2 * Eigen::Vector3d::UnitZ()).cast<Complex>();
}

// Full-wheel direct reference: physical forces (1) on all teeth, (K - w^2 M + i w C) u = F,
// response at the sensor DOFs of sector `copy`.
Eigen::MatrixXcd full_wheel_response(const Fixture& fx, const std::vector<ToothLoad>& loads, int k,
                                     const Eigen::VectorXd& speeds, int copy) {
  const cyclic::ReplicatedMesh full = cyclic::replicate(fx.mesh, kSectors);
  const solid::SolidSystem fs = solid::assemble(full.mesh);
  std::unordered_map<long, int> index;
  for (int i = 0; i < fx.mesh.num_nodes(); ++i) index[fx.id(i)] = i;
  const double alpha = 2.0 * kPi / kSectors;
  Eigen::VectorXcd F = Eigen::VectorXcd::Zero(fs.num_dofs());
  for (int j = 0; j < kSectors; ++j) {
    const Eigen::Matrix3d R = cyclic::rotation(Eigen::Vector3d::UnitZ(), j * alpha);
    const Complex phase = std::polar(1.0, k * j * alpha);
    for (const ToothLoad& load : loads) {
      const int node = full.node_map[static_cast<std::size_t>(j)]
                                    [static_cast<std::size_t>(index.at(load.node_id))];
      const Eigen::Vector3cd f = phase * (R.cast<Complex>() * load.force);
      for (int c = 0; c < 3; ++c) F[fs.node_dof(node, c)] += f[c];
    }
  }
  const Eigen::SparseMatrix<Complex> Kc = fs.K.cast<Complex>(), Mc = fs.M.cast<Complex>();
  const Eigen::SparseMatrix<Complex> Cc = (kRayleighA * fs.M + kRayleighB * fs.K).cast<Complex>();
  const auto sensors = fx.sensors();
  Eigen::MatrixXcd out(speeds.size(), static_cast<Eigen::Index>(sensors.size()));
  linalg::SparseLU<Complex> lu;
  for (Eigen::Index s = 0; s < speeds.size(); ++s) {
    const double w = k * speeds[s];
    const Eigen::SparseMatrix<Complex> D = Kc - Complex(w * w) * Mc + Complex(0.0, w) * Cc;
    EXPECT_EQ(lu.compute(D), Status::Ok);
    const Eigen::VectorXcd u = lu.solve(F);
    for (std::size_t i = 0; i < sensors.size(); ++i) {
      const int node = full.node_map[static_cast<std::size_t>(copy)]
                                    [static_cast<std::size_t>(index.at(sensors[i].node_id))];
      out(s, static_cast<Eigen::Index>(i)) = u[fs.node_dof(node, sensors[i].component)];
    }
  }
  return out;
}

double relative_difference(const Eigen::MatrixXcd& a, const Eigen::MatrixXcd& b) {
  return (a - b).cwiseAbs().maxCoeff() / b.cwiseAbs().maxCoeff();
}

ModalDamping rayleigh_ratios(const cyclic::NodalDiameterModes& modes) {
  ModalDamping d;
  d.damping_ratios.resize(modes.eigen.eigenvalues.size());
  for (Eigen::Index r = 0; r < d.damping_ratios.size(); ++r) {
    const double w = std::sqrt(modes.eigen.eigenvalues[r]);
    d.damping_ratios[r] = kRayleighA / (2.0 * w) + kRayleighB * w / 2.0;
  }
  return d;
}

struct Case {
  int h, k;
  bool interface_load;
};

// (1) Sector modal sum and sector direct solve vs the full wheel, for every kind of order:
// k = h (backward), N - h (forward, conjugate pattern), N + h, h = 0 (k = N), h = N/2, and a
// load on an interface node. Speeds: below, near and above the lowest resonance of ND h.
// Tolerances: sector direct vs full direct is the same linear algebra (T_h^H D T_h restricted to
// the cyclic subspace), so they agree to the LU round-off, 1e-9 relative to the largest
// response; the modal sum over all modes of ND h is exact for Rayleigh damping, its error is the
// eigenvector round-off of the dense solver (backward error ~1e-15) amplified by the modal
// condition, 1e-7 leaves a wide margin.
TEST(CyclicForced, SectorMatchesFullWheelForEveryOrderType) {
  const Fixture fx;
  for (const Case c : {Case{2, 2, false}, Case{2, 6, false}, Case{2, 10, true}, Case{0, 8, false},
                       Case{4, 4, true}, Case{4, 12, false}, Case{1, 7, true}, Case{3, 3, true}}) {
    SCOPED_TRACE(::testing::Message() << "h = " << c.h << ", k = " << c.k
                                      << (c.interface_load ? ", interface load" : ""));
    std::vector<ToothLoad> loads = {
        {fx.id(fx.mid_node), tooth_force(fx.mesh.coords[static_cast<std::size_t>(fx.mid_node)])}};
    if (c.interface_load)
      loads.push_back({fx.id(fx.left_node),
                       0.5 * tooth_force(fx.mesh.coords[static_cast<std::size_t>(fx.left_node)])});
    const cyclic::NodalDiameterModes modes = fx.all_modes(c.h);
    const double w1 = std::sqrt(modes.eigen.eigenvalues[0]);
    Eigen::VectorXd speeds(4);
    speeds << 0.5 * w1 / c.k, 0.999 * w1 / c.k, w1 / c.k, 1.7 * w1 / c.k;

    const CyclicOrderModel model =
        make_cyclic_order_model(fx.sector, modes, c.k, loads, fx.sensors(), rayleigh_ratios(modes));
    const Eigen::MatrixXcd modal = model.response(speeds);
    const Eigen::MatrixXcd direct = cyclic_direct_response(
        fx.system.K, fx.system.M, fx.rayleigh(), fx.sector, c.h, c.k, loads, fx.sensors(), speeds);
    const Eigen::MatrixXcd full = full_wheel_response(fx, loads, c.k, speeds, 0);
    const double e_direct = relative_difference(direct, full);
    const double e_modal = relative_difference(modal, full);
    std::printf("h %d k %d%s: sector direct vs full %.2e, modal sum vs full %.2e\n", c.h, c.k,
                c.interface_load ? " (+interface load)" : "", e_direct, e_modal);
    EXPECT_LT(e_direct, 1e-9);
    EXPECT_LT(e_modal, 1e-7);

    // Sector j of the full wheel carries the pattern e^{+-i j phi_h} R(j alpha) u_0 (the sign of
    // eq. 2 / eq. 3), i.e. the phase e^{i k j alpha} of the force. Sensor node values rotate
    // with R, so compare the rotation-invariant uz component directly.
    const int j = 3;
    const Eigen::MatrixXcd full_j = full_wheel_response(fx, loads, c.k, speeds, j);
    const Complex phase = std::polar(1.0, 2.0 * kPi * c.k * j / kSectors);
    EXPECT_LT((full_j.col(1) - phase * full.col(1)).cwiseAbs().maxCoeff(),
              1e-9 * full.col(1).cwiseAbs().maxCoeff());
  }
}

// Craig-Bampton sector (reduce::craig_bampton).
//  (a) Masters = the free interface nodes only: the tooth load and the sensors sit on interior
//      nodes, so the load is projected by T^T and the sensor values recovered by x = T q (the
//      `recovery` argument). Keeping every fixed-interface mode makes T square and invertible,
//      so the reduced sector is the unreduced one in other coordinates and its modal sum must
//      equal the unreduced sector's direct solve (1e-7, as above).
//  (b) Masters = interfaces + the load and sensor nodes (docs/theory.md §9: excitation and sensor
//  nodes
//      stay physical), half of the fixed-interface modes: the truncation error must stay below
//      1e-2 of the largest response (measured figure printed).
TEST(CyclicForced, CraigBamptonSectorWithRecoveryAndTruncation) {
  const Fixture fx;
  std::vector<long> interface_ids;
  for (const char* set : {"left", "right"})
    for (int node : fx.mesh.node_sets.at(set))
      if (fx.system.node_dof(node, 0) >= 0) interface_ids.push_back(fx.id(node));
  std::vector<long> with_loads = interface_ids;
  with_loads.push_back(fx.id(fx.mid_node));
  with_loads.push_back(fx.id(fx.sensor_node));
  const int h = 2, k = 6;
  const std::vector<ToothLoad> loads = {
      {fx.id(fx.mid_node), tooth_force(fx.mesh.coords[static_cast<std::size_t>(fx.mid_node)])}};
  const cyclic::NodalDiameterModes unreduced = fx.all_modes(h);
  const double w1 = std::sqrt(unreduced.eigen.eigenvalues[0]);
  Eigen::VectorXd speeds(3);
  speeds << 0.3 * w1 / k, 0.8 * w1 / k, 1.01 * w1 / k;
  const Eigen::MatrixXcd reference = cyclic_direct_response(
      fx.system.K, fx.system.M, fx.rayleigh(), fx.sector, h, k, loads, fx.sensors(), speeds);

  for (const bool truncated : {false, true}) {
    const std::vector<int> masters =
        reduce::select_dofs(fx.system.dofs, truncated ? with_loads : interface_ids);
    const int n_interior = fx.system.num_dofs() - static_cast<int>(masters.size());
    reduce::CraigBamptonOptions cb;
    cb.n_modes = truncated ? n_interior / 2 : n_interior;
    const reduce::ReducedComponent rc =
        reduce::craig_bampton(fx.system.K, fx.system.M, fx.system.dofs, masters, cb);
    const std::vector<solid::DofInfo> dofs = rc.reduced_dofs();
    cyclic::InterfaceOptions io;
    io.n_sectors = kSectors;
    const cyclic::CyclicSector sector(dofs, cyclic::find_interfaces(dofs, io));
    cyclic::CyclicModesOptions o;
    o.nodal_diameters = {h};
    o.eigen.method = eig::Method::Dense;
    o.eigen.n_modes = static_cast<int>(sector.num_reduced_dofs());
    const Eigen::SparseMatrix<double> K = rc.K.sparseView(), M = rc.M.sparseView();
    const cyclic::NodalDiameterModes modes =
        cyclic::solve_cyclic_modes(K, M, sector, o).diameters.at(0);
    const CyclicOrderModel model = make_cyclic_order_model(sector, modes, k, loads, fx.sensors(),
                                                           rayleigh_ratios(modes), 0, &rc);
    const double error = relative_difference(model.response(speeds), reference);
    std::printf("Craig-Bampton, %s masters, %d of %d interior modes: error %.2e\n",
                truncated ? "interface + load + sensor" : "interface", cb.n_modes, n_interior,
                error);
    EXPECT_LT(error, truncated ? 1e-2 : 1e-7);
    if (!truncated) {
      // Without the component the interior nodes are not in the sector.
      EXPECT_THROW(
          make_cyclic_order_model(sector, modes, k, loads, fx.sensors(), rayleigh_ratios(modes)),
          InputError);
    }
  }
}

// The order relation and its travelling direction (file comment of cyclic_forced_response.hpp).
TEST(CyclicForced, OrderRelationNamesTheRuleAndTheWave) {
  EXPECT_EQ(relate_order(8, 2, 2).rule, "h");
  EXPECT_EQ(relate_order(8, 2, 2).wave, TravellingWave::Backward);
  EXPECT_FALSE(relate_order(8, 2, 2).conjugate);
  EXPECT_EQ(relate_order(8, 2, 6).rule, "N-h");
  EXPECT_EQ(relate_order(8, 2, 6).wave, TravellingWave::Forward);
  EXPECT_TRUE(relate_order(8, 2, 6).conjugate);
  EXPECT_EQ(relate_order(8, 2, 10).rule, "N+h");
  EXPECT_EQ(relate_order(8, 2, 14).rule, "2N-h");
  EXPECT_EQ(relate_order(8, 0, 16).rule, "2N");
  EXPECT_EQ(relate_order(8, 4, 12).wave, TravellingWave::Standing);
  EXPECT_FALSE(relate_order(8, 4, 12).conjugate);
}

// (2) One dominant mode. Near W_1 = w_1 / k the response is the SDOF term
//   u = psi_s (psi^H f) / (w_1^2 - w^2 + 2 i zeta w_1 w),  peak |psi_s psi^H f| / (2 zeta w_1^2)
// (to O(zeta^2)), and the half-power band gives Q = 1 / (2 zeta) (Ewins, Modal Testing, 2000,
// sec. 2.2 and 4.3). zeta = 1e-3 (Q = 500). The other modes add a background that is bounded
// here by the sum of their terms' magnitudes at W_1; the tolerance is that bound plus 1e-4 for
// the parabolic refinement on a grid of 2e-4 W_1 (half-power band 2e-3 W_1: 10 samples in band).
TEST(CyclicForced, DominantModeGivesSdofPeakAndHalfPowerQ) {
  const Fixture fx;
  const int h = 2, k = 2;
  const cyclic::NodalDiameterModes modes = fx.all_modes(h);
  CyclicForcedSettings settings;
  settings.excitations = {
      {h,
       k,
       {{fx.id(fx.mid_node), tooth_force(fx.mesh.coords[static_cast<std::size_t>(fx.mid_node)])}}}};
  settings.sensors = fx.sensors();
  settings.damping.q_factor = 500.0;
  const double zeta = 1e-3;
  const double w1 = std::sqrt(modes.eigen.eigenvalues[0]);
  const double W1 = w1 / k;
  const int n = 201;
  settings.speeds = Eigen::VectorXd::LinSpaced(n, W1 * (1 - 0.02), W1 * (1 + 0.02));
  const CyclicForcedResult r = run_cyclic_forced_response(fx.sector, {modes}, settings);
  const CyclicOrderModel model = make_cyclic_order_model(
      fx.sector, modes, k, settings.excitations[0].loads, fx.sensors(), settings.damping);
  int checked = 0;
  for (int s = 0; s < 3; ++s) {
    const double sdof =
        std::abs(model.sensor_shapes(s, 0) * model.modal_force[0]) / (2.0 * zeta * w1 * w1);
    double background = 0.0;
    for (Eigen::Index m = 1; m < model.num_modes(); ++m)
      background += model.modal_term(m, W1).cwiseAbs()[s];
    if (sdof < 20.0 * background) continue;  // a sensor near a node line of mode 1
    ++checked;
    const auto peak = std::find_if(r.peaks.begin(), r.peaks.end(), [&](const SpeedPeak& p) {
      return p.sensor == s && p.curve == 0;
    });
    ASSERT_NE(peak, r.peaks.end());
    EXPECT_TRUE(peak->resolved);
    EXPECT_NEAR(peak->speed / W1, 1.0, 1e-4);
    std::printf("sensor %d: peak %.6e sdof %.6e (background %.2e), Q %.2f vs 500\n", s,
                peak->amplitude, sdof, background, peak->q_factor);
    EXPECT_LE(std::abs(peak->amplitude - sdof), background + 1e-4 * sdof)
        << "peak " << peak->amplitude << " sdof " << sdof << " background " << background;
    // Half-power Q from the sampled curve: the crossings are linearly interpolated between
    // samples 0.1 band apart (error ~1e-3 of the band) and the background shifts them by about
    // background / sdof of the band.
    EXPECT_NEAR(peak->q_factor, 500.0, 500.0 * (2e-3 + 2.0 * background / sdof));
  }
  EXPECT_GE(checked, 2);
  // The resonance table lists W_1 = w_1 / k with the sensors' amplitudes at W_1.
  const Table t = r.resonance_table();
  EXPECT_NEAR(t.column("resonance_speed_rpm").numbers[0], W1 * 60.0 / (2.0 * kPi), 1e-9 * W1);
  EXPECT_EQ(t.column("in_range").numbers[0], 1.0);
  EXPECT_DOUBLE_EQ(t.column("q_factor").numbers[0], 500.0);
}

// Superposition of two orders exciting different nodal diameters: the sum of amplitudes and the
// RMS follow from the per-order curves (definitions in the header), and resonant_orders finds
// exactly the (h, k) whose resonances fall in the speed range.
TEST(CyclicForced, SuperposedOrdersSumAmplitudesAndRms) {
  const Fixture fx;
  const cyclic::NodalDiameterModes m2 = fx.all_modes(2), m3 = fx.all_modes(3);
  const ToothLoad load{fx.id(fx.mid_node),
                       tooth_force(fx.mesh.coords[static_cast<std::size_t>(fx.mid_node)])};
  CyclicForcedSettings settings;
  settings.excitations = {{2, 6, {load}}, {3, 3, {load}}};
  settings.sensors = fx.sensors();
  settings.damping.damping_ratio = 0.01;
  settings.modes_used = 4;
  const double lo = std::sqrt(m2.eigen.eigenvalues[0]) / 6 * 0.8;
  const double hi = std::sqrt(m3.eigen.eigenvalues[0]) / 3 * 1.2;
  settings.speeds = Eigen::VectorXd::LinSpaced(400, lo, hi);
  const CyclicForcedResult r = run_cyclic_forced_response(fx.sector, {m2, m3}, settings);
  ASSERT_EQ(r.orders.size(), 2u);
  const Eigen::MatrixXd a0 = r.orders[0].displacement.cwiseAbs();
  const Eigen::MatrixXd a1 = r.orders[1].displacement.cwiseAbs();
  EXPECT_LT((r.amplitude_sum - (a0 + a1)).cwiseAbs().maxCoeff(),
            1e-12 * r.amplitude_sum.maxCoeff());
  EXPECT_LT(
      (r.amplitude_rms - ((a0.cwiseAbs2() + a1.cwiseAbs2()) / 2).cwiseSqrt()).cwiseAbs().maxCoeff(),
      1e-12 * r.amplitude_sum.maxCoeff());
  EXPECT_TRUE(std::any_of(r.peaks.begin(), r.peaks.end(),
                          [](const SpeedPeak& p) { return p.curve == -1; }));
  const auto pairs = resonant_orders({m2, m3}, kSectors, lo, hi, 16);
  for (const OrderPair& p : pairs) {
    const auto& m = p.nodal_diameter == 2 ? m2 : m3;
    bool hit = false;
    for (Eigen::Index i = 0; i < m.eigen.eigenvalues.size(); ++i) {
      const double W = std::sqrt(m.eigen.eigenvalues[i]) / p.engine_order;
      hit = hit || (W >= lo && W <= hi);
    }
    EXPECT_TRUE(hit);
  }
  EXPECT_TRUE(std::any_of(pairs.begin(), pairs.end(), [](const OrderPair& p) {
    return p.nodal_diameter == 2 && p.engine_order == 6;
  }));
  EXPECT_NO_THROW(r.response_table().validate());
  EXPECT_NO_THROW(r.resonance_table().validate());
  EXPECT_NO_THROW(r.peak_table().validate());
}

// (4) Bad input is refused with InputError.
TEST(CyclicForced, BadInputIsRefused) {
  const Fixture fx;
  const cyclic::NodalDiameterModes modes = fx.all_modes(2);
  const std::vector<ToothLoad> loads = {{fx.id(fx.mid_node), Eigen::Vector3cd(1.0, 0.0, 0.0)}};
  ModalDamping damping;
  damping.damping_ratio = 0.01;
  // k = 3 is +-3 (mod 8), not +-2.
  EXPECT_THROW(make_cyclic_order_model(fx.sector, modes, 3, loads, fx.sensors(), damping),
               InputError);
  EXPECT_THROW(relate_order(8, 5, 5), InputError);  // h above N/2
  EXPECT_THROW(relate_order(8, 2, 0), InputError);
  // Missing excitation node, and a load on a clamped DOF.
  EXPECT_THROW(make_cyclic_order_model(fx.sector, modes, 2, {{999999, Eigen::Vector3cd(1, 0, 0)}},
                                       fx.sensors(), damping),
               InputError);
  const int clamped = nearest_node(fx.mesh, Eigen::Vector3d(0.05, 0.0, 0.01));
  EXPECT_THROW(
      make_cyclic_order_model(fx.sector, modes, 2, {{fx.id(clamped), Eigen::Vector3cd(1, 0, 0)}},
                              fx.sensors(), damping),
      InputError);
  // Missing sensor node.
  EXPECT_THROW(
      make_cyclic_order_model(fx.sector, modes, 2, loads, {{"nowhere", 999999, 0}}, damping),
      InputError);
  // Damping: none, or two forms at once.
  EXPECT_THROW(make_cyclic_order_model(fx.sector, modes, 2, loads, fx.sensors(), {}), InputError);
  ModalDamping both;
  both.damping_ratio = 0.01;
  both.q_factor = 50;
  EXPECT_THROW(make_cyclic_order_model(fx.sector, modes, 2, loads, fx.sensors(), both), InputError);
  // Speeds not increasing, zero speed.
  CyclicForcedSettings settings;
  settings.excitations = {{2, 2, loads}};
  settings.sensors = fx.sensors();
  settings.damping = damping;
  settings.speeds = Eigen::Vector3d(100.0, 300.0, 200.0);
  EXPECT_THROW(run_cyclic_forced_response(fx.sector, {modes}, settings), InputError);
  settings.speeds = Eigen::Vector2d(0.0, 100.0);
  EXPECT_THROW(run_cyclic_forced_response(fx.sector, {modes}, settings), InputError);
  // A nodal diameter without modes.
  settings.speeds = Eigen::Vector2d(100.0, 200.0);
  settings.excitations = {{3, 3, loads}};
  EXPECT_THROW(run_cyclic_forced_response(fx.sector, {modes}, settings), InputError);
}

}  // namespace
}  // namespace geardyn::response
