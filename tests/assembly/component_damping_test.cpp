// Modal damping of a component joined to the rotor ([[solids]] modal_damping_ratio,
// docs/theory.md §9, eq. 9.4): C_eta = diag(2 zeta omega_k) in the fixed-interface modal block.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <string>

#include "geardyn/analyses/modal.hpp"
#include "geardyn/analyses/model_file.hpp"
#include "geardyn/assembly/solid_coupling.hpp"
#include "geardyn/assembly/system_builder.hpp"
#include "geardyn/core/error.hpp"
#include "spider_test_support.hpp"

namespace geardyn {
namespace {

using test::spider_plate;
using test::spider_rotor;

model::Model parse(const std::string& text) { return analyses::parse_model(text, "damped.toml"); }

// The plate of spider_test_support.hpp held by one rigid spider to a node fixed in all six DOFs:
// the coupled system is the plate's fixed-interface component alone (M_eta = I, K_eta = Lambda).
std::string grounded_plate(const std::string& ratio_line) {
  return R"(version = 1

[[materials]]
name = "steel"
youngs_modulus = 2.1e11
poisson_ratio = 0.3
density = 7800.0

[[nodes]]
name = "hub"
position = [0.0, 0.0, 0.0]

[[constraints]]
node = "hub"
dofs = ["ux", "uy", "uz", "rx", "ry", "rz"]

[[solids]]
name = "disk"
type = "annular_plate"
material = "steel"
inner_radius = 0.02
outer_radius = 0.15
thickness = 0.01
radial_elements = 4
circumferential_elements = 24
layers = 1
order = 2
coupling_modes = 6
)" + ratio_line +
         R"(
  [[solids.spiders]]
  node_set = "inner"
  node = "hub"
  kind = "rigid"
)";
}

// A damping matrix diagonal in the undamped modal coordinates makes each mode an SDOF
// q'' + 2 zeta omega q' + omega^2 q = 0 with roots lambda = omega (-zeta +- i sqrt(1 - zeta^2)),
// so -Re(lambda) / |lambda| = zeta and |lambda| = omega exactly (Craig & Kurdila, Fundamentals
// of Structural Dynamics, 2nd ed., 2006, sec. 10.3 on modal damping). What is left is the
// round-off of M_eta = Phi^T M Phi = I (about 1e-13 here) and of the complex eigen-solve,
// far below the 1e-8 asked.
TEST(ComponentModalDamping, EveryFixedInterfaceModeGetsTheRatio) {
  constexpr double zeta = 0.03;
  const model::Model model = parse(grounded_plate("modal_damping_ratio = 0.03"));
  const auto coupled = assembly::couple_solids(model, nullptr);
  ASSERT_EQ(coupled.size(), 1u);
  const Eigen::VectorXd& f_hz = coupled[0].reduced.fixed_interface_hz;
  ASSERT_EQ(f_hz.size(), 6);

  const fe::LinearSystem system = assembly::build_system(model);
  ASSERT_EQ(system.size(), 6);  // the hub's DOFs are held: only the modal coordinates remain
  analyses::ModalSettings settings;
  settings.n_modes = 6;
  const auto r =
      analyses::run_modal(model, settings, analyses::Context("modal").with_system(&system));
  ASSERT_EQ(r.status, Status::Ok) << r.message;
  ASSERT_EQ(r.complex.size(), 6u);
  for (std::size_t k = 0; k < r.complex.size(); ++k) {
    const double omega = 2.0 * std::numbers::pi * f_hz[static_cast<Eigen::Index>(k)];
    EXPECT_NEAR(r.complex[k].damping_ratio, zeta, 1e-8) << "mode " << k + 1;
    EXPECT_NEAR(std::abs(r.complex[k].eigenvalue), omega, 1e-8 * omega) << "mode " << k + 1;
  }
}

// The constraint modes stay undamped: on the rotor, the body adds C only to the modal block, so
// the system's C is T^T C_body T with nothing on the rotor nodes' DOFs from the plate (the
// rotor's bearings carry no damping here, so C is the plate's modal damping alone).
TEST(ComponentModalDamping, OnlyTheModalCoordinatesAreDamped) {
  const std::string plate = spider_plate("steel", 4);
  const std::string key = "coupling_modes = 4\n";
  const std::string damped = plate.substr(0, plate.find(key) + key.size()) +
                             "modal_damping_ratio = 0.05\n" +
                             plate.substr(plate.find(key) + key.size());
  const fe::LinearSystem system = assembly::build_system(parse(spider_rotor(damped)));
  const Eigen::MatrixXd C(system.C);
  const Eigen::MatrixXd K(system.K);
  int damped_equations = 0;
  for (int eq = 0; eq < system.size(); ++eq) {
    if (!system.dofs.is_generalized(eq)) {
      EXPECT_EQ(C.row(eq).norm(), 0.0) << "equation " << eq;
      continue;
    }
    ++damped_equations;
    // 2 zeta sqrt(lambda) with lambda = K_eta (diagonal): exact up to the sqrt's rounding.
    EXPECT_NEAR(C(eq, eq), 2.0 * 0.05 * std::sqrt(K(eq, eq)), 1e-14 * C(eq, eq));
    EXPECT_EQ(C.row(eq).norm(), std::abs(C(eq, eq)));
  }
  EXPECT_EQ(damped_equations, 4);
}

// Without the key (or with 0) the body adds no damping: the system is the one of before.
TEST(ComponentModalDamping, AbsentKeyLeavesTheSystemUndamped) {
  const model::Model model = parse(spider_rotor(spider_plate("steel", 4)));
  EXPECT_EQ(model.solids.at(0).modal_damping_ratio, 0.0);
  const auto coupled = assembly::couple_solids(model, nullptr);
  EXPECT_EQ(coupled.at(0).body.C.size(), 0);
  const fe::LinearSystem system = assembly::build_system(model);
  EXPECT_EQ(system.C.nonZeros(), 0);
}

// A ratio outside [0, 1) is a located input error naming the key.
TEST(ComponentModalDamping, BadRatioIsALocatedError) {
  for (const char* value : {"-0.01", "1.0", "2.5"}) {
    try {
      parse(grounded_plate(std::string("modal_damping_ratio = ") + value));
      ADD_FAILURE() << value << " accepted";
    } catch (const InputError& e) {
      EXPECT_NE(e.key_path().find("modal_damping_ratio"), std::string::npos) << e.what();
      EXPECT_EQ(e.where().file, "damped.toml");
      EXPECT_GT(e.where().line, 0);
    }
  }
}

}  // namespace
}  // namespace geardyn
