// Modal analysis: tables and plots of modal_output, shift selection, input checks, reporting of
// fewer modes, and dense vs sparse on a rotor with a rigid-body mode.
// (Closed-form and published references: modal_validation_test.cpp.)
#include "geardyn/analyses/modal.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>

#include "geardyn/assembly/system_builder.hpp"
#include "geardyn/core/error.hpp"
#include "support/output_tables.hpp"
#include "support/rotor_models.hpp"

namespace geardyn::analyses {
namespace {

using C = model::Component;
constexpr double kPi = std::numbers::pi;

using test::column_names;
using test::table;

// A uniform shaft on two stiff bearings (lateral DOFs only): the output has one mode-shape plot
// for the shaft with one trace per shown mode and one point per station, and the mode_shapes
// table holds every node of every mode, normalised to 1.
model::Model shaft_on_bearings() {
  model::Model model;
  model::Material steel;
  steel.name = "steel";
  steel.youngs_modulus = 2.1e11;
  steel.shear_modulus = 8.1e10;
  steel.density = 7800;
  model.materials.push_back(steel);
  model::Shaft s;
  s.name = "rotor";
  s.material = "steel";
  model::ShaftElement e;
  e.length = 0.8;
  e.outer_diameter = 0.05;
  e.divisions = 8;
  s.elements.push_back(e);
  model.shafts.push_back(s);
  for (const char* node : {"rotor.0", "rotor.8"}) {
    model::Bearing b;
    b.node = node;
    b.stiffness = {test::diagonal6(1e8, 1e8, 0, 0, 0, 0)};
    b.damping = {test::diagonal6(200, 200, 0, 0, 0, 0)};
    model.bearings.push_back(b);
  }
  for (int i = 0; i <= 8; ++i)
    model.constraints.push_back(test::fix("rotor." + std::to_string(i), {C::Uz, C::Rz}));
  return model;
}

TEST(Modal, ShaftOutputHasShapePlotsAndNormalisedShapes) {
  const auto model = shaft_on_bearings();
  const auto system = assembly::build_system(model);
  analyses::ModalSettings settings;
  settings.n_modes = 8;
  settings.speed = 500.0;
  const ModalResult r = run_modal(model, settings, Context("modal").with_system(&system));
  ASSERT_EQ(r.status, Status::Ok) << r.message;
  const AnalysisOutput out =
      modal_output(model, settings, r, Context("modal").with_system(&system));
  ASSERT_EQ(out.plots.size(), 1u);
  EXPECT_EQ(out.plots[0].name, "mode_shapes_rotor");
  ASSERT_EQ(out.plots[0].traces.size(), 6u);
  for (const auto& tr : out.plots[0].traces) {
    EXPECT_EQ(tr.x.size(), 9u);
    EXPECT_NEAR(*std::max_element(tr.y.begin(), tr.y.end()), 1.0, 1e-12);
  }
  const Table& shapes = table(out, "mode_shapes");
  EXPECT_NO_THROW(shapes.validate());
  EXPECT_EQ(shapes.rows(), 8u * 9u);
  EXPECT_EQ(column_names(shapes),
            (std::vector<std::string>{"mode", "node", "shaft", "axial_position_m", "ux", "uy", "uz",
                                      "rx", "ry", "rz"}));
  double largest = 0.0;
  for (const char* c : {"ux", "uy", "uz", "rx", "ry", "rz"})
    for (double v : shapes.column(c).numbers) largest = std::max(largest, v);
  EXPECT_NEAR(largest, 1.0, 1e-12);
  for (const Mode& mode : r.complex) {
    EXPECT_EQ(mode.kind, ModeKind::Lateral);
    EXPECT_NE(mode.whirl, Whirl::None);  // spinning with gyroscopic shaft elements
  }
  // The lowest pair: backward below forward at speed (gyroscopic stiffening of forward whirl).
  ASSERT_GE(r.complex.size(), 2u);
  EXPECT_EQ(r.complex[0].whirl, Whirl::Backward);
  EXPECT_EQ(r.complex[1].whirl, Whirl::Forward);
}

TEST(Modal, ShiftSelectsModesNearAFrequency) {
  const auto model = shaft_on_bearings();
  const auto system = assembly::build_system(model);
  analyses::ModalSettings all;
  all.n_modes = 12;
  all.complex_modes = false;
  const ModalResult every = run_modal(model, all, Context("modal").with_system(&system));
  ASSERT_EQ(every.status, Status::Ok);
  ASSERT_EQ(every.undamped.size(), 12u);
  // Shift exactly at the 9th undamped frequency: it and its isotropic twin are nearest.
  analyses::ModalSettings near = all;
  near.n_modes = 2;
  near.shift = every.undamped[8].frequency_hz * 2 * kPi;
  const ModalResult r = run_modal(model, near, Context("modal").with_system(&system));
  ASSERT_EQ(r.status, Status::Ok) << r.message;
  ASSERT_EQ(r.undamped.size(), 2u);
  for (const Mode& mode : r.undamped)
    EXPECT_NEAR(mode.frequency_hz, every.undamped[8].frequency_hz,
                1e-8 * every.undamped[8].frequency_hz);
  // Without complex modes the "modes" table lists the undamped ones.
  const AnalysisOutput out = modal_output(model, all, every, Context("m").with_system(&system));
  EXPECT_EQ(table(out, "modes").rows(), 12u);
  EXPECT_EQ(table(out, "modes").column("damping_ratio").numbers[0], 0.0);
}

TEST(Modal, InvalidSettingsThrowInputError) {
  const auto model = test::jeffcott(1.0, 1.0, 0.0);
  const auto system = assembly::build_system(model);
  analyses::ModalSettings bad;
  bad.n_modes = 0;
  EXPECT_THROW(run_modal(model, bad, Context("modal").with_system(&system)), InputError);
  bad.n_modes = 1;
  bad.shift = -1.0;
  EXPECT_THROW(run_modal(model, bad, Context("modal").with_system(&system)), InputError);
}

// More modes asked than the model has: the modes that exist, status ok, and a note that says
// so (not a failure at run time that check did not foresee).
TEST(Modal, FewerModesThanAskedIsReportedNotHidden) {
  const auto model = test::jeffcott(10.0, 1e6, 10.0);
  const auto system = assembly::build_system(model);
  analyses::ModalSettings settings;
  settings.n_modes = 5;  // the system has two
  const ModalResult r = run_modal(model, settings, Context("modal").with_system(&system));
  EXPECT_EQ(r.status, Status::Ok) << r.message;
  EXPECT_EQ(r.complex.size(), 2u);
  EXPECT_NE(r.fewer_modes_note.find("2"), std::string::npos) << r.fewer_modes_note;
  const AnalysisOutput out = modal_output(model, settings, r, Context("m").with_system(&system));
  EXPECT_EQ(out.status, Status::Ok);
  EXPECT_NE(out.notes[0].find("n_modes = 5"), std::string::npos) << out.notes[0];
}

}  // namespace
}  // namespace geardyn::analyses

