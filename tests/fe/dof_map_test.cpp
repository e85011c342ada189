// Unit tests of the DOF map: node naming and positions, node frames, constraint elimination.
#include "geardyn/fe/dof_map.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "fe_test_support.hpp"
#include "geardyn/core/error.hpp"

namespace geardyn::fe {
namespace {

using model::Component;

model::Model two_shafts() {
  model::Model m;
  m.materials.push_back(test::material("steel", 2e11, 8e10, 7800));
  model::Shaft a = test::uniform_shaft("a", "steel", 1.0, 0.05, 2);
  model::ShaftElement extra = a.elements.front();
  extra.length = 0.3;
  extra.divisions = 3;
  a.elements.push_back(extra);
  a.origin = {1.0, 2.0, 3.0};
  a.speed_ratio = 2.5;
  model::Shaft b = test::uniform_shaft("b", "steel", 0.5, 0.05, 1);
  b.axis = {1.0, 0.0, 0.0};
  b.speed_ratio = -1.0;
  m.shafts = {a, b};
  model::Node free;
  free.name = "housing";
  free.position = {0.0, 0.0, 1.0};
  free.axis = {0.0, 1.0, 0.0};
  free.speed_ratio = 0.5;
  m.nodes.push_back(free);
  return m;
}

TEST(DofMap, ShaftStationsThenFreeNodes) {
  const DofMap map = DofMap::build(two_shafts());
  ASSERT_EQ(map.num_nodes(), 6 + 2 + 1);
  EXPECT_EQ(map.node(0).name, "a.0");
  EXPECT_EQ(map.node(5).name, "a.5");
  EXPECT_EQ(map.node(6).name, "b.0");
  EXPECT_EQ(map.node(8).name, "housing");
  EXPECT_EQ(map.num_dofs(), 9 * 6);
  // a.3 is the first division of the second section: z = 1.0 + 0.1.
  const NodeInfo& a3 = map.node(map.node_index("a.3"));
  EXPECT_NEAR(a3.axial_position, 1.1, 1e-15);
  EXPECT_NEAR((a3.position - Eigen::Vector3d(1.0, 2.0, 4.1)).norm(), 0.0, 1e-14);
  EXPECT_EQ(a3.shaft, 0);
  EXPECT_EQ(a3.station, 3);
  EXPECT_DOUBLE_EQ(a3.speed_ratio, 2.5);
  EXPECT_DOUBLE_EQ(map.node(7).speed_ratio, -1.0);
  EXPECT_NEAR((map.node(7).position - Eigen::Vector3d(0.5, 0, 0)).norm(), 0.0, 1e-15);
  EXPECT_DOUBLE_EQ(map.node(8).speed_ratio, 0.5);
  EXPECT_EQ(map.node(8).shaft, -1);
  EXPECT_EQ(map.find_node("nope"), -1);
  EXPECT_THROW((void)map.node_index("nope"), std::out_of_range);
}

TEST(DofMap, ConstraintsEliminateDofs) {
  model::Model m = two_shafts();
  m.constraints.push_back(test::constrain("a.0", {Component::Ux, Component::Rz}));
  m.constraints.push_back(test::constrain(
      "housing",
      {Component::Ux, Component::Uy, Component::Uz, Component::Rx, Component::Ry, Component::Rz}));
  const DofMap map = DofMap::build(m);
  EXPECT_EQ(map.num_dofs(), 9 * 6 - 8);
  EXPECT_EQ(map.dof(0, Component::Ux), -1);
  EXPECT_EQ(map.dof(0, Component::Uy), 0);
  EXPECT_EQ(map.dof(0, Component::Rz), -1);
  EXPECT_EQ(map.dof(1, Component::Ux), 4);
  for (int c = 0; c < 6; ++c) EXPECT_EQ(map.node_dofs(8)[static_cast<std::size_t>(c)], -1);
  // The inverse map agrees with the forward map for every equation.
  for (int e = 0; e < map.num_dofs(); ++e)
    EXPECT_EQ(map.dof(map.dof_node(e), map.dof_component(e)), e);
}

TEST(DofMap, UnknownConstraintNodeIsInputError) {
  model::Model m = two_shafts();
  m.constraints.push_back(test::constrain("a.99", {Component::Ux}));
  EXPECT_THROW((void)DofMap::build(m), InputError);
}

TEST(DofMap, DuplicateNodeNameIsInputError) {
  model::Model m = two_shafts();
  m.nodes.front().name = "a.1";
  EXPECT_THROW((void)DofMap::build(m), InputError);
}

TEST(DofMap, ZeroAxisIsInputError) {
  model::Model m = two_shafts();
  m.shafts[1].axis = {0.0, 0.0, 0.0};
  EXPECT_THROW((void)DofMap::build(m), InputError);
}

TEST(FrameFromAxis, OrthonormalRightHandedWithAxisAsE3) {
  const std::vector<Eigen::Vector3d> axes = {{0, 0, 1}, {0, 0, -1},       {1, 0, 0},   {0, 1, 0},
                                             {1, 1, 1}, {0.9, 0.1, -0.3}, {-1, 0.2, 0}};
  for (const Eigen::Vector3d& axis : axes) {
    const Eigen::Matrix3d R = frame_from_axis(axis);
    EXPECT_NEAR((R.transpose() * R - Eigen::Matrix3d::Identity()).norm(), 0.0, 1e-14);
    EXPECT_NEAR(R.determinant(), 1.0, 1e-14);
    EXPECT_NEAR((R.col(2) - axis.normalized()).norm(), 0.0, 1e-14);
  }
  EXPECT_NEAR((frame_from_axis({0, 0, 1}) - Eigen::Matrix3d::Identity()).norm(), 0.0, 1e-15);
  // Axis within 30 deg of x: e1 comes from global y.
  const Eigen::Matrix3d Rx = frame_from_axis({1, 0, 0});
  EXPECT_NEAR((Rx.col(0) - Eigen::Vector3d::UnitY()).norm(), 0.0, 1e-15);
  EXPECT_NEAR((Rx.col(1) - Eigen::Vector3d::UnitZ()).norm(), 0.0, 1e-15);
  // Axis along y: e1 is global x.
  EXPECT_NEAR((frame_from_axis({0, 1, 0}).col(0) - Eigen::Vector3d::UnitX()).norm(), 0.0, 1e-15);
}

}  // namespace
}  // namespace geardyn::fe
