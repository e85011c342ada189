// The scalar outputs of the solid-component analyses (solid_modal, cyclic_modal, reduction):
// each read from the typed result, checked against that result, against the table the analysis
// prints, and against an independent solve of the same mesh.
//
// Solid: an annular steel plate, 8 sectors of 45 deg, clamped at the inner radius (a coarse
// version of examples/annular_plate_cyclic).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

#include "geardyn/analyses/cyclic_modal.hpp"
#include "geardyn/analyses/model_file.hpp"
#include "geardyn/analyses/reduction.hpp"
#include "geardyn/analyses/registry.hpp"
#include "geardyn/analyses/solid_modal.hpp"
#include "support/gear_models.hpp"

namespace geardyn::analyses {
namespace {

using namespace test;

const std::string kModel = R"(version = 1
[[materials]]
name = "steel"
youngs_modulus = 200e9
poisson_ratio = 0.3
density = 7850

[[solids]]
name = "plate"
type = "annular_plate"
material = "steel"
inner_radius = 0.05
outer_radius = 0.2
thickness = 0.01
sectors = 8
radial_elements = 3
circumferential_elements = 2
layers = 1
order = 2
fixed_sets = ["inner"]

[[analyses]]
name = "cyclic"
type = "cyclic_modal"
solid = "plate"
n_modes = 2
compare_full = true
shapes = 0

[[analyses]]
name = "wheel"
type = "solid_modal"
solid = "plate"
full_wheel = true
n_modes = 6
shapes = 0

[[analyses]]
name = "sector"
type = "solid_modal"
solid = "plate"
n_modes = 5
shapes = 0

[[analyses]]
name = "reduced"
type = "reduction"
solid = "plate"
master_sets = ["left", "right"]
reduced_modes = 12
n_modes = 5
save = false
)";

class SolidScalars : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    // Parsed from text (no file): the ctest processes of this suite share nothing on disk.
    model_ = new model::Model(parse_model(kModel, "solid_scalars.toml"));
    outcomes_ = new std::vector<Outcome>();
    for (const auto& a : model_->analyses) {
      Context context(*model_, a);
      context.with_solids(&solids());
      outcomes_->push_back(type_of(a).run(*model_, a, context));
    }
  }
  static void TearDownTestSuite() {
    delete outcomes_;
    delete model_;
  }
  static const assembly::SolidComponents& solids() {
    static const assembly::SolidComponents built = assembly::build_solids(*model_);
    return built;
  }

  static double scalar(std::size_t i, const std::string& quantity, int mode = 1,
                       std::string* unit = nullptr) {
    ScalarRequest q;
    q.quantity = quantity;
    q.mode = mode;
    std::string u;
    const double v = type_of(model_->analyses[i]).scalar((*outcomes_)[i], q, u);
    if (unit != nullptr) *unit = u;
    return v;
  }
  static const Outcome& outcome(std::size_t i) { return (*outcomes_)[i]; }

  static model::Model* model_;
  static std::vector<Outcome>* outcomes_;
};

model::Model* SolidScalars::model_ = nullptr;
std::vector<Outcome>* SolidScalars::outcomes_ = nullptr;

// natural_frequency of solid_modal: mode n of the typed result and of the printed modes table
// (exactly), ascending. The whole wheel is the same mesh as the cyclic solve, whose lowest
// frequency is the lowest of every nodal diameter: equal to round-off of the two eigen-solves
// (residuals ~1e-16, moderate condition numbers; 1e-8 as in the example's test).
TEST_F(SolidScalars, SolidModalNaturalFrequency) {
  const auto& r = result_of<SolidModalResult>(outcome(1));
  const Table& modes = table(outcome(1).output, "modes");
  std::string unit;
  for (int n = 1; n <= 6; ++n) {
    const double f = scalar(1, "natural_frequency", n, &unit);
    EXPECT_EQ(unit, "Hz");
    EXPECT_EQ(f, r.frequency_hz[static_cast<std::size_t>(n - 1)]);
    EXPECT_EQ(f, modes.column("frequency_hz").numbers[static_cast<std::size_t>(n - 1)]);
    if (n > 1) {
      EXPECT_GE(f, scalar(1, "natural_frequency", n - 1));
    }
  }
  const double f1 = scalar(0, "natural_frequency", 1);
  EXPECT_NEAR(scalar(1, "natural_frequency", 1), f1, 1e-8 * f1);
  EXPECT_THROW(scalar(1, "natural_frequency", 7), std::runtime_error);
  EXPECT_THROW(scalar(1, "natural_frequency", 0), std::runtime_error);
}