namespace geardyn::analyses {
namespace {

// A free-free-in-torsion rotor: 40 Timoshenko elements, two disks, two damped bearings acting
// laterally and axially only, spinning. Torsion is a rigid-body motion (lambda = 0, a double root
// of the quadratic problem), the rest is gyroscopic and non-proportionally damped. Dense (every
// eigenvalue of the state operator) and sparse (shift-invert Arnoldi) are independent paths and
// must agree to the Arnoldi tolerance on the elastic modes.
model::Model free_torsion_rotor() {
  model::Model model = shaft_on_bearings();
  model.constraints.clear();
  model.shafts[0].elements[0].divisions = 40;
  model.bearings.clear();
  for (const char* node : {"rotor.0", "rotor.40"}) {
    model::Bearing b;
    b.node = node;
    b.stiffness = {test::diagonal6(2e7, 3e7, 1e8, 0, 0, 0)};
    b.damping = {test::diagonal6(800, 1200, 500, 0, 0, 0)};
    model.bearings.push_back(b);
  }
  for (const char* node : {"rotor.12", "rotor.30"}) {
    model::Disk d;
    d.node = node;
    d.mass = 8.0;
    d.diametral_inertia = 0.05;
    d.polar_inertia = 0.09;
    model.disks.push_back(d);
  }
  return model;
}

TEST(Modal, DenseAndSparseAgreeOnARotorWithARigidBodyMode) {
  const auto model = free_torsion_rotor();
  const auto system = assembly::build_system(model);
  ASSERT_EQ(system.size(), 41 * 6);
  analyses::ModalSettings settings;
  settings.n_modes = 10;
  settings.speed = 6000.0 * 2 * kPi / 60.0;
  settings.method = analyses::EigenMethod::Dense;
  const ModalResult dense = run_modal(model, settings, Context("modal").with_system(&system));
  settings.method = analyses::EigenMethod::Sparse;
  const ModalResult sparse = run_modal(model, settings, Context("modal").with_system(&system));
  ASSERT_EQ(dense.status, Status::Ok) << dense.message;
  ASSERT_EQ(sparse.status, Status::Ok) << sparse.message;
  ASSERT_EQ(dense.complex.size(), 10u);
  ASSERT_EQ(sparse.complex.size(), 10u);
  EXPECT_TRUE(dense.complex[0].rigid_body);
  EXPECT_TRUE(sparse.complex[0].rigid_body);
  for (std::size_t j = 0; j < 10; ++j) {
    if (dense.complex[j].rigid_body) continue;
    const auto a = dense.complex[j].eigenvalue, b = sparse.complex[j].eigenvalue;
    EXPECT_LE(std::abs(a - b), 1e-8 * std::abs(a)) << "mode " << j + 1 << ": " << a << " vs " << b;
    EXPECT_EQ(dense.complex[j].whirl, sparse.complex[j].whirl) << "mode " << j + 1;
    EXPECT_EQ(dense.complex[j].kind, sparse.complex[j].kind) << "mode " << j + 1;
  }
  for (std::size_t j = 0; j < dense.undamped.size(); ++j)
    EXPECT_NEAR(dense.undamped[j].frequency_hz, sparse.undamped[j].frequency_hz,
                1e-8 * std::max(1.0, dense.undamped[j].frequency_hz));
}

}  // namespace
}  // namespace geardyn::analyses
