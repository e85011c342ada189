// Validation of solids joined to the rotor through spiders (component/solid_coupling.hpp).
//
// System (spider_test_support.hpp): steel shaft d = 40 mm, L = 0.4 m, 4 Timoshenko elements,
// bearings k = 1e7 N/m at both ends (axial at s.0, torsion fixed at s.0); an annular plate
// b = 20 mm, a = 150 mm, h = 10 mm (hex20, 4 x 24 x 1 elements) at mid-span, joined to s.2 by a
// spider on its "inner" node set (r = b).
//
// (a) A very stiff plate (E x 1e4) must behave as the rigid disk of the same mass and inertias,
//     m = rho pi (a^2 - b^2) h, Ip = m (a^2 + b^2) / 2, Id = m (3 (a^2 + b^2) + h^2) / 12
//     (e.g. Friswell et al., Dynamics of Rotating Machines, CUP 2010, sec. 5.2), at rest and
//     spinning (gyroscopic).
// (b) A flexible (steel) plate: Craig-Bampton coupling is a Rayleigh-Ritz method on nested
//     subspaces, so each natural frequency lies above the unreduced coupled system's and falls
//     monotonically as coupling_modes grows (Courant-Fischer); it must converge to the direct
//     assembly of rotor + full plate mesh (built here as one sparse system).
// (c) An averaging (RBE3) spider imposes 6 constraints where the rigid one imposes one per set
//     DOF: every motion admissible with the rigid spider is admissible with the averaging one, so
//     its frequencies are lower or equal (and equal to the rigid ones for the stiff plate).
#include <gtest/gtest.h>

#include <Eigen/SparseCholesky>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <string>
#include <vector>

#include "geardyn/analyses/modal.hpp"
#include "geardyn/analyses/model_file.hpp"
#include "geardyn/assembly/solid_coupling.hpp"
#include "geardyn/assembly/system_builder.hpp"
#include "geardyn/eig/symmetric_eigen.hpp"
#include "geardyn/model/parse.hpp"
#include "spider_test_support.hpp"

