// Gmsh reader: physical groups, materials, errors, and the node order of quadratic elements
// checked against meshes Gmsh itself generates (a mid-edge node of a straight edge lies at the
// midpoint of the corners that gmsh_edges() names; this validates that table against Gmsh).
#include "geardyn/meshio/gmsh_reader.hpp"

#include <gmsh.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "geardyn/meshgen/gmsh_session.hpp"
#include "geardyn/meshio/element_ordering.hpp"

namespace geardyn::meshio {
namespace {

namespace fs = std::filesystem;
const std::string kData = std::string(GEARDYN_SOURCE_DIR) + "/tests/meshio/data/";

solid::Material material(const std::string& name, double E, double nu, double rho) {
  solid::Material m;
  m.name = name;
  m.E = E;
  m.nu = nu;
  m.rho = rho;
  return m;
}

GmshReadOptions pair_options() {
  GmshReadOptions options;
  options.default_material = material("steel", 2.1e11, 0.3, 7800);
  options.volume_materials["linear_part"] = material("aluminium", 7e10, 0.25, 2700);
  return options;
}

GmshReadOptions box_options() {
  GmshReadOptions options;
  options.default_material = material("steel", 2.1e11, 0.3, 7800);
  return options;
}

int index_of(const solid::Mesh& mesh, long id) {
  const auto it = std::find(mesh.node_ids.begin(), mesh.node_ids.end(), id);
  return it == mesh.node_ids.end() ? -1 : static_cast<int>(it - mesh.node_ids.begin());
}

// pair_mesh.msh (written by data/make_pair.py): volume 1 "quadratic_part" (hex20, prism15,
// tet10: 11 corners + 20 mid-edge nodes), volume 2 "linear_part" (hex8, prism6, tet4: 11 nodes),
// surface "fixed" (the hex20's bottom face, 8 nodes, one quad8), point "tip" (node 31).
TEST(GmshReader, PhysicalGroupsAndMaterials) {
  const solid::Mesh mesh = read_gmsh(kData + "pair_mesh.msh", pair_options());
  ASSERT_EQ(mesh.num_nodes(), 42);
  EXPECT_TRUE(std::is_sorted(mesh.node_ids.begin(), mesh.node_ids.end()));
  ASSERT_EQ(mesh.num_elements(), 6);  // the quad8 and the point element are not volume elements
  const std::vector<solid::ElementType> types = {
      solid::ElementType::Hex20, solid::ElementType::Wedge15, solid::ElementType::Tet10,
      solid::ElementType::Hex8,  solid::ElementType::Wedge6,  solid::ElementType::Tet4};
  const std::vector<long> ids = {1, 2, 3, 11, 12, 13};
  for (std::size_t e = 0; e < 6; ++e) {
    EXPECT_EQ(mesh.elements[e].type, types[e]);
    EXPECT_EQ(mesh.elements[e].id, ids[e]);
  }
  EXPECT_EQ(mesh.element_sets.at("quadratic_part"), (std::vector<int>{0, 1, 2}));
  EXPECT_EQ(mesh.element_sets.at("linear_part"), (std::vector<int>{3, 4, 5}));
  EXPECT_EQ(mesh.element_sets.count("fixed"), 0u);
  EXPECT_EQ(mesh.node_sets.at("quadratic_part").size(), 31u);
  EXPECT_EQ(mesh.node_sets.at("linear_part").size(), 11u);
  std::vector<int> fixed;
  for (long id : {1, 2, 3, 4, 101, 102, 104, 106}) fixed.push_back(index_of(mesh, id));
  std::sort(fixed.begin(), fixed.end());
  EXPECT_EQ(mesh.node_sets.at("fixed"), fixed);
  EXPECT_EQ(mesh.node_sets.at("tip"), (std::vector<int>{index_of(mesh, 31)}));
  ASSERT_EQ(mesh.materials.size(), 2u);
  EXPECT_EQ(mesh.materials[static_cast<std::size_t>(mesh.elements[0].material)].name, "steel");
  EXPECT_EQ(mesh.materials[static_cast<std::size_t>(mesh.elements[3].material)].name, "aluminium");
  EXPECT_EQ(mesh.materials[static_cast<std::size_t>(mesh.elements[3].material)].E, 7e10);
}

TEST(GmshReader, Errors) {
  // Missing file.
  try {
    (void)read_gmsh(kData + "no_such_file.msh", pair_options());
    FAIL() << "no InputError";
  } catch (const InputError& e) {
    EXPECT_EQ(e.key_path(), "file");
  }
  // A material for a physical volume the file does not have: the available ones are listed.
  GmshReadOptions options = pair_options();
  options.volume_materials["hub"] = material("steel", 2.1e11, 0.3, 7800);
  try {
    (void)read_gmsh(kData + "pair_mesh.msh", options);
    FAIL() << "no InputError";
  } catch (const InputError& e) {
    EXPECT_EQ(e.key_path(), "volume_materials");
    EXPECT_EQ(e.found(), "'hub'");
    EXPECT_NE(e.hint().find("linear_part, quadratic_part"), std::string::npos) << e.what();
  }
  // No default material although elements need it.
  options = pair_options();
  options.default_material = solid::Material{};
  options.default_material.where = SourceLocation{"model.toml", 12, 3};
  try {
    (void)read_gmsh(kData + "pair_mesh.msh", options);
    FAIL() << "no InputError";
  } catch (const InputError& e) {
    EXPECT_EQ(e.key_path(), "default_material.E");
    EXPECT_EQ(e.where().file, "model.toml");
    EXPECT_EQ(e.where().line, 12);
  }
}

class GmshFiles : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           ("geardyn_gmsh_" +
            std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()));
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  fs::path dir_;
};

