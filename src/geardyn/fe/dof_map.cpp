#include "geardyn/fe/dof_map.hpp"

#include <fmt/format.h>

#include <cmath>
#include <stdexcept>

#include "geardyn/core/error.hpp"

namespace geardyn::fe {
namespace {

Eigen::Vector3d to_vector(const model::Vec3& v) { return {v[0], v[1], v[2]}; }

// A unit axis, or an InputError naming the key: a zero axis would give no frame at all.
Eigen::Vector3d unit_axis(const model::Vec3& axis, const SourceLocation& where,
                          const std::string& key_path) {
  const Eigen::Vector3d a = to_vector(axis);
  const double length = a.norm();
  if (!(length > 0.0) || !std::isfinite(length)) {
    throw InputError(where, key_path, "a non-zero finite axis vector",
                     fmt::format("[{}, {}, {}]", axis[0], axis[1], axis[2]));
  }
  return a / length;
}

}  // namespace

Eigen::Matrix3d frame_from_axis(const Eigen::Vector3d& axis) {
  const Eigen::Vector3d e3 = axis.normalized();
  // cos(30 deg): beyond it the projection of global x would be short and ill-conditioned.
  const double kCos30 = std::sqrt(3.0) / 2.0;
  const Eigen::Vector3d reference =
      std::abs(e3.x()) > kCos30 ? Eigen::Vector3d::UnitY() : Eigen::Vector3d::UnitX();
  const Eigen::Vector3d e1 = (reference - reference.dot(e3) * e3).normalized();
  const Eigen::Vector3d e2 = e3.cross(e1);
  Eigen::Matrix3d frame;
  frame.col(0) = e1;
  frame.col(1) = e2;
  frame.col(2) = e3;
  return frame;
}

DofMap DofMap::build(const model::Model& model) {
  DofMap map;
  auto add_node = [&map](NodeInfo info, const SourceLocation& where, const std::string& key) {
    if (map.by_name_.count(info.name) != 0) {
      throw InputError(where, key, "a unique node name",
                       fmt::format("'{}' defined twice", info.name));
    }
    map.by_name_.emplace(info.name, static_cast<int>(map.nodes_.size()));
    map.nodes_.push_back(std::move(info));
  };

  for (std::size_t s = 0; s < model.shafts.size(); ++s) {
    const model::Shaft& shaft = model.shafts[s];
    const std::string key = fmt::format("shafts[{}]", s);
    const Eigen::Vector3d axis = unit_axis(shaft.axis, shaft.where, key + ".axis");
    const Eigen::Matrix3d frame = frame_from_axis(axis);
    const Eigen::Vector3d origin = to_vector(shaft.origin);
    double z = 0.0;
    int station = 0;
    auto add_station = [&]() {
      NodeInfo info;
      info.name = fmt::format("{}.{}", shaft.name, station);
      info.position = origin + z * axis;
      info.frame = frame;
      info.speed_ratio = shaft.speed_ratio;
      info.shaft = static_cast<int>(s);
      info.station = station;
      info.axial_position = z;
      add_node(std::move(info), shaft.where, key);
      ++station;
    };
    add_station();
    for (std::size_t e = 0; e < shaft.elements.size(); ++e) {
      const model::ShaftElement& element = shaft.elements[e];
      if (element.divisions < 1) {
        throw InputError(element.where, fmt::format("{}.elements[{}].divisions", key, e),
                         "an integer >= 1", std::to_string(element.divisions));
      }
      if (!(element.length > 0.0)) {
        throw InputError(element.where, fmt::format("{}.elements[{}].length", key, e),
                         "a positive length [m]", fmt::format("{}", element.length));
      }
      const double start = z;
      for (int d = 1; d <= element.divisions; ++d) {
        // Measured from the section start so that rounding does not drift over divisions.
        z = start + element.length * d / element.divisions;
        add_station();
      }
    }
  }

  for (std::size_t n = 0; n < model.nodes.size(); ++n) {
    const model::Node& node = model.nodes[n];
    const std::string key = fmt::format("nodes[{}]", n);
    NodeInfo info;
    info.name = node.name;
    info.position = to_vector(node.position);
    info.frame = frame_from_axis(unit_axis(node.axis, node.where, key + ".axis"));
    info.speed_ratio = node.speed_ratio;
    add_node(std::move(info), node.where, key + ".name");
  }

  const std::size_t n_nodes = map.nodes_.size();
  std::vector<bool> fixed(n_nodes * 6, false);
  // DOF sets: the model's `dofs`, a shaft's own `dofs` for its nodes; a component outside the
  // set is absent, like a constrained one.
  for (std::size_t k = 0; k < n_nodes; ++k) {
    const int shaft = map.nodes_[k].shaft;
    const model::Shaft* owner =
        shaft >= 0 ? &model.shafts[static_cast<std::size_t>(shaft)] : nullptr;
    const model::DofSet set = owner != nullptr && owner->dofs ? *owner->dofs : model.dofs;
    const std::array<bool, 6> kept = model::dof_set_components(set);
    for (std::size_t c = 0; c < 6; ++c)
      if (!kept[c]) fixed[k * 6 + c] = true;
  }
  for (std::size_t c = 0; c < model.constraints.size(); ++c) {
    const model::Constraint& constraint = model.constraints[c];
    const int index = map.find_node(constraint.node);
    if (index < 0) {
      throw InputError(constraint.where, fmt::format("constraints[{}].node", c),
                       "the name of a shaft station or node", fmt::format("'{}'", constraint.node));
    }
    for (model::Component component : constraint.dofs) {
      fixed[static_cast<std::size_t>(index) * 6 + static_cast<std::size_t>(component)] = true;
    }
  }

  map.equation_.assign(n_nodes * 6, -1);
  for (std::size_t i = 0; i < n_nodes * 6; ++i) {
    if (fixed[i]) continue;
    map.equation_[i] = map.num_dofs_++;
    map.dof_node_.push_back(static_cast<int>(i / 6));
    map.dof_component_.push_back(static_cast<model::Component>(i % 6));
  }
  return map;
}

int DofMap::find_node(const std::string& name) const {
  const auto it = by_name_.find(name);
  return it == by_name_.end() ? -1 : it->second;
}

int DofMap::node_index(const std::string& name) const {
  const int index = find_node(name);
  if (index < 0) throw std::out_of_range(fmt::format("DofMap: no node named '{}'", name));
  return index;
}

model::Component DofMap::dof_component(int equation) const {
  if (dof_node(equation) < 0)
    throw std::logic_error(fmt::format(
        "DofMap: equation {} is a generalised coordinate, with no component", equation));
  return dof_component_[static_cast<std::size_t>(equation)];
}

int DofMap::add_node(NodeInfo info, const std::array<bool, 6>& active, const std::string& key) {
  if (by_name_.count(info.name) != 0) {
    throw InputError({}, key, "a unique node name", fmt::format("'{}' defined twice", info.name));
  }
  const int index = static_cast<int>(nodes_.size());
  by_name_.emplace(info.name, index);
  nodes_.push_back(std::move(info));
  for (std::size_t c = 0; c < 6; ++c) {
    if (!active[c]) {
      equation_.push_back(-1);
      continue;
    }
    equation_.push_back(num_dofs_++);
    dof_node_.push_back(index);
    dof_component_.push_back(static_cast<model::Component>(c));
  }
  return index;
}

int DofMap::add_generalized(const std::string& name, int count) {
  for (const GeneralizedRange& r : generalized_) {
    if (r.name == name) {
      throw InputError({}, name, "a unique name for a range of generalised coordinates",
                       fmt::format("'{}' twice", name));
    }
  }
  if (count < 0) throw std::logic_error("DofMap::add_generalized: negative count");
  const int first = num_dofs_;
  generalized_.push_back({name, first, count});
  for (int k = 0; k < count; ++k) {
    dof_node_.push_back(-1);
    // Never read: dof_component refuses generalised coordinates.
    dof_component_.push_back(model::Component::Ux);
    ++num_dofs_;
  }
  return first;
}

int DofMap::num_generalized() const {
  int n = 0;
  for (const GeneralizedRange& r : generalized_) n += r.count;
  return n;
}

std::array<int, 6> DofMap::node_dofs(int node) const {
  std::array<int, 6> dofs{};
  for (int c = 0; c < 6; ++c)
    dofs[static_cast<std::size_t>(c)] = dof(node, static_cast<model::Component>(c));
  return dofs;
}

Eigen::MatrixXd rigid_body_candidates(const DofMap& dofs) {
  const int n = dofs.num_dofs();
  int n_shafts = 0;
  for (const auto& node : dofs.nodes()) n_shafts = std::max(n_shafts, node.shaft + 1);
  // Sets: the whole model (-2), each shaft (0 .. n_shafts - 1), nodes on no shaft (-1).
  std::vector<int> sets = {-2, -1};
  for (int s = 0; s < n_shafts; ++s) sets.push_back(s);
  std::vector<Eigen::VectorXd> columns;
  auto in_set = [](const NodeInfo& node, int set) { return set == -2 || node.shaft == set; };
  auto put = [&](Eigen::VectorXd& v, int k, const Eigen::Vector3d& u, const Eigen::Vector3d& r) {
    const auto eq = dofs.node_dofs(k);
    for (std::size_t c = 0; c < 3; ++c) {
      if (eq[c] >= 0) v[eq[c]] = u[static_cast<Eigen::Index>(c)];
      if (eq[c + 3] >= 0) v[eq[c + 3]] = r[static_cast<Eigen::Index>(c)];
    }
  };
  for (int set : sets) {
    Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
    int count = 0;
    for (const auto& node : dofs.nodes())
      if (in_set(node, set)) {
        centroid += node.position;
        ++count;
      }
    if (count == 0) continue;
    centroid /= count;
    for (int axis = 0; axis < 3; ++axis) {
      const Eigen::Vector3d a = Eigen::Vector3d::Unit(axis);
      Eigen::VectorXd translation = Eigen::VectorXd::Zero(n), rotation = Eigen::VectorXd::Zero(n);
      for (int k = 0; k < dofs.num_nodes(); ++k) {
        const NodeInfo& node = dofs.node(k);
        if (!in_set(node, set)) continue;
        const Eigen::Matrix3d Ft = node.frame.transpose();
        put(translation, k, Ft * a, Eigen::Vector3d::Zero());
        put(rotation, k, Ft * a.cross(node.position - centroid), Ft * a);
      }
      columns.push_back(std::move(translation));
      columns.push_back(std::move(rotation));
    }
    Eigen::VectorXd spin = Eigen::VectorXd::Zero(n);
    for (int k = 0; k < dofs.num_nodes(); ++k)
      if (in_set(dofs.node(k), set))
        put(spin, k, Eigen::Vector3d::Zero(), Eigen::Vector3d::UnitZ());
    columns.push_back(std::move(spin));
  }
  Eigen::VectorXd train = Eigen::VectorXd::Zero(n);
  for (int k = 0; k < dofs.num_nodes(); ++k)
    put(train, k, Eigen::Vector3d::Zero(), Eigen::Vector3d(0.0, 0.0, dofs.node(k).speed_ratio));
  columns.push_back(std::move(train));
  Eigen::MatrixXd candidates(n, static_cast<Eigen::Index>(columns.size()));
  for (std::size_t c = 0; c < columns.size(); ++c)
    candidates.col(static_cast<Eigen::Index>(c)) = columns[c];
  return candidates;
}

}  // namespace geardyn::fe