namespace geardyn {
namespace {

using test::spider_plate;
using test::spider_rotor;

model::Model parse(const std::string& text) { return analyses::parse_model(text, "spider.toml"); }

// The lowest n natural frequencies [Hz] of (K, M).
Eigen::VectorXd frequencies(const Eigen::SparseMatrix<double>& K,
                            const Eigen::SparseMatrix<double>& M, int n) {
  eig::SymmetricEigenOptions o;
  o.n_modes = n;
  const auto r = eig::solve_symmetric(K, M, o);
  EXPECT_EQ(r.status, Status::Ok) << r.message;
  return r.eigenvalues.cwiseMax(0.0).cwiseSqrt() / (2.0 * std::numbers::pi);
}

std::string rigid_disk() {
  const test::PlateInertia p = test::plate_inertia();
  return fmt::format(R"(
[[disks]]
node = "s.2"
mass = {}
polar_inertia = {}
diametral_inertia = {}
)",
                     p.mass, p.polar, p.diametral);
}

// The mesh's rigid-body mass matrix about s.2 against the analytic disk. The hex20 edges are
// quadratic interpolations of the arcs (mid-side nodes on the circle); with half-angle
// alpha = pi / 24 per element the area they enclose differs from the circle's by about
// alpha^4 / 15 = 2e-5 (measured: 1.0e-5 for m, 1.9e-5 for Ip and Id): tolerance 5e-5.
TEST(SpiderValidation, RigidMassOfThePlate) {
  const model::Model m = parse(spider_rotor(spider_plate("stiff", 0)));
  const assembly::CoupledSolid c =
      assembly::couple_solid(m, m.solids[0], assembly::build_solid(m, m.solids[0]));
  const test::PlateInertia p = test::plate_inertia();
  const Eigen::Matrix<double, 6, 6>& J = c.rigid_mass;
  const double tol = 5e-5;
  EXPECT_NEAR(J(0, 0), p.mass, tol * p.mass);
  EXPECT_NEAR(J(2, 2), p.mass, tol * p.mass);
  EXPECT_NEAR(J(3, 3), p.diametral, tol * p.diametral);
  EXPECT_NEAR(J(4, 4), p.diametral, tol * p.diametral);
  EXPECT_NEAR(J(5, 5), p.polar, tol * p.polar);
  EXPECT_NEAR(c.polar_inertia, J(5, 5), 1e-12 * p.polar);
  // Centre of mass at the node: no mass-rotation coupling.
  const double coupling = J.topRightCorner<3, 3>().norm();
  EXPECT_LT(coupling, 1e-9 * p.mass * test::kPlateOuter);
  std::printf("plate: m = %.8g kg (analytic %.8g), Ip = %.8g (%.8g), Id = %.8g (%.8g) kg m^2\n",
              J(0, 0), p.mass, J(5, 5), p.polar, J(3, 3), p.diametral);
}

// (a) Stiff plate = rigid disk. The plate's own modes rise by sqrt(1e4) = 100 over steel's (the
// lowest coupled plate mode of the steel plate is 334 Hz, so above 30 kHz); a rotor mode at f
// moves by about (f / f_plate)^2 / 2 <= 1e-3 for f <= 1.3 kHz, and the mesh inertia is exact
// to 2e-5 (RigidMassOfThePlate): tolerance 1e-3 relative (measured: <= 1.6e-4 rigid, 4.1e-4
// averaging, whose inner ring stays elastic).
TEST(SpiderValidation, StiffPlateIsTheRigidDisk) {
  const int kModes = 10;
  const fe::LinearSystem disk = assembly::build_system(parse(spider_rotor(rigid_disk())));
  const Eigen::VectorXd f_disk = frequencies(disk.K, disk.M, kModes);
  for (const char* kind : {"rigid", "averaging"}) {
    const model::Model m = parse(spider_rotor(spider_plate("stiff", 4, kind)));
    const fe::LinearSystem plate = assembly::build_system(m);
    const Eigen::VectorXd f_plate = frequencies(plate.K, plate.M, kModes);
    for (int i = 0; i < kModes; ++i) {
      std::printf("%s mode %d: rigid disk %.6f Hz, stiff plate %.6f Hz (%.2e)\n", kind, i + 1,
                  f_disk[i], f_plate[i], f_plate[i] / f_disk[i] - 1.0);
      EXPECT_NEAR(f_plate[i], f_disk[i], 1e-3 * f_disk[i]) << kind << " mode " << i + 1;
    }
  }
}

// (a) spinning: the body's gyroscopic matrix is that of its rigid polar inertia, so forward and
// backward whirl split as for the rigid disk. Complex modes at 6000 rad/s (~57000 rpm, where
// Omega Ip / Id = 2 gives a strong split); same tolerance as at rest.
TEST(SpiderValidation, StiffPlateSpinsLikeTheRigidDisk) {
  analyses::ModalSettings s;
  s.speed = 6000.0;
  s.n_modes = 8;
  const model::Model disk_model = parse(spider_rotor(rigid_disk()));
  const model::Model plate_model = parse(spider_rotor(spider_plate("stiff", 4)));
  const auto disk_system = assembly::build_system(disk_model);
  const auto plate_system = assembly::build_system(plate_model);
  const auto disk =
      analyses::run_modal(disk_model, s, analyses::Context("modal").with_system(&disk_system));
  const auto plate =
      analyses::run_modal(plate_model, s, analyses::Context("modal").with_system(&plate_system));
  ASSERT_EQ(disk.status, Status::Ok) << disk.message;
  ASSERT_EQ(plate.status, Status::Ok) << plate.message;
  ASSERT_GE(plate.complex.size(), 8u);
  for (std::size_t i = 0; i < 8; ++i) {
    const auto& a = disk.complex[i];
    const auto& b = plate.complex[i];
    std::printf("at 6000 rad/s mode %zu: rigid disk %.5f Hz %s, plate %.5f Hz %s\n", i + 1,
                a.frequency_hz, std::string(analyses::to_string(a.whirl)).c_str(), b.frequency_hz,
                std::string(analyses::to_string(b.whirl)).c_str());
    EXPECT_NEAR(b.frequency_hz, a.frequency_hz, 1e-3 * a.frequency_hz) << "mode " << i + 1;
    EXPECT_EQ(b.whirl, a.whirl) << "mode " << i + 1;
  }
}

// The unreduced coupled system: rotor equations, plus every z coordinate of the plate that is
// not a spider master (the masters are the rotor node's DOFs: shaft along z, node frame =
// global axes).
struct Direct {
  Eigen::SparseMatrix<double> K, M;
};
Direct direct_system(const model::Model& m) {
  const fe::LinearSystem rotor = fe::assemble(m);  // the rotor alone: fe knows no solids
  const assembly::SolidComponent built = assembly::build_solid(m, m.solids[0]);
  const assembly::SpiderSystem ss = assembly::spider_system(m, m.solids[0], built);
  const int node = rotor.dofs.node_index(m.solids[0].spiders[0].node);
  std::vector<int> index(ss.dofs.size(), -1);
  for (std::size_t k = 0; k < ss.masters.size(); ++k)
    index[static_cast<std::size_t>(ss.masters[k])] =
        rotor.dofs.dof(node, static_cast<model::Component>(k));
  int next = rotor.size();
  for (auto& i : index)
    if (i == -1) i = next++;
  using Triplets = std::vector<Eigen::Triplet<double>>;
  auto combine = [&](const Eigen::SparseMatrix<double>& rotor_matrix,
                     const Eigen::SparseMatrix<double>& body) {
    Triplets t;
    for (int c = 0; c < rotor_matrix.outerSize(); ++c)
      for (Eigen::SparseMatrix<double>::InnerIterator it(rotor_matrix, c); it; ++it)
        t.emplace_back(static_cast<int>(it.row()), static_cast<int>(it.col()), it.value());
    for (int c = 0; c < body.outerSize(); ++c)
      for (Eigen::SparseMatrix<double>::InnerIterator it(body, c); it; ++it)
        t.emplace_back(index[static_cast<std::size_t>(it.row())],
                       index[static_cast<std::size_t>(it.col())], it.value());
    Eigen::SparseMatrix<double> out(next, next);
    out.setFromTriplets(t.begin(), t.end());
    return out;
  };
  return {combine(rotor.K, ss.K), combine(rotor.M, ss.M)};
}

// (b) Flexible plate: convergence of the Craig-Bampton coupling to the direct assembly.
TEST(SpiderValidation, FlexiblePlateConvergesToTheDirectAssembly) {
  const int kModes = 12;
  const model::Model base = parse(spider_rotor(spider_plate("steel", 0)));
  const Direct direct = direct_system(base);
  const Eigen::VectorXd f_direct = frequencies(direct.K, direct.M, kModes);
  std::printf("direct coupled system: %ld DOFs\n", static_cast<long>(direct.K.rows()));

  const std::vector<int> modes = {0, 5, 10, 20, 40};
  std::vector<Eigen::VectorXd> f(modes.size());
  std::vector<double> plate_fraction(kModes, 0.0);
  for (std::size_t k = 0; k < modes.size(); ++k) {
    const model::Model m = parse(spider_rotor(spider_plate("steel", modes[k])));
    const fe::LinearSystem s = assembly::build_system(m);
    eig::SymmetricEigenOptions o;
    o.n_modes = kModes;
    const auto r = eig::solve_symmetric(s.K, s.M, o);
    ASSERT_EQ(r.status, Status::Ok) << r.message;
    f[k] = r.eigenvalues.cwiseMax(0.0).cwiseSqrt() / (2.0 * std::numbers::pi);
    if (modes[k] == 40)
      for (int i = 0; i < kModes; ++i)
        plate_fraction[static_cast<std::size_t>(i)] =
            fe::mode_families(s, r.eigenvectors.col(i).cast<std::complex<double>>()).body;
  }
  for (int i = 0; i < kModes; ++i) {
    std::printf("mode %2d: direct %9.3f Hz | CB", i + 1, f_direct[i]);
    for (std::size_t k = 0; k < modes.size(); ++k)
      std::printf("  %d: %+.2e", modes[k], f[k][i] / f_direct[i] - 1.0);
    std::printf("  | body energy %.2f\n", plate_fraction[static_cast<std::size_t>(i)]);
    for (std::size_t k = 0; k < modes.size(); ++k) {
      // Upper bound of the direct frequency (round-off allowance 1e-9).
      EXPECT_GE(f[k][i], f_direct[i] * (1.0 - 1e-9)) << "mode " << i + 1 << ", " << modes[k];
      // Monotone in the number of modes kept.
      if (k > 0) {
        EXPECT_LE(f[k][i], f[k - 1][i] * (1.0 + 1e-9)) << "mode " << i + 1;
      }
    }
    // 40 fixed-interface modes against 12 system modes below 1.1 kHz: the error of a
    // Craig-Bampton model falls with the square of f / f_cut and of the omitted modes'
    // participation (measured: <= 8.6e-6 with 40 modes, 2.8e-3 with 5): tolerance 1e-4.
    EXPECT_NEAR(f.back()[i], f_direct[i], 1e-4 * f_direct[i]) << "mode " << i + 1;
  }
  // Convergence, not only agreement: the worst error with 40 modes is far below that with 5.
  auto worst = [&](const Eigen::VectorXd& fk) {
    return (fk.array() / f_direct.array() - 1.0).abs().maxCoeff();
  };
  EXPECT_LT(worst(f.back()), 0.05 * worst(f[1]));
  // The plate's own modes (umbrella ND 0, ND 1 coupled with shaft tilting) are among these.
  EXPECT_TRUE(
      std::any_of(plate_fraction.begin(), plate_fraction.end(), [](double x) { return x > 0.5; }));
}

// (c) averaging <= rigid for the flexible plate (nested admissible spaces, exact systems: the
// direct assemblies).
TEST(SpiderValidation, AveragingSpiderIsSofterThanRigid) {
  const int kModes = 10;
  const Direct rigid = direct_system(parse(spider_rotor(spider_plate("steel", 0, "rigid"))));
  const Direct averaging =
      direct_system(parse(spider_rotor(spider_plate("steel", 0, "averaging"))));
  const Eigen::VectorXd fr = frequencies(rigid.K, rigid.M, kModes);
  const Eigen::VectorXd fa = frequencies(averaging.K, averaging.M, kModes);
  for (int i = 0; i < kModes; ++i) {
    std::printf("mode %d: rigid spider %.4f Hz, averaging spider %.4f Hz\n", i + 1, fr[i], fa[i]);
    EXPECT_LE(fa[i], fr[i] * (1.0 + 1e-9)) << "mode " << i + 1;
  }
}

// Solid sensor: with the stiff plate the mean lateral translation of the outer ring (centroid on
// the axis at the node) equals the node's under a static lateral force at the node, to the
// plate's relative flexibility (~1e-4).
TEST(SpiderValidation, SolidSensorReadsTheRingMotion) {
  const model::Model m = parse(spider_rotor(spider_plate("stiff", 4) + R"(
[[sensors]]
name = "rim_x"
solid = "disk"
node_set = "outer"
dof = "ux"
)"));
  const fe::LinearSystem s = assembly::build_system(m);
  const int node = s.dofs.node_index("s.2");
  const Eigen::VectorXd f = s.unit_load(node, model::Component::Ux);
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> ldlt(s.K);
  const Eigen::VectorXd x = ldlt.solve(f);
  const double hub = x[s.dofs.dof(node, model::Component::Ux)];
  const double rim = x[s.dofs.dof(s.dofs.node_index("disk/outer"), model::Component::Ux)];
  std::printf("static ux: node %.9e m, outer-ring mean %.9e m\n", hub, rim);
  EXPECT_NEAR(rim, hub, 1e-4 * std::abs(hub));
}

}  // namespace
}  // namespace geardyn