TEST_F(GmshFiles, UnreadableAndUnsupportedFiles) {
  std::ofstream(dir_ / "garbage.msh") << "this is not a mesh\n";
  try {
    (void)read_gmsh(dir_ / "garbage.msh", box_options());
    FAIL() << "no InputError";
  } catch (const InputError& e) {
    EXPECT_NE(e.found().find("Gmsh"), std::string::npos) << e.what();
  }
  // One pyramid (type 7).
  std::ofstream(dir_ / "pyramid.msh")
      << "$MeshFormat\n4.1 0 8\n$EndMeshFormat\n$Nodes\n1 5 1 5\n3 1 0 5\n1\n2\n3\n4\n5\n"
         "0 0 0\n1 0 0\n1 1 0\n0 1 0\n0.5 0.5 1\n$EndNodes\n$Elements\n1 1 1 1\n3 1 7 1\n"
         "1 1 2 3 4 5\n$EndElements\n";
  try {
    (void)read_gmsh(dir_ / "pyramid.msh", box_options());
    FAIL() << "no InputError";
  } catch (const InputError& e) {
    EXPECT_NE(e.found().find("type 7"), std::string::npos) << e.what();
  }
  // Surface elements only.
  std::ofstream(dir_ / "surface.msh")
      << "$MeshFormat\n4.1 0 8\n$EndMeshFormat\n$Nodes\n1 3 1 3\n2 1 0 3\n1\n2\n3\n"
         "0 0 0\n1 0 0\n0 1 0\n$EndNodes\n$Elements\n1 1 1 1\n2 1 2 1\n1 1 2 3\n$EndElements\n";
  try {
    (void)read_gmsh(dir_ / "surface.msh", box_options());
    FAIL() << "no InputError";
  } catch (const InputError& e) {
    EXPECT_EQ(e.key_path(), "elements");
  }
}

enum class Shape { Tet, Hex, Prism };

// A 1 x 1 x 1 box meshed by Gmsh with second-order elements of the requested shape, written to
// `path` (physical volume "box", physical surface "bottom").
void generate_box(Shape shape, const fs::path& path) {
  meshgen::GmshSession session("box");
  if (shape == Shape::Tet) {
    gmsh::model::occ::addBox(0, 0, 0, 1, 1, 1);
    gmsh::model::occ::synchronize();
    gmsh::option::setNumber("Mesh.MeshSizeMax", 0.5);
  } else {
    const int surface = gmsh::model::occ::addRectangle(0, 0, 0, 1, 1);
    gmsh::vectorpair out;
    gmsh::model::occ::extrude({{2, surface}}, 0, 0, 1, out, {2}, {}, true);
    gmsh::model::occ::synchronize();
    gmsh::option::setNumber("Mesh.MeshSizeMax", 0.5);
    if (shape == Shape::Hex) {
      gmsh::model::mesh::setTransfiniteAutomatic();
    }
  }
  gmsh::model::addPhysicalGroup(3, {1}, 1);
  gmsh::model::setPhysicalName(3, 1, "box");
  gmsh::vectorpair surfaces;
  gmsh::model::getEntities(surfaces, 2);
  gmsh::model::addPhysicalGroup(2, {surfaces.front().second}, 2);
  gmsh::model::setPhysicalName(2, 2, "bottom");
  gmsh::model::mesh::generate(3);
  gmsh::model::mesh::setOrder(2);
  gmsh::write(path.string());
}

TEST_F(GmshFiles, GmshGeneratedQuadraticElementsMatchTheEdgeTable) {
  const std::vector<std::pair<Shape, solid::ElementType>> cases = {
      {Shape::Tet, solid::ElementType::Tet10},
      {Shape::Hex, solid::ElementType::Hex20},
      {Shape::Prism, solid::ElementType::Wedge15}};
  for (const auto& [shape, type] : cases) {
    const fs::path path = dir_ / "box.msh";
    generate_box(shape, path);
    const solid::Mesh mesh = read_gmsh(path, box_options());
    ASSERT_GT(mesh.num_elements(), 0);
    double volume = 0;
    for (const solid::Element& e : mesh.elements) {
      ASSERT_EQ(e.type, type) << solid::to_string(type);
      const double measure = corner_volume_measure(e.type, e.nodes, mesh.coords);
      EXPECT_GT(measure, 0);
      const auto edges = gmsh_edges(e.type);
      const std::size_t corners = static_cast<std::size_t>(num_corner_nodes(e.type));
      for (std::size_t k = 0; k < edges.size(); ++k) {
        const Eigen::Vector3d& a = mesh.coords[static_cast<std::size_t>(
            e.nodes[static_cast<std::size_t>(edges[k].first)])];
        const Eigen::Vector3d& b = mesh.coords[static_cast<std::size_t>(
            e.nodes[static_cast<std::size_t>(edges[k].second)])];
        const Eigen::Vector3d& m = mesh.coords[static_cast<std::size_t>(e.nodes[corners + k])];
        ASSERT_LE((m - 0.5 * (a + b)).norm(), 1e-12)
            << solid::to_string(type) << " element " << e.id << " edge " << k;
      }
      // The corner volume measure is 6 V for a tet and V for parallelepipeds and right prisms.
      volume += measure / (type == solid::ElementType::Tet10 ? 6.0 : 1.0);
    }
    // The elements fill the unit box: straight-sided, so the corner volumes add up to 1.
    EXPECT_NEAR(volume, 1.0, 1e-12) << solid::to_string(type);
    EXPECT_EQ(mesh.element_sets.at("box").size(), static_cast<std::size_t>(mesh.num_elements()));
    EXPECT_FALSE(mesh.node_sets.at("bottom").empty());
  }
}

}  // namespace
}  // namespace geardyn::meshio
