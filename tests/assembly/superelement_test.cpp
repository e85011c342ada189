// Unit tests of the DofMap's appended nodes and generalised coordinates, and of joining a
// superelement (a body given by matrices) to the rotor system.
#include "geardyn/fe/superelement.hpp"

#include <gtest/gtest.h>

#include <limits>
#include <stdexcept>

#include "geardyn/core/error.hpp"
#include "geardyn/fe/dof_map.hpp"
#include "geardyn/fe/element_types.hpp"
#include "geardyn/fe/linear_system.hpp"
#include "geardyn/fe/rigid_disk.hpp"

namespace geardyn::fe {
namespace {

using model::Component;

// One free node "hub" whose spin axis is global x (frame != identity), torsion fixed.
model::Model hub_model() {
  model::Model m;
  model::Node hub;
  hub.name = "hub";
  hub.position = {0.0, 0.0, 0.0};
  hub.axis = {1.0, 0.0, 0.0};
  hub.speed_ratio = 1.0;
  m.nodes.push_back(hub);
  model::Constraint c;
  c.node = "hub";
  c.dofs = {Component::Rz};
  m.constraints.push_back(c);
  return m;
}

TEST(DofMapAppend, NodesAndGeneralisedCoordinatesAfterTheModel) {
  DofMap map = DofMap::build(hub_model());
  ASSERT_EQ(map.num_dofs(), 5);
  NodeInfo sensor;
  sensor.name = "disk/outer";
  sensor.frame = Eigen::Matrix3d::Identity();
  const int index = map.add_node(sensor, {true, true, true, false, false, false});
  EXPECT_EQ(index, 1);
  EXPECT_EQ(map.num_nodes(), 2);
  EXPECT_EQ(map.dof(index, Component::Ux), 5);
  EXPECT_EQ(map.dof(index, Component::Uz), 7);
  EXPECT_EQ(map.dof(index, Component::Rx), -1);
  EXPECT_EQ(map.dof_node(6), index);
  EXPECT_EQ(map.dof_component(6), Component::Uy);
  EXPECT_EQ(map.find_node("disk/outer"), index);

  const int first = map.add_generalized("disk", 3);
  EXPECT_EQ(first, 8);
  EXPECT_EQ(map.num_dofs(), 11);
  EXPECT_EQ(map.num_generalized(), 3);
  ASSERT_EQ(map.generalized().size(), 1u);
  EXPECT_EQ(map.generalized()[0].name, "disk");
  EXPECT_EQ(map.generalized()[0].first, 8);
  EXPECT_EQ(map.generalized()[0].count, 3);
  EXPECT_TRUE(map.is_generalized(10));
  EXPECT_FALSE(map.is_generalized(7));
  EXPECT_EQ(map.dof_node(9), -1);
  // A generalised coordinate has no component: asking is a bug, not a silent Ux.
  EXPECT_THROW((void)map.dof_component(9), std::logic_error);
  // Node DOFs of the model keep their numbers.
  EXPECT_EQ(map.dof(0, Component::Ux), 0);
  EXPECT_EQ(map.dof(0, Component::Rz), -1);

  EXPECT_THROW(map.add_generalized("disk", 1), InputError);
  EXPECT_THROW(map.add_node(sensor, {true, true, true, false, false, false}), InputError);
}

// A body with one point on "hub", given in global axes, enters the node-frame equations as
// R^T A R with R = blockdiag(F, F): e.g. a rigid disk about global x written in global axes must
// give the same matrices as [[disks]] at the node (whose frame has e3 = x).
TEST(Superelement, RotatedIntoTheNodeFrame) {
  const double m = 3.0, Id = 0.02, Ip = 0.05;
  model::Model with_disk = hub_model();
  model::Disk disk;
  disk.name = "d";
  disk.node = "hub";
  disk.mass = m;
  disk.polar_inertia = Ip;
  disk.diametral_inertia = Id;
  with_disk.disks.push_back(disk);
  const LinearSystem reference = assemble(with_disk);

  const DofMap map = DofMap::build(hub_model());
  const Matrix6d R = node_rotation(map.node(0).frame);
  Superelement body;
  body.name = "disk";
  SuperelementPoint point;
  point.node = "hub";
  body.points.push_back(point);
  body.M = R * rigid_disk_mass(m, Id, Ip) * R.transpose();
  body.K = Eigen::MatrixXd::Identity(6, 6) * 1e6;  // isotropic: the same in every frame
  body.G = R * rigid_disk_gyroscopic(Ip) * R.transpose();
  const LinearSystem joined = assemble(hub_model(), {}, {body});
  ASSERT_EQ(joined.size(), reference.size());
  EXPECT_LT((Eigen::MatrixXd(joined.M) - Eigen::MatrixXd(reference.M)).norm(), 1e-14);
  EXPECT_LT((Eigen::MatrixXd(joined.G) - Eigen::MatrixXd(reference.G)).norm(), 1e-14);
  EXPECT_LT((Eigen::MatrixXd(joined.K) - 1e6 * Eigen::MatrixXd::Identity(5, 5)).norm(), 1e-8);
}

// New nodes and generalised coordinates: a 2-point body (a model node + a new sensor node with
// translations only) with 2 modal coordinates; the matrices land where the DofMap says.
TEST(Superelement, NewNodesAndGeneralisedCoordinates) {
  Superelement body;
  body.name = "plate";
  SuperelementPoint joint;
  joint.node = "hub";
  SuperelementPoint sensor;
  sensor.node = "plate/rim";
  sensor.new_node = true;
  sensor.position = {0.0, 0.1, 0.0};
  sensor.components = {true, true, true, false, false, false};
  body.points = {joint, sensor};
  body.n_generalized = 2;
  ASSERT_EQ(body.n_physical(), 9);
  ASSERT_EQ(body.size(), 11);
  Eigen::MatrixXd K = Eigen::MatrixXd::Zero(11, 11);
  for (int i = 0; i < 11; ++i) K(i, i) = 1.0 + i;
  K(9, 6) = K(6, 9) = 0.5;  // modal coordinate 1 - sensor ux
  body.K = K;
  body.M = Eigen::MatrixXd::Identity(11, 11);
  const LinearSystem s = assemble(hub_model(), {}, {body});
  const DofMap& d = s.dofs;
  ASSERT_EQ(s.size(), 5 + 3 + 2);
  const int rim = d.find_node("plate/rim");
  ASSERT_GE(rim, 0);
  EXPECT_EQ(d.node(rim).shaft, -1);
  EXPECT_NEAR((d.node(rim).position - Eigen::Vector3d(0.0, 0.1, 0.0)).norm(), 0.0, 0.0);
  const int ux = d.dof(rim, Component::Ux);
  const int eta0 = d.generalized().at(0).first;
  EXPECT_EQ(eta0, 8);
  EXPECT_DOUBLE_EQ(s.K.coeff(ux, ux), 7.0);
  EXPECT_DOUBLE_EQ(s.K.coeff(eta0, eta0), 10.0);
  EXPECT_DOUBLE_EQ(s.K.coeff(eta0, ux), 0.5);
  EXPECT_DOUBLE_EQ(s.K.coeff(eta0 + 1, eta0 + 1), 11.0);
  EXPECT_EQ(d.dof(rim, Component::Rx), -1);

  // Energy families: a shape only in the modal coordinates is all "body".
  Eigen::VectorXcd shape = Eigen::VectorXcd::Zero(s.size());
  shape(eta0) = 1.0;
  const ModeFamilies f = mode_families(s, shape);
  EXPECT_DOUBLE_EQ(f.body, 1.0);
  EXPECT_DOUBLE_EQ(f.lateral + f.axial + f.torsional, 0.0);
}

TEST(Superelement, BadInput) {
  Superelement body;
  body.name = "plate";
  body.points.push_back({});
  body.points.back().node = "nowhere";
  body.K = body.M = Eigen::MatrixXd::Identity(6, 6);
  EXPECT_THROW(assemble(hub_model(), {}, {body}), InputError);  // unknown node
  body.points.back().node = "hub";
  body.K = Eigen::MatrixXd::Identity(5, 5);
  EXPECT_THROW(assemble(hub_model(), {}, {body}), InputError);  // wrong size
  body.K = Eigen::MatrixXd::Identity(6, 6);
  body.K(0, 0) = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(assemble(hub_model(), {}, {body}), InputError);  // not finite
}

}  // namespace
}  // namespace geardyn::fe
