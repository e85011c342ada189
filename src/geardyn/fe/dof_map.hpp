#pragma once
// The one owner of DOF numbering. Every node has six DOFs (ux, uy, uz, rx, ry, rz) in its own
// frame (columns e1, e2, e3 of `frame`, e3 = spin axis). Constrained DOFs are eliminated: they
// have no equation number. Nodes: shaft stations in model order ("<shaft>.<k>"), then free nodes.
// Bodies joined to the model (reduced solids, fe/superelement.hpp) may then append nodes of their
// own (add_node) and generalised coordinates that belong to no node (add_generalized, e.g. the
// fixed-interface modal coordinates of a Craig-Bampton body). Equations are numbered in the order
// they are added, so the model's node DOFs keep their numbers.
#include <Eigen/Dense>
#include <array>
#include <string>
#include <unordered_map>
#include <vector>

#include "geardyn/model/model.hpp"

namespace geardyn::fe {

struct NodeInfo {
  std::string name;
  Eigen::Vector3d position;
  Eigen::Matrix3d frame;   ///< columns e1, e2, e3 in global coordinates; u_global = frame * u_node
  double speed_ratio = 0;  ///< spin speed / reference speed (sign: sense about e3)
  int shaft = -1;          ///< index into model.shafts, -1 for a free node
  int station = -1;        ///< station index along the shaft
  double axial_position = 0;  ///< distance from the shaft origin along the axis [m]
};

/// A named range of generalised coordinates (equations first .. first + count - 1).
struct GeneralizedRange {
  std::string name;
  int first = 0;
  int count = 0;
};

class DofMap {
 public:
  /// Builds nodes and numbering from the model. Throws InputError for constraints naming an
  /// unknown node (the parser normally catches that first).
  static DofMap build(const model::Model& model);

  int num_nodes() const { return static_cast<int>(nodes_.size()); }
  int num_dofs() const { return num_dofs_; }
  const NodeInfo& node(int index) const { return nodes_.at(static_cast<std::size_t>(index)); }
  const std::vector<NodeInfo>& nodes() const { return nodes_; }
  /// Node index by name, -1 if there is none.
  int find_node(const std::string& name) const;
  /// Node index by name; throws std::out_of_range naming the node.
  int node_index(const std::string& name) const;
  /// Equation number of a node DOF, -1 when constrained.
  int dof(int node, model::Component c) const {
    return equation_[static_cast<std::size_t>(node) * 6 + static_cast<std::size_t>(c)];
  }
  /// Inverse map: node and component of an equation. dof_node is -1 for a generalised
  /// coordinate; dof_component throws std::logic_error for one (it has no component: check
  /// is_generalized first).
  int dof_node(int equation) const { return dof_node_[static_cast<std::size_t>(equation)]; }
  model::Component dof_component(int equation) const;
  /// True for an equation that is a generalised coordinate (no node).
  bool is_generalized(int equation) const { return dof_node(equation) < 0; }
  /// The 6 equation numbers of a node (-1 where constrained).
  std::array<int, 6> node_dofs(int node) const;

  /// Appends a node that is not in the model (e.g. a sensor point of a coupled solid): the
  /// components with active[c] get the next equation numbers, the others none (-1). Returns its
  /// index. Throws InputError (key `key`) when the name is taken.
  int add_node(NodeInfo info, const std::array<bool, 6>& active, const std::string& key = "node");
  /// Appends `count` >= 0 generalised coordinates named `name` (unique among the ranges).
  /// Returns the equation number of the first. Throws InputError for a repeated name.
  int add_generalized(const std::string& name, int count);
  const std::vector<GeneralizedRange>& generalized() const { return generalized_; }
  /// Number of generalised coordinates of all ranges.
  int num_generalized() const;

 private:
  std::vector<NodeInfo> nodes_;
  std::unordered_map<std::string, int> by_name_;
  std::vector<int> equation_;
  std::vector<int> dof_node_;
  std::vector<model::Component> dof_component_;
  std::vector<GeneralizedRange> generalized_;
  int num_dofs_ = 0;
};

/// A right-handed orthonormal frame with e3 = axis: e1 is global x projected on the plane normal
/// to the axis (global y if the axis is within 30 deg of x), e2 = e3 x e1. For axis = z this is
/// the global frame.
Eigen::Matrix3d frame_from_axis(const Eigen::Vector3d& axis);

/// Candidate rigid-body motions in equation space (n x c): for the whole model, each shaft and
/// the set of nodes on no shaft, the three global translations, the three rotations about
/// global axes through the set's centroid and the spin of the set (rz = 1 in the node frames);
/// and the spin of the whole drive train, rz = speed_ratio at every node (gears turning
/// together). Generalised coordinates (modal coordinates of coupled solids) are 0.
Eigen::MatrixXd rigid_body_candidates(const DofMap& dofs);

}  // namespace geardyn::fe