// natural_frequency of cyclic_modal: mode n over all nodal diameters in ascending order, a
// double mode counted once: the sorted frequency column of the printed cyclic_modes table
// (exactly). Against the full wheel, where a double mode appears twice: the distinct
// frequencies of the wheel's 6 lowest modes are the cyclic ones to 1e-8 (see above).
TEST_F(SolidScalars, CyclicModalNaturalFrequencyOverAllNodalDiameters) {
  const auto& r = result_of<CyclicModalResult>(outcome(0));
  std::vector<double> sorted =
      table(outcome(0).output, "cyclic_modes").column("frequency_hz").numbers;
  std::sort(sorted.begin(), sorted.end());
  ASSERT_EQ(sorted.size(), r.frequency_hz.size());
  ASSERT_EQ(sorted.size(), 10u);  // ND 0 .. 4, 2 modes each
  for (std::size_t n = 1; n <= sorted.size(); ++n)
    EXPECT_EQ(scalar(0, "natural_frequency", static_cast<int>(n)), sorted[n - 1]) << n;
  EXPECT_THROW(scalar(0, "natural_frequency", 11), std::runtime_error);

  const Table& full = table(outcome(0).output, "cyclic_vs_full");
  for (std::size_t j = 0; j < full.rows(); ++j) {
    const double f = full.column("full_hz").numbers[j];
    const auto near = std::find_if(sorted.begin(), sorted.end(),
                                   [&](double c) { return std::abs(c - f) <= 1e-8 * f; });
    EXPECT_NE(near, sorted.end()) << "full-wheel mode " << j + 1 << " at " << f << " Hz";
  }
}

// max_frequency_error: the largest |error_pct| of the typed result and of the printed
// reduction_frequencies table (exactly), and 100 (f_reduced - f_full) / f_full from the
// frequencies of the same sector solved by solid_modal (round-off of two eigen-solves on
// frequencies of order 1e3 Hz: 1e-6 %). Craig-Bampton is Rayleigh-Ritz: errors >= 0.
// reduced_dofs: the master DOFs of the two sector faces plus the 12 fixed-interface modes.
TEST_F(SolidScalars, ReductionErrorAndSize) {
  const auto& r = result_of<ReductionResult>(outcome(3));
  std::string unit;
  const double e = scalar(3, "max_frequency_error", 1, &unit);
  EXPECT_EQ(unit, "%");
  EXPECT_EQ(e, r.max_error_pct);
  double worst = 0.0, worst_independent = 0.0;
  const Table& cmp = table(outcome(3).output, "reduction_frequencies");
  ASSERT_EQ(cmp.rows(), 5u);
  for (std::size_t j = 0; j < cmp.rows(); ++j) {
    worst = std::max(worst, std::abs(cmp.column("error_pct").numbers[j]));
    const double full = scalar(2, "natural_frequency", static_cast<int>(j + 1));
    const double reduced = cmp.column("reduced_hz").numbers[j];
    EXPECT_GE(reduced, full * (1 - 1e-10)) << "mode " << j + 1;
    worst_independent = std::max(worst_independent, std::abs(100.0 * (reduced - full) / full));
  }
  EXPECT_EQ(e, worst);
  EXPECT_NEAR(e, worst_independent, 1e-6);
  EXPECT_GT(e, 0.0);

  const double n = scalar(3, "reduced_dofs");
  EXPECT_EQ(n, static_cast<double>(r.reduced->size()));
  EXPECT_EQ(n, static_cast<double>(r.master_dofs + 12));
}

// check accepted it, so run must not refuse it: more fixed-interface modes than the interior
// has (known only once the masters are chosen), and convergence counts beyond them. All
// interior modes are kept — the Craig-Bampton basis then spans the whole space, so the reduced
// frequencies equal the full ones up to the eigen-solvers' accuracy (1e-6 %: the full modes
// come from an iterative solve converged to ~1e-10 in the residual, and the projection on the
// constraint modes loses a few digits more; measured 6.7e-8 %) — and the notes say what was
// left out.
TEST(Reduction, ModeCountsBeyondTheInteriorAreKeptToWhatExistsWithANote) {
  std::string text = kModel;
  const std::string asked = "reduced_modes = 12\n";
  text.replace(text.find(asked), asked.size(), "reduced_modes = 400\nconvergence = [0, 10, 300]\n");
  const model::Model m = parse_model(text, "beyond_interior.toml");
  const assembly::SolidComponents solids = assembly::build_solids(m);
  const model::Analysis& a = *m.find_analysis("reduced");
  Context context(m, a);
  context.with_solids(&solids);
  const Outcome o = type_of(a).run(m, a, context);
  ASSERT_EQ(o.output.status, Status::Ok) << o.output.message;
  const auto& r = result_of<ReductionResult>(o);
  EXPECT_EQ(r.modes_asked_beyond_interior, 400);
  EXPECT_EQ(r.reduced->size(), static_cast<int>(solids.at("plate").system.K.rows()));
  EXPECT_LT(r.max_error_pct, 1e-6);
  const Table& conv = table(o.output, "reduction_convergence");
  EXPECT_EQ(conv.column("n_modes").numbers, (std::vector<double>{0, 10}));
  bool said_interior = false, said_dropped = false;
  for (const auto& note : o.output.notes) {
    said_interior = said_interior || note.find("reduced_modes = 400 exceeds") != std::string::npos;
    said_dropped = said_dropped || note.find("the counts 300 exceed") != std::string::npos;
  }
  EXPECT_TRUE(said_interior);
  EXPECT_TRUE(said_dropped);
}

}  // namespace
}  // namespace geardyn::analyses
