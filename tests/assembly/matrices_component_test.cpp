// [[solids]] type = "matrices": stiffness and mass exported by another FE code (Matrix Market)
// with a DOF map, used as a cyclic sector. The oracle is the same sector built from its mesh:
// geardyn writes the mesh's K, M and DOF map (the form ANSYS / Nastran exports take), reads them
// back as a "matrices" component and must give the same cyclic frequencies, with and without
// Craig-Bampton + interface-mode reduction. Values are written in shortest round-trip form, so
// the matrices agree to round-off (the symmetric files keep the lower triangle) and what is left
// is the solver's round-off: tolerance 1e-9 relative (Ritz values converge to 1e-10).
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <string>

#include "geardyn/analyses/cyclic_modal.hpp"
#include "geardyn/analyses/model_file.hpp"
#include "geardyn/analyses/registry.hpp"
#include "geardyn/analyses/run_analysis.hpp"
#include "geardyn/assembly/solid_component.hpp"
#include "geardyn/core/error.hpp"
#include "geardyn/meshio/matrix_market.hpp"
#include "geardyn/model/parse.hpp"

namespace geardyn {
namespace {

namespace fs = std::filesystem;

// A coarse 24-sector annular plate (the geometry of examples/annular_plate_cyclic), clamped at
// the inner radius: 1 050 DOFs per sector.
const std::string kMaterials = R"(version = 1
[[materials]]
name = "steel"
youngs_modulus = 200e9
poisson_ratio = 0.33
density = 7850
)";

const std::string kPlate = R"(
[[solids]]
name = "plate"
type = "annular_plate"
material = "steel"
inner_radius = 0.03
outer_radius = 0.3
thickness = 0.01
sectors = 24
radial_elements = 6
circumferential_elements = 1
layers = 1
order = 2
fixed_sets = ["inner"]
)";

std::string cyclic_analysis(const std::string& extra) {
  return R"(
[[analyses]]
name = "cyclic"
type = "cyclic_modal"
solid = "plate"
n_modes = 3
nodal_diameters = [0, 1, 2, 3, 12]
shapes = 0
)" + extra;
}

class MatricesComponent : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           ("geardyn_matrices_" +
            std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()));
    fs::create_directories(dir_);
    const model::Model mesh_model =
        analyses::parse_model(kMaterials + kPlate, (dir_ / "mesh.toml").string());
    mesh_ = assembly::build_solid(mesh_model, mesh_model.solids.front());
    meshio::write_matrix_market(dir_ / "K.mtx", mesh_.system.K, true);
    meshio::write_matrix_market(dir_ / "M.mtx", mesh_.system.M, true);
    meshio::write_dof_map_csv(dir_ / "dofs.csv", mesh_.system.dofs);
  }
  void TearDown() override { fs::remove_all(dir_); }

  static std::string matrices_solid(const std::string& extra = "") {
    return R"(
[[solids]]
name = "plate"
type = "matrices"
stiffness_file = "K.mtx"
mass_file = "M.mtx"
dof_map_file = "dofs.csv"
sectors = 24
)" + extra;
  }

  model::Model parse(const std::string& text) const {
    return analyses::parse_model(text, (dir_ / "model.toml").string());
  }

  // Frequencies of the cyclic_modal table of a run on `solid`.
  static std::vector<double> cyclic_frequencies(const model::Model& m,
                                                const assembly::SolidComponent& solid) {
    const auto& a = m.analyses.front();
    const auto& s = a.settings_of<analyses::CyclicModalSettings>();
    const assembly::SolidComponents solids = {{s.solid, solid}};
    analyses::Context context(m, a);
    context.with_solids(&solids);
    const analyses::CyclicModalResult r = analyses::run_cyclic_modal(m, s, context);
    const AnalysisOutput out = analyses::cyclic_modal_output(m, s, r, context);
    return out.tables.front().column("frequency_hz").numbers;
  }

  fs::path dir_;
  assembly::SolidComponent mesh_;
};

