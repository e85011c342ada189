#include "geardyn/assembly/static_deflection.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <tuple>
#include <utility>
#include <vector>

#include "geardyn/assembly/solid_coupling.hpp"
#include "geardyn/fe/gear_mesh_element.hpp"
#include "geardyn/fe/linear_system.hpp"
#include "geardyn/linalg/sparse_factorization.hpp"
#include "geardyn/linalg/submatrix.hpp"

namespace geardyn::assembly {

namespace {

// The rotor without the linked mesh's spring (the tooth force is the load instead).
fe::LinearSystem system_without_mesh(const model::Model& model, std::size_t mesh_index) {
  model::Model copy = model;
  copy.gear_meshes.erase(copy.gear_meshes.begin() + static_cast<std::ptrdiff_t>(mesh_index));
  std::vector<fe::Superelement> bodies;
  if (has_joined_solids(copy))
    for (CoupledSolid& solid : couple_solids(copy, nullptr))
      bodies.push_back(std::move(solid.body));
  return fe::assemble(copy, {}, bodies);
}

// The equations kept for the static solve: every DOF but the torsional ones (rz).
std::vector<int> kept_equations(const fe::DofMap& dofs) {
  std::vector<int> keep;
  for (int eq = 0; eq < dofs.num_dofs(); ++eq)
    if (dofs.is_generalized(eq) || dofs.dof_component(eq) != model::Component::Rz)
      keep.push_back(eq);
  return keep;
}

struct RigidMotion {
  std::string what;
  Eigen::VectorXd shape;  // over the kept equations
};

// Rigid translations along and rotations about the global axes of each shaft, of the nodes on
// no shaft and of the whole model, restricted to the kept equations (motions that only turn
// about a held rz vanish there and are left out).
std::vector<RigidMotion> rigid_motions(const model::Model& model, const fe::DofMap& dofs,
                                       const std::vector<int>& reduced, Eigen::Index n) {
  std::vector<std::pair<int, std::string>> sets;  // the smallest sets first
  for (std::size_t s = 0; s < model.shafts.size(); ++s)
    sets.emplace_back(static_cast<int>(s), fmt::format("shaft '{}'", model.shafts[s].name));
  sets.emplace_back(-1, "the nodes on no shaft");
  sets.emplace_back(-2, "the whole rotor");
  const char* axes[] = {"x", "y", "z"};
  std::vector<RigidMotion> out;
  for (const auto& [set, label] : sets) {
    auto in_set = [which = set](const fe::NodeInfo& node) {
      return which == -2 || node.shaft == which;
    };
    Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
    int count = 0;
    for (const auto& node : dofs.nodes())
      if (in_set(node)) {
        centroid += node.position;
        ++count;
      }
    if (count == 0) continue;
    centroid /= count;
    for (int axis = 0; axis < 3; ++axis) {
      const Eigen::Vector3d a = Eigen::Vector3d::Unit(axis);
      for (int rotation = 0; rotation < 2; ++rotation) {
        Eigen::VectorXd v = Eigen::VectorXd::Zero(n);
        for (int k = 0; k < dofs.num_nodes(); ++k) {
          const fe::NodeInfo& node = dofs.node(k);
          if (!in_set(node)) continue;
          const Eigen::Vector3d u = rotation ? a.cross(node.position - centroid) : a;
          const Eigen::Vector3d r = rotation ? a : Eigen::Vector3d::Zero();
          const Eigen::Vector3d un = node.frame.transpose() * u, rn = node.frame.transpose() * r;
          const auto eq = dofs.node_dofs(k);
          for (std::size_t c = 0; c < 3; ++c) {
            if (eq[c] >= 0 && reduced[static_cast<std::size_t>(eq[c])] >= 0)
              v[reduced[static_cast<std::size_t>(eq[c])]] = un[static_cast<Eigen::Index>(c)];
            if (eq[c + 3] >= 0 && reduced[static_cast<std::size_t>(eq[c + 3])] >= 0)
              v[reduced[static_cast<std::size_t>(eq[c + 3])]] = rn[static_cast<Eigen::Index>(c)];
          }
        }
        if (v.norm() < 1e-12) continue;  // only rz components: held
        out.push_back(
            {fmt::format("{} {} global {}", label,
                         rotation ? "turns freely about" : "moves freely along", axes[axis]),
             std::move(v)});
      }
    }
  }
  return out;
}

// Adds a force F and moment M (global) at `node` to the reduced load vector.
void add_load(Eigen::VectorXd& f, const fe::DofMap& dofs, const std::vector<int>& reduced, int node,
              const Eigen::Vector3d& F, const Eigen::Vector3d& M) {
  const Eigen::Matrix3d Rt = dofs.node(node).frame.transpose();
  const Eigen::Vector3d Fn = Rt * F, Mn = Rt * M;
  const auto eq = dofs.node_dofs(node);
  for (std::size_t c = 0; c < 3; ++c) {
    if (eq[c] >= 0 && reduced[static_cast<std::size_t>(eq[c])] >= 0)
      f[reduced[static_cast<std::size_t>(eq[c])]] += Fn[static_cast<Eigen::Index>(c)];
    if (eq[c + 3] >= 0 && reduced[static_cast<std::size_t>(eq[c + 3])] >= 0)
      f[reduced[static_cast<std::size_t>(eq[c + 3])]] += Mn[static_cast<Eigen::Index>(c)];
  }
}

// Global displacement and rotation of `node` from the reduced solution (held or constrained
// components are 0).
std::pair<Eigen::Vector3d, Eigen::Vector3d> node_motion(const Eigen::VectorXd& x,
                                                        const fe::DofMap& dofs,
                                                        const std::vector<int>& reduced, int node) {
  Eigen::Vector3d u = Eigen::Vector3d::Zero(), r = Eigen::Vector3d::Zero();
  const auto eq = dofs.node_dofs(node);
  for (std::size_t c = 0; c < 3; ++c) {
    if (eq[c] >= 0 && reduced[static_cast<std::size_t>(eq[c])] >= 0)
      u[static_cast<Eigen::Index>(c)] = x[reduced[static_cast<std::size_t>(eq[c])]];
    if (eq[c + 3] >= 0 && reduced[static_cast<std::size_t>(eq[c + 3])] >= 0)
      r[static_cast<Eigen::Index>(c)] = x[reduced[static_cast<std::size_t>(eq[c + 3])]];
  }
  const Eigen::Matrix3d& R = dofs.node(node).frame;
  return {R * u, R * r};
}

std::size_t find_mesh(const model::Model& model, const std::string& name,
                      const SourceLocation& where, const std::string& key) {
  std::string names;
  for (std::size_t i = 0; i < model.gear_meshes.size(); ++i) {
    if (model.gear_meshes[i].name == name) return i;
    names += fmt::format("{}\"{}\"", names.empty() ? "" : ", ", model.gear_meshes[i].name);
  }
  throw InputError(where, key, "the name of a [[gear_meshes]] entry of the rotor model",
                   fmt::format("\"{}\"", name),
                   names.empty() ? "the model has no [[gear_meshes]]; give the rotor's gear mesh "
                                   "or remove the key"
                                 : "gear meshes: " + names);
}

}  // namespace

MeshDeflection mesh_static_deflection(const model::Model& model, const std::string& mesh_name,
                                      const MeshToothLoad& load, double face_width_m,
                                      const SourceLocation& where, const std::string& key) {
  const std::size_t index = find_mesh(model, mesh_name, where, key);
  const model::GearMesh& mesh = model.gear_meshes[index];
  if (mesh.type != model::GearType::Spur && mesh.type != model::GearType::Helical)
    throw InputError(where, key, "a spur or helical gear mesh (cylindrical gears)",
                     fmt::format("gear mesh '{}' of a bevel or hypoid type", mesh_name));
  const fe::LinearSystem system = system_without_mesh(model, index);
  const fe::DofMap& dofs = system.dofs;
  const int n1 = dofs.node_index(mesh.gear1), n2 = dofs.node_index(mesh.gear2);
  const fe::NodeInfo& g1 = dofs.node(n1);
  const fe::NodeInfo& g2 = dofs.node(n2);
  const fe::GearMeshGeometry geo =
      fe::gear_mesh_geometry(mesh, g1, g2, fmt::format("gear_meshes[{}]", index));

  const std::vector<int> keep = kept_equations(dofs);
  std::vector<int> reduced(static_cast<std::size_t>(dofs.num_dofs()), -1);
  for (std::size_t i = 0; i < keep.size(); ++i)
    reduced[static_cast<std::size_t>(keep[i])] = static_cast<int>(i);
  const auto n = static_cast<Eigen::Index>(keep.size());
  const Eigen::SparseMatrix<double> K = linalg::submatrix(system.K_at(0.0), keep, keep);

  const std::string expected = fmt::format(
      "a rotor held against every rigid-body motion without the spring of gear mesh '{}' "
      "(bearings or [[constraints]]; torsion is held for this static solve)",
      mesh_name);
  const std::string hint =
      "give the [[bearings]] a stiffness in that direction, add [[constraints]], or remove "
      "deflection_mesh";
  const double scale = n > 0 ? linalg::norm1(K) : 0.0;
  for (const RigidMotion& m : rigid_motions(model, dofs, reduced, n))
    if ((K * m.shape).norm() <= 1e-9 * scale * m.shape.norm())
      throw InputError(where, key, expected, m.what, hint);

  // Tooth force on gear 1 at the pitch point (top of the header).
  const double axial_sign = geo.axial_force == 0.0 ? 0.0 : (geo.axial_force > 0.0 ? 1.0 : -1.0);
  const Eigen::Vector3d F1 = -geo.sigma * load.tangential_n * geo.tangential -
                             load.radial_n * geo.radial + axial_sign * load.axial_n * geo.axial;
  Eigen::VectorXd f = Eigen::VectorXd::Zero(n);
  add_load(f, dofs, reduced, n1, F1, (geo.pitch_point - g1.position).cross(F1));
  add_load(f, dofs, reduced, n2, -F1, geo.lever2.cross(-F1));

  // A pivoted LU is backward stable: its residual is round-off times ||K|| ||x||; a larger one
  // (1e-10, far above 2e-16 times a few hundred equations) means a numerically singular K.
  linalg::SparseLU<double> lu;
  const Status status = n > 0 ? lu.compute(K) : Status::Singular;
  Eigen::VectorXd x = status == Status::Ok ? lu.solve(f) : Eigen::VectorXd();
  if (status != Status::Ok || !x.allFinite() || (K * x - f).norm() > 1e-10 * scale * x.norm())
    throw InputError(where, key, expected,
                     status != Status::Ok
                         ? fmt::format("a singular stiffness matrix ({})", lu.message())
                         : std::string("a stiffness matrix too ill-conditioned "
                                       "for the static solve"),
                     hint);

  MeshDeflection d;
  d.mesh = mesh_name;
  d.gear1 = mesh.gear1;
  d.gear2 = mesh.gear2;
  std::tie(d.displacement1, d.tilt1) = node_motion(x, dofs, reduced, n1);
  std::tie(d.displacement2, d.tilt2) = node_motion(x, dofs, reduced, n2);
  const Eigen::Vector3d ea = g1.frame.col(2);
  const double hand = mesh.hand == model::Hand::Right ? 1.0 : -1.0;
  d.face_direction = mesh.type == model::GearType::Helical ? -geo.sigma * hand * ea : ea;
  const Eigen::Vector3d n_t = geo.line_of_action - geo.line_of_action.dot(ea) * ea;
  d.line_of_action = n_t.normalized();
  d.plane_normal = d.face_direction.cross(d.line_of_action);
  auto slope = [&](const Eigen::Vector3d& tilt, const Eigen::Vector3d& along) {
    return tilt.cross(d.face_direction).dot(along);
  };
  d.slope1_rad = slope(d.tilt1, d.line_of_action);
  d.slope2_rad = slope(d.tilt2, d.line_of_action);
  d.out_of_plane_slope1_rad = slope(d.tilt1, d.plane_normal);
  d.out_of_plane_slope2_rad = slope(d.tilt2, d.plane_normal);
  d.misalignment_m = face_width_m * (d.slope2_rad - d.slope1_rad);
  d.out_of_plane_misalignment_m =
      face_width_m * (d.out_of_plane_slope2_rad - d.out_of_plane_slope1_rad);
  return d;
}

}  // namespace geardyn::assembly
