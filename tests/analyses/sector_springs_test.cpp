// Transverse springs on a cyclic sector through the model file: a Nastran deck of a 7-sector
// annular sector (hex8) with CELAS2 springs on ux, uy and, through a cylindrical displacement
// system (CD), along the radius, run by cyclic_modal (with compare_full) and by solid_modal with
// full_wheel. Both full-wheel models are the sector replicated with each copy's springs rotated
// with it (cyclic/replicate.hpp), the same discrete structure as the cyclic model, so the
// full-wheel spectrum is the union over nodal diameters of the cyclic spectra (Thomas,
// "Dynamics of rotationally periodic structures", Int. J. Numer. Meth. Eng. 14 (1979) 81-102).
// Tolerance 1e-8 relative: the eigen-solvers' accuracy, as the cyclic-vs-full tests.
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <string>
#include <vector>

#include "geardyn/analyses/cyclic_modal.hpp"
#include "geardyn/analyses/model_file.hpp"
#include "geardyn/analyses/registry.hpp"
#include "geardyn/analyses/solid_modal.hpp"
#include "geardyn/assembly/solid_component.hpp"
#include "geardyn/solid/structured_mesh.hpp"

namespace geardyn::analyses {
namespace {

namespace fs = std::filesystem;

// The deck: grids, CHEXAs, MAT1/PSOLID, a cylindrical system 1 about z, and springs on an
// interior node (ux), a left-face node (uy), a right-face node (radial, CD = 1) and uz of an
// interior node (along the axis: holds the out-of-plane rigid-body motion).
std::string sector_deck(int n_sectors) {
  solid::Material steel;
  steel.E = 200e9;
  steel.nu = 0.3;
  steel.rho = 7850;
  const solid::Mesh m = solid::annular_sector_mesh(
      0.05, 0.15, 0.02, 2 * std::numbers::pi / n_sectors, 2, 3, 1, solid::ElementType::Hex8, steel);
  const auto& left = m.node_sets.at("left");
  const auto& right = m.node_sets.at("right");
  std::vector<int> interior;
  for (int i = 0; i < m.num_nodes(); ++i)
    if (std::find(left.begin(), left.end(), i) == left.end() &&
        std::find(right.begin(), right.end(), i) == right.end())
      interior.push_back(i);
  const int radial_node = right[1];
  std::string deck = "BEGIN BULK\nCORD2C,1,0,0.,0.,0.,0.,0.,1.,\n,1.,0.,0.\n";
  for (int i = 0; i < m.num_nodes(); ++i) {
    const Eigen::Vector3d& x = m.coords[static_cast<std::size_t>(i)];
    deck += fmt::format("GRID,{},,{:.17E},{:.17E},{:.17E}{}\n", i + 1, x.x(), x.y(), x.z(),
                        i == radial_node ? ",1" : "");
  }
  for (int e = 0; e < m.num_elements(); ++e) {
    const auto& v = m.elements[static_cast<std::size_t>(e)].nodes;
    deck += fmt::format("CHEXA,{},1,{},{},{},{},{},{},\n,{},{}\n", e + 1, v[0] + 1, v[1] + 1,
                        v[2] + 1, v[3] + 1, v[4] + 1, v[5] + 1, v[6] + 1, v[7] + 1);
  }
  deck += "MAT1,1,2.+11,,0.3,7850.\nPSOLID,1,1\n";
  deck += fmt::format("CELAS2,1001,4.+7,{},1\n", interior.at(0) + 1);
  deck += fmt::format("CELAS2,1002,2.+7,{},2\n", left[1] + 1);
  deck += fmt::format("CELAS2,1003,3.+7,{},1\n", radial_node + 1);
  deck += fmt::format("CELAS2,1004,1.+7,{},3\n", interior.at(1) + 1);
  deck += "ENDDATA\n";
  return deck;
}

TEST(SectorSprings, CyclicModalAndFullWheelAgreeWithTransverseSprings) {
  const fs::path dir = fs::temp_directory_path() / "geardyn_sector_springs";
  fs::create_directories(dir);
  std::ofstream(dir / "sector.bdf") << sector_deck(7);
  const std::string text = R"(version = 1

[[solids]]
name = "ring"
type = "mesh"
file = "sector.bdf"
sectors = 7

[[analyses]]
name = "cyclic"
type = "cyclic_modal"
solid = "ring"
n_modes = 4
compare_full = true
shapes = 0

[[analyses]]
name = "wheel"
type = "solid_modal"
solid = "ring"
full_wheel = true
n_modes = 12
shapes = 0
)";
  const model::Model m = parse_model(text, (dir / "model.toml").string());
  const assembly::SolidComponents solids = assembly::build_solids(m);
  std::vector<Outcome> outcomes;
  for (const auto& a : m.analyses) {
    Context context(m, a);
    context.with_solids(&solids);
    outcomes.push_back(type_of(a).run(m, a, context));
    ASSERT_EQ(outcomes.back().output.status, Status::Ok) << outcomes.back().output.message;
  }
  fs::remove_all(dir);

  const auto& cyc = result_of<CyclicModalResult>(outcomes[0]);
  ASSERT_TRUE(cyc.full.done);
  EXPECT_GE(cyc.full.full_hz.size(), 12u);
  EXPECT_LT(cyc.full.worst_error, 1e-8);
  EXPECT_GT(cyc.full.full_hz.front(), 1.0);  // every rigid-body motion held by the springs

  // The full_wheel solid_modal: its 12 lowest are the cyclic ones (double modes twice).
  std::vector<double> union_hz;
  for (const auto& d : cyc.modes.diameters)
    for (Eigen::Index j = 0; j < d.frequency_hz.size(); ++j)
      for (int k = 0; k < d.multiplicity; ++k) union_hz.push_back(d.frequency_hz[j]);
  std::sort(union_hz.begin(), union_hz.end());
  const auto& wheel = result_of<SolidModalResult>(outcomes[1]);
  ASSERT_EQ(wheel.frequency_hz.size(), 12u);
  for (std::size_t j = 0; j < 12; ++j)
    EXPECT_NEAR(wheel.frequency_hz[j], union_hz[j], 1e-8 * union_hz[j]) << "mode " << j;
}

}  // namespace
}  // namespace geardyn::analyses
