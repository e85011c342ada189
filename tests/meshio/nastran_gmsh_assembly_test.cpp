// One model, two formats: data/pair_deck.bdf (Nastran: mid-edge grids in Nastran order, three
// elements mirrored, the linear part placed through a CORD2C system, small / large / free field,
// MAT1 with E and G) and data/pair_mesh.msh (Gmsh order, positive orientation, Cartesian
// coordinates), both written by data/make_pair.py from one list of corners and one table of
// mid-edge nodes. Read independently, they must give the same mesh and, assembled by
// solid::assemble, the same K and M.
//
// Tolerance 1e-12 relative: the only numerical difference between the inputs is the position of
// the linear part's grids, given in the deck as (r, theta) with 13 and 11 decimals, i.e. off by
// < 1e-13 m on a 1 m model; K and M depend smoothly on positions, so they differ by ~1e-13 of
// their largest entry. A wrong node permutation or orientation changes entries by O(1).
#include <gtest/gtest.h>

#include "geardyn/meshio/gmsh_reader.hpp"
#include "geardyn/meshio/nastran_reader.hpp"
#include "geardyn/solid/assembly.hpp"

namespace geardyn::meshio {
namespace {

const std::string kData = std::string(GEARDYN_SOURCE_DIR) + "/tests/meshio/data/";

solid::Material material(const std::string& name, long id, double E, double nu, double rho) {
  solid::Material m;
  m.name = name;
  m.id = id;
  m.E = E;
  m.nu = nu;
  m.rho = rho;
  return m;
}

double relative_difference(const Eigen::SparseMatrix<double>& a,
                           const Eigen::SparseMatrix<double>& b) {
  const Eigen::SparseMatrix<double> d = a - b;
  double dmax = 0, bmax = 0;
  for (int k = 0; k < d.outerSize(); ++k)
    for (Eigen::SparseMatrix<double>::InnerIterator it(d, k); it; ++it)
      dmax = std::max(dmax, std::abs(it.value()));
  for (int k = 0; k < b.outerSize(); ++k)
    for (Eigen::SparseMatrix<double>::InnerIterator it(b, k); it; ++it)
      bmax = std::max(bmax, std::abs(it.value()));
  return dmax / bmax;
}

TEST(NastranAndGmsh, SameMeshAndSameMatrices) {
  const NastranDeck deck = read_nastran(kData + "pair_deck.bdf");
  EXPECT_TRUE(deck.unsupported.empty());
  EXPECT_TRUE(deck.warnings.empty());
  const solid::Mesh& a = deck.mesh;

  // The deck's MAT1 2 has E = 7e10, G = 2.8e10: NU = E / 2G - 1 = 0.25.
  GmshReadOptions options;
  options.default_material = material("MAT1_1", 1, 2.1e11, 0.3, 7800);
  options.volume_materials["linear_part"] = material("MAT1_2", 2, 7e10, 0.25, 2700);
  solid::Mesh b = read_gmsh(kData + "pair_mesh.msh", options);
  for (int n : solid::nodes_of_set(b, "fixed", {})) {
    solid::Constraint c;
    c.node = n;
    c.components = {true, true, true, false, false, false};
    b.constraints.push_back(c);
  }

  // Mesh contents.
  ASSERT_EQ(a.node_ids, b.node_ids);
  double position_error = 0;
  for (std::size_t i = 0; i < a.coords.size(); ++i)
    position_error = std::max(position_error, (a.coords[i] - b.coords[i]).norm());
  EXPECT_LE(position_error, 1e-13);
  ASSERT_EQ(a.num_elements(), b.num_elements());
  for (std::size_t e = 0; e < a.elements.size(); ++e) {
    EXPECT_EQ(a.elements[e].id, b.elements[e].id);
    EXPECT_EQ(a.elements[e].type, b.elements[e].type);
    EXPECT_EQ(a.elements[e].nodes, b.elements[e].nodes) << "element " << a.elements[e].id;
    const solid::Material& ma = a.materials[static_cast<std::size_t>(a.elements[e].material)];
    const solid::Material& mb = b.materials[static_cast<std::size_t>(b.elements[e].material)];
    EXPECT_EQ(ma.E, mb.E);
    EXPECT_EQ(ma.nu, mb.nu);
    EXPECT_EQ(ma.rho, mb.rho);
  }
  EXPECT_EQ(a.node_sets.at("SPC1_1"), b.node_sets.at("fixed"));

  // Matrices.
  const solid::SolidSystem sa = solid::assemble(a);
  const solid::SolidSystem sb = solid::assemble(b);
  ASSERT_EQ(sa.num_dofs(), sb.num_dofs());
  EXPECT_EQ(sa.num_dofs(), 3 * (42 - 8));
  const double dK = relative_difference(sa.K, sb.K);
  const double dM = relative_difference(sa.M, sb.M);
  EXPECT_LE(dK, 1e-12);
  EXPECT_LE(dM, 1e-12);
  // The comparison is not vacuous: both systems have mass 7800 V1 + 2700 V2 > 0.
  EXPECT_GT(sa.solid_mass, 0);
  EXPECT_NEAR(sa.solid_mass, sb.solid_mass, 1e-12 * sb.solid_mass);
  RecordProperty("relative_difference_K", std::to_string(dK));
  RecordProperty("relative_difference_M", std::to_string(dM));
  std::printf("relative difference K %.3e, M %.3e (%d DOFs)\n", dK, dM, sa.num_dofs());
}

}  // namespace
}  // namespace geardyn::meshio