TEST_F(MatricesComponent, GivesTheCyclicFrequenciesOfTheMeshItCameFrom) {
  const model::Model m = parse(kMaterials + matrices_solid() + cyclic_analysis(""));
  const assembly::SolidComponent external = assembly::build_solid(m, m.solids.front());
  EXPECT_TRUE(external.external_matrices);
  EXPECT_FALSE(external.has_mesh());
  EXPECT_EQ(external.system.num_dofs(), mesh_.system.num_dofs());
  // The symmetric file keeps the lower triangle: equal up to the assembly's round-off asymmetry.
  EXPECT_LT((external.system.K - mesh_.system.K).norm(), 1e-15 * mesh_.system.K.norm());

  const model::Model mesh_model = parse(kMaterials + kPlate + cyclic_analysis(""));
  const std::vector<double> reference = cyclic_frequencies(mesh_model, mesh_);
  const std::vector<double> imported = cyclic_frequencies(m, external);
  ASSERT_EQ(reference.size(), 15u);
  ASSERT_EQ(imported.size(), reference.size());
  // The two routes factorise differently ordered patterns (the mesh's K keeps explicit zeros
  // the file drops), so the Lanczos iterations take different rounding paths; their converged
  // frequencies agree to the eigen-solver's accuracy: up to 1.9e-9 relative measured (AMD EPYC,
  // Debian 12's OpenBLAS and SuiteSparse), so 1e-8.
  for (std::size_t i = 0; i < reference.size(); ++i)
    EXPECT_NEAR(imported[i], reference[i], 1e-8 * reference[i]) << "row " << i;
  // Sanity of the oracle: ND 0..3 lowest frequencies near Leissa's thin-plate values (115.60,
  // 95.05, 150.10, 333.83 Hz) within the 8 % a mesh this coarse allows (one hex20 layer).
  const double leissa[] = {115.60, 95.05, 150.10, 333.83};
  for (int h = 0; h < 4; ++h) EXPECT_NEAR(imported[3 * h], leissa[h], 0.08 * leissa[h]) << h;
}

TEST_F(MatricesComponent, CraigBamptonAndInterfaceModesWorkOnImportedMatrices) {
  const std::string reduce =
      "reduction = \"craig_bampton\"\nreduced_modes = 20\n"
      "interface_modes = 12\n";
  const model::Model m = parse(kMaterials + matrices_solid() + cyclic_analysis(reduce));
  const model::Model mesh_model = parse(kMaterials + kPlate + cyclic_analysis(reduce));
  const assembly::SolidComponent external = assembly::build_solid(m, m.solids.front());
  const std::vector<double> reference = cyclic_frequencies(mesh_model, mesh_);
  const std::vector<double> imported = cyclic_frequencies(m, external);
  ASSERT_EQ(imported.size(), reference.size());
  for (std::size_t i = 0; i < reference.size(); ++i)
    EXPECT_NEAR(imported[i], reference[i], 1e-9 * reference[i]) << "row " << i;
}

// The drivers' own checks are located by the analysis's Context: a reduction of a component
// without a mesh names analyses[0].solid at the analysis's line (expected and found as before).
TEST_F(MatricesComponent, DriverErrorsNameTheAnalysisKey) {
  auto error_of = [&](const std::string& text) -> InputError {
    const model::Model m = parse(text);
    const model::Analysis& a = m.analyses.front();
    try {
      (void)analyses::type_of(a).run(m, a, analyses::Context(m, a));
    } catch (const InputError& e) {
      return e;
    }
    ADD_FAILURE() << "no error";
    return InputError({}, "", "", "");
  };
  const InputError e = error_of(kMaterials + matrices_solid() + R"(
[[analyses]]
name = "reduce"
type = "reduction"
solid = "plate"
master_sets = ["outer"]
)");
  EXPECT_EQ(e.key_path(), "analyses[0].solid");
  EXPECT_EQ(e.found(), "solid 'plate' of type \"matrices\"");
  EXPECT_GT(e.where().line, 0);
}

TEST_F(MatricesComponent, BadInputNamesTheKey) {
  auto expect_error = [&](const std::string& text, const std::string& key) {
    try {
      const model::Model m = parse(text);
      const assembly::SolidComponents solids = assembly::build_solids(m);
      analyses::check_inputs(m, solids);
      FAIL() << "no error for key " << key;
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find(key), std::string::npos) << e.what();
    }
  };
  // A missing file.
  std::string text = kMaterials + matrices_solid() + cyclic_analysis("");
  text.replace(text.find("M.mtx"), 5, "none.mtx");
  expect_error(text, "solids[0].mass_file");
  // Node sets do not exist without a mesh.
  expect_error(kMaterials + matrices_solid() +
                   cyclic_analysis("reduction = \"craig_bampton\"\nmaster_sets = [\"outer\"]\n"),
               "analyses[0].master_sets[0]");
  // A key of another type.
  expect_error(kMaterials + matrices_solid("material = \"steel\"\n") + cyclic_analysis(""),
               "material");
  // K and M of different sizes.
  meshio::write_matrix_market(dir_ / "M_small.mtx",
                              Eigen::SparseMatrix<double>(mesh_.system.M.topLeftCorner(30, 30)),
                              true);
  text = kMaterials + matrices_solid() + cyclic_analysis("");
  text.replace(text.find("\"M.mtx\""), 7, "\"M_small.mtx\"");
  expect_error(text, "M_small.mtx");
}

}  // namespace
}  // namespace geardyn
