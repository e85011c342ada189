#include "geardyn/fe/linear_system.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <complex>

#include "geardyn/core/error.hpp"
#include "geardyn/fe/bearing_element.hpp"
#include "geardyn/fe/coupling_element.hpp"
#include "geardyn/fe/gear_mesh_element.hpp"
#include "geardyn/fe/rigid_disk.hpp"
#include "geardyn/fe/timoshenko_beam.hpp"

namespace geardyn::fe {
namespace {

using Triplets = std::vector<Eigen::Triplet<double>>;

template <std::size_t N>
std::array<int, 2 * N> concat(const std::array<int, N>& a, const std::array<int, N>& b) {
  std::array<int, 2 * N> out{};
  std::copy(a.begin(), a.end(), out.begin());
  std::copy(b.begin(), b.end(), out.begin() + N);
  return out;
}

// Adds factor x element into the triplet list; constrained (-1) rows and columns are dropped,
// which is what eliminating a zero displacement does.
template <std::size_t N, class Matrix>
void scatter(Triplets& triplets, const std::array<int, N>& equations, const Matrix& element,
             double factor = 1.0) {
  for (std::size_t r = 0; r < N; ++r) {
    if (equations[r] < 0) continue;
    for (std::size_t c = 0; c < N; ++c) {
      if (equations[c] < 0) continue;
      const double value = element(static_cast<int>(r), static_cast<int>(c));
      if (value != 0.0) triplets.emplace_back(equations[r], equations[c], factor * value);
    }
  }
}

SparseMatrix from_triplets(int n, const Triplets& triplets) {
  SparseMatrix m(n, n);
  m.setFromTriplets(triplets.begin(), triplets.end());
  m.makeCompressed();
  return m;
}

int require_node(const DofMap& dofs, const std::string& name, const SourceLocation& where,
                 const std::string& key) {
  const int index = dofs.find_node(name);
  if (index < 0) {
    throw InputError(where, key, "the name of a shaft station (\"<shaft>.<k>\") or node",
                     fmt::format("'{}'", name));
  }
  return index;
}

// q = T u_local of a joined body: u_local the 6 equations of each point's node (in the node
// frame; -1 where constrained) then its generalised coordinates (`equations`), T the listed rows
// of blockdiag(F, F) per point and the identity on the generalised coordinates.
Eigen::MatrixXd body_map(const DofMap& dofs, const Superelement& body,
                         const std::vector<int>& point_nodes, int first_generalized,
                         std::vector<int>& equations) {
  const auto n_points = body.points.size();
  const Eigen::Index n_local =
      static_cast<Eigen::Index>(6 * n_points) + static_cast<Eigen::Index>(body.n_generalized);
  Eigen::MatrixXd T = Eigen::MatrixXd::Zero(body.size(), n_local);
  equations.clear();
  Eigen::Index row = 0;
  for (std::size_t p = 0; p < n_points; ++p) {
    const int node = point_nodes[p];
    const auto eq = dofs.node_dofs(node);
    equations.insert(equations.end(), eq.begin(), eq.end());
    const Matrix6d R = node_rotation(dofs.node(node).frame);
    for (int c = 0; c < 6; ++c) {
      if (!body.points[p].components[static_cast<std::size_t>(c)]) continue;
      T.block(row++, static_cast<Eigen::Index>(6 * p), 1, 6) = R.row(c);
    }
  }
  for (int k = 0; k < body.n_generalized; ++k) {
    equations.push_back(first_generalized + k);
    T(row++, static_cast<Eigen::Index>(6 * n_points) + k) = 1.0;
  }
  return T;
}

void require_finite_non_negative(double value, const SourceLocation& where, const std::string& key,
                                 const char* what) {
  if (!(value >= 0.0) || !std::isfinite(value)) {
    throw InputError(where, key, what, fmt::format("{}", value));
  }
}

template <class Matrix>
void require_finite(const Matrix& m, const SourceLocation& where, const std::string& key) {
  if (!m.allFinite()) throw InputError(where, key, "finite matrix entries", "NaN or infinity");
}

struct Assembler {
  const model::Model& model;
  LinearSystem& system;
  Triplets M, K, C, G, K_loss;

  const DofMap& dofs() const { return system.dofs; }

  void shafts() {
    for (std::size_t s = 0; s < model.shafts.size(); ++s) {
      const model::Shaft& shaft = model.shafts[s];
      const std::string key = fmt::format("shafts[{}]", s);
      int node = dofs().node_index(shaft.name + ".0");
      const double speed_ratio = shaft.speed_ratio;
      if (!(std::isnan(shaft.shear_coefficient) || shaft.shear_coefficient > 0)) {
        throw InputError(shaft.where, key + ".shear_coefficient", "a positive number (or none)",
                         fmt::format("{}", shaft.shear_coefficient));
      }
      for (std::size_t e = 0; e < shaft.elements.size(); ++e) {
        const model::ShaftElement& element = shaft.elements[e];
        const std::string ekey = fmt::format("{}.elements[{}]", key, e);
        const std::string& material_name =
            element.material.empty() ? shaft.material : element.material;
        const model::Material* material = model.find_material(material_name);
        if (material == nullptr) {
          throw InputError(element.where, ekey + ".material", "the name of a material",
                           fmt::format("'{}'", material_name));
        }
        if (!(material->youngs_modulus > 0) || !(material->shear_modulus > 0) ||
            !(material->density >= 0)) {
          throw InputError(material->where, fmt::format("materials.{}", material->name),
                           "positive E and G and non-negative density",
                           fmt::format("E = {}, G = {}, rho = {}", material->youngs_modulus,
                                       material->shear_modulus, material->density));
        }
        if (!(element.outer_diameter > 0) || !(element.inner_diameter >= 0) ||
            !(element.inner_diameter < element.outer_diameter)) {
          throw InputError(element.where, ekey, "0 <= inner_diameter < outer_diameter",
                           fmt::format("outer {} m, inner {} m", element.outer_diameter,
                                       element.inner_diameter));
        }
        require_finite_non_negative(element.loss_factor, element.where, ekey + ".loss_factor",
                                    "a non-negative loss factor");
        BeamProperties p;
        p.length = element.length / element.divisions;
        p.outer_diameter = element.outer_diameter;
        p.inner_diameter = element.inner_diameter;
        p.youngs_modulus = material->youngs_modulus;
        p.shear_modulus = material->shear_modulus;
        p.density = material->density;
        p.shear_coefficient = shaft.shear_coefficient;
        p.theory = shaft.theory;
        p.rotary_inertia = shaft.rotary_inertia;
        p.gyroscopic = shaft.gyroscopic;
        const BeamMatrices beam = timoshenko_beam(p);
        for (int d = 0; d < element.divisions; ++d, ++node) {
          const auto eq = concat(dofs().node_dofs(node), dofs().node_dofs(node + 1));
          scatter(K, eq, beam.stiffness);
          scatter(M, eq, beam.mass);
          if (speed_ratio != 0.0) scatter(G, eq, beam.gyroscopic, speed_ratio);
          // The global loss factor is added to all of K at the end.
          if (element.loss_factor != 0.0) scatter(K_loss, eq, beam.stiffness, element.loss_factor);
        }
      }
    }
  }

  void masses() {
    for (std::size_t i = 0; i < model.disks.size(); ++i) {
      const model::Disk& disk = model.disks[i];
      const std::string key = fmt::format("disks[{}]", i);
      const int node = require_node(dofs(), disk.node, disk.where, key + ".node");
      require_finite_non_negative(disk.mass, disk.where, key + ".mass", "a mass >= 0 [kg]");
      require_finite_non_negative(disk.polar_inertia, disk.where, key + ".polar_inertia",
                                  "an inertia >= 0 [kg m^2]");
      require_finite_non_negative(disk.diametral_inertia, disk.where, key + ".diametral_inertia",
                                  "an inertia >= 0 [kg m^2]");
      const auto eq = dofs().node_dofs(node);
      scatter(M, eq, rigid_disk_mass(disk.mass, disk.diametral_inertia, disk.polar_inertia));
      const double ratio = dofs().node(node).speed_ratio;
      if (ratio != 0.0) scatter(G, eq, rigid_disk_gyroscopic(disk.polar_inertia), ratio);
    }
    for (std::size_t i = 0; i < model.point_masses.size(); ++i) {
      const model::PointMass& mass = model.point_masses[i];
      const std::string key = fmt::format("point_masses[{}]", i);
      const int node = require_node(dofs(), mass.node, mass.where, key + ".node");
      require_finite_non_negative(mass.mass, mass.where, key + ".mass", "a mass >= 0 [kg]");
      scatter(M, dofs().node_dofs(node), point_mass_matrix(mass.mass));
    }
  }

  void bearings() {
    for (std::size_t i = 0; i < model.bearings.size(); ++i) {
      const model::Bearing& bearing = model.bearings[i];
      const std::string key = fmt::format("bearings[{}]", i);
      const int node1 = require_node(dofs(), bearing.node, bearing.where, key + ".node");
      const int node2 = bearing.node2.empty()
                            ? -1
                            : require_node(dofs(), bearing.node2, bearing.where, key + ".node2");
      if (node1 == node2) {
        throw InputError(bearing.where, key + ".node2", "a node other than 'node'",
                         fmt::format("'{}' twice", bearing.node));
      }
      const std::size_t n_table = std::max<std::size_t>(bearing.speeds.size(), 1);
      auto check_size = [&](std::size_t size, const char* what) {
        if (size != 0 && size != n_table) {
          throw InputError(bearing.where, key + "." + what,
                           fmt::format("{} matrices (one per speed)", n_table),
                           std::to_string(size));
        }
      };
      check_size(bearing.stiffness.size(), "stiffness");
      check_size(bearing.damping.size(), "damping");
      for (std::size_t k = 0; k < bearing.speeds.size(); ++k) {
        if (!std::isfinite(bearing.speeds[k]) ||
            (k > 0 && !(bearing.speeds[k] > bearing.speeds[k - 1]))) {
          throw InputError(bearing.where, fmt::format("{}.speeds[{}]", key, k),
                           "finite, strictly increasing speeds",
                           fmt::format("{}", bearing.speeds[k]));
        }
      }

      const Eigen::Matrix3d& frame1 = dofs().node(node1).frame;
      auto element = [&](const model::Bearing::Matrix6& values, const std::string& what) {
        const Matrix6d b = bearing_matrix(values);
        require_finite(b, bearing.where, key + "." + what);
        Matrix12d out = Matrix12d::Zero();
        if (node2 < 0) {
          out.topLeftCorner<6, 6>() = b;
        } else {
          out = bearing_between_nodes(b, frame1, dofs().node(node2).frame);
        }
        return out;
      };
      std::array<int, 6> eq2;
      eq2.fill(-1);
      if (node2 >= 0) eq2 = dofs().node_dofs(node2);
      const auto eq = concat(dofs().node_dofs(node1), eq2);

      if (bearing.speeds.size() <= 1) {
        // A one-row table is a constant bearing.
        if (!bearing.stiffness.empty())
          scatter(K, eq, element(bearing.stiffness.front(), "stiffness"));
        if (!bearing.damping.empty()) scatter(C, eq, element(bearing.damping.front(), "damping"));
        continue;
      }
      SpeedDependentBearing table;
      table.speeds = bearing.speeds;
      table.equations = eq;
      for (std::size_t k = 0; k < n_table; ++k) {
        table.stiffness.push_back(
            bearing.stiffness.empty()
                ? Matrix12d::Zero().eval()
                : element(bearing.stiffness[k], fmt::format("stiffness[{}]", k)));
        table.damping.push_back(bearing.damping.empty()
                                    ? Matrix12d::Zero().eval()
                                    : element(bearing.damping[k], fmt::format("damping[{}]", k)));
      }
      system.speed_bearings.push_back(std::move(table));
    }
  }

  void couplings() {
    for (std::size_t i = 0; i < model.couplings.size(); ++i) {
      const model::Coupling& coupling = model.couplings[i];
      const std::string key = fmt::format("couplings[{}]", i);
      const int node1 = require_node(dofs(), coupling.node1, coupling.where, key + ".node1");
      const bool ground = coupling.node2.empty();
      const int node2 =
          ground ? -1 : require_node(dofs(), coupling.node2, coupling.where, key + ".node2");
      const std::size_t expected = ground ? 36 : 144;
      auto add = [&](const std::vector<double>& values, const char* what, Triplets& target) {
        if (values.empty()) return;
        if (values.size() != expected) {
          throw InputError(
              coupling.where, key + "." + what,
              fmt::format("{} numbers ({} row-major)", expected, ground ? "6x6" : "12x12"),
              std::to_string(values.size()));
        }
        if (ground) {
          const Matrix6d a = coupling_to_ground(values, dofs().node(node1).frame);
          require_finite(a, coupling.where, key + "." + what);
          scatter(target, dofs().node_dofs(node1), a);
        } else {
          const Matrix12d a =
              coupling_between_nodes(values, dofs().node(node1).frame, dofs().node(node2).frame);
          require_finite(a, coupling.where, key + "." + what);
          scatter(target, concat(dofs().node_dofs(node1), dofs().node_dofs(node2)), a);
        }
      };
      add(coupling.stiffness, "stiffness", K);
      add(coupling.damping, "damping", C);
      add(coupling.mass, "mass", M);
    }
  }

  // Each body: q = T u over the equations of its points' nodes (6 per model-node point, the
  // node's equations for a new node) and its generalised coordinates; adds T^T A T.
  void superelements(const std::vector<Superelement>& bodies,
                     const std::vector<std::vector<int>>& point_nodes,
                     const std::vector<int>& first_generalized) {
    for (std::size_t b = 0; b < bodies.size(); ++b) {
      const Superelement& body = bodies[b];
      const std::string key = fmt::format("superelement '{}'", body.name);
      const auto n = static_cast<Eigen::Index>(body.size());
      if (body.K.rows() != n || body.K.cols() != n || body.M.rows() != n || body.M.cols() != n ||
          (body.G.size() != 0 && (body.G.rows() != n || body.G.cols() != n)) ||
          (body.C.size() != 0 && (body.C.rows() != n || body.C.cols() != n))) {
        throw InputError({}, key, fmt::format("K, M (and G, C) of size {} x {}", n, n),
                         fmt::format("K {} x {}, M {} x {}, G {} x {}, C {} x {}", body.K.rows(),
                                     body.K.cols(), body.M.rows(), body.M.cols(), body.G.rows(),
                                     body.G.cols(), body.C.rows(), body.C.cols()));
      }
      require_finite(body.K, {}, key + ".K");
      require_finite(body.M, {}, key + ".M");
      require_finite(body.G, {}, key + ".G");
      require_finite(body.C, {}, key + ".C");
      std::vector<int> equations;
      const Eigen::MatrixXd T =
          body_map(dofs(), body, point_nodes[b], first_generalized[b], equations);
      const Eigen::Index n_local = T.cols();
      auto add = [&](const Eigen::MatrixXd& A, Triplets& target) {
        if (A.size() == 0) return;
        const Eigen::MatrixXd local = T.transpose() * A * T;
        for (Eigen::Index r = 0; r < n_local; ++r) {
          const int er = equations[static_cast<std::size_t>(r)];
          if (er < 0) continue;
          for (Eigen::Index c = 0; c < n_local; ++c) {
            const int ec = equations[static_cast<std::size_t>(c)];
            if (ec >= 0 && local(r, c) != 0.0) target.emplace_back(er, ec, local(r, c));
          }
        }
      };
      add(body.K, K);
      add(body.M, M);
      add(body.G, G);
      add(body.C, C);
    }
  }

  void gear_meshes() {
    for (std::size_t i = 0; i < model.gear_meshes.size(); ++i) {
      const model::GearMesh& mesh = model.gear_meshes[i];
      const std::string key = fmt::format("gear_meshes[{}]", i);
      const int node1 = require_node(dofs(), mesh.gear1, mesh.where, key + ".gear1");
      const int node2 = require_node(dofs(), mesh.gear2, mesh.where, key + ".gear2");
      if (node1 == node2) {
        throw InputError(mesh.where, key + ".gear2", "a node other than gear1",
                         fmt::format("'{}' twice", mesh.gear1));
      }
      // Zero is allowed: a variant of the model with the gears uncoupled.
      if (!(mesh.stiffness >= 0) || !std::isfinite(mesh.stiffness)) {
        throw InputError(mesh.where, key + ".stiffness", "a non-negative mesh stiffness [N/m]",
                         fmt::format("{}", mesh.stiffness));
      }
      require_finite_non_negative(mesh.damping, mesh.where, key + ".damping",
                                  "a non-negative mesh damping [N s/m]");
      const NodeInfo& gear1 = dofs().node(node1);
      const NodeInfo& gear2 = dofs().node(node2);
      const GearMeshGeometry geometry = gear_mesh_geometry(mesh, gear1, gear2, key);
      const Vector12d v = gear_mesh_vector(geometry, gear1, gear2);
      const Matrix12d vvT = v * v.transpose();
      const auto eq = concat(dofs().node_dofs(node1), dofs().node_dofs(node2));
      scatter(K, eq, vvT, mesh.stiffness);
      if (mesh.damping > 0) scatter(C, eq, vvT, mesh.damping);
    }
  }
};

}  // namespace

LinearSystem assemble(const model::Model& model, [[maybe_unused]] const AssemblyOptions& options,
                      const std::vector<Superelement>& superelements) {
  LinearSystem system;
  system.dofs = DofMap::build(model);
  // Bodies append their nodes, then their generalised coordinates, after the model's nodes.
  std::vector<std::vector<int>> point_nodes(superelements.size());
  std::vector<int> first_generalized(superelements.size(), 0);
  for (std::size_t b = 0; b < superelements.size(); ++b) {
    const Superelement& body = superelements[b];
    for (std::size_t p = 0; p < body.points.size(); ++p) {
      const SuperelementPoint& point = body.points[p];
      const std::string key = fmt::format("superelement '{}'.points[{}]", body.name, p);
      if (!point.new_node) {
        point_nodes[b].push_back(require_node(system.dofs, point.node, {}, key));
        continue;
      }
      NodeInfo info;
      info.name = point.node;
      info.position = point.position;
      info.frame = Eigen::Matrix3d::Identity();
      info.speed_ratio = point.speed_ratio;
      point_nodes[b].push_back(system.dofs.add_node(std::move(info), point.components, key));
    }
    first_generalized[b] = system.dofs.add_generalized(body.name, body.n_generalized);
  }
  const model::Damping& damping = model.damping;
  require_finite_non_negative(damping.loss_factor, {}, "damping.loss_factor",
                              "a non-negative loss factor");
  if (!std::isfinite(damping.rayleigh_alpha) || !std::isfinite(damping.rayleigh_beta)) {
    throw InputError(
        {}, "damping.rayleigh", "finite Rayleigh coefficients",
        fmt::format("alpha {}, beta {}", damping.rayleigh_alpha, damping.rayleigh_beta));
  }

  Assembler a{model, system, {}, {}, {}, {}, {}};
  a.shafts();
  a.masses();
  a.bearings();
  a.couplings();
  a.gear_meshes();
  a.superelements(superelements, point_nodes, first_generalized);

  const int n = system.size();
  system.M = from_triplets(n, a.M);
  system.K = from_triplets(n, a.K);
  system.G = from_triplets(n, a.G);
  system.K_loss = from_triplets(n, a.K_loss);
  system.C = from_triplets(n, a.C);
  // Structural damping of the whole (speed-independent) structure: K_loss += eta K.
  if (damping.loss_factor != 0.0) system.K_loss += damping.loss_factor * system.K;
  // Rayleigh damping on the speed-independent matrices (speed-dependent bearings excluded).
  if (damping.rayleigh_alpha != 0.0) system.C += damping.rayleigh_alpha * system.M;
  if (damping.rayleigh_beta != 0.0) system.C += damping.rayleigh_beta * system.K;
  system.C.makeCompressed();
  system.K_loss.makeCompressed();
  return system;
}

namespace {

SparseMatrix add_speed_bearings(const LinearSystem& system, const SparseMatrix& base, double speed,
                                bool stiffness) {
  if (system.speed_bearings.empty()) return base;
  Triplets triplets;
  for (const SpeedDependentBearing& b : system.speed_bearings) {
    const Matrix12d m = interpolate_by_speed(b.speeds, stiffness ? b.stiffness : b.damping, speed);
    scatter(triplets, b.equations, m);
  }
  SparseMatrix out = base + from_triplets(system.size(), triplets);
  out.makeCompressed();
  return out;
}

}  // namespace

namespace {

/// The bearing's 12 coordinates gathered from a system vector (0 at constrained / ground ends).
Eigen::Matrix<double, 12, 1> gather12(const std::array<int, 12>& equations,
                                      const Eigen::VectorXd& x) {
  Eigen::Matrix<double, 12, 1> out = Eigen::Matrix<double, 12, 1>::Zero();
  for (int i = 0; i < 12; ++i)
    if (const int e = equations[static_cast<std::size_t>(i)]; e >= 0) out[i] = x[e];
  return out;
}

void scatter12(const std::array<int, 12>& equations, const Eigen::Matrix<double, 12, 1>& f,
               double scale, Eigen::VectorXd& out) {
  for (int i = 0; i < 12; ++i)
    if (const int e = equations[static_cast<std::size_t>(i)]; e >= 0) out[e] += scale * f[i];
}

}  // namespace

void SpeedDependentBearing::add_force(double speed, const Eigen::VectorXd& q,
                                      const Eigen::VectorXd& v, Eigen::VectorXd& r) const {
  const Matrix12d Kb = interpolate_by_speed(speeds, stiffness, speed);
  const Matrix12d Cb = interpolate_by_speed(speeds, damping, speed);
  scatter12(equations, Kb * gather12(equations, q) + Cb * gather12(equations, v), 1.0, r);
}

void SpeedDependentBearing::add_tangent(double speed, double c_k, double c_c,
                                        std::vector<Eigen::Triplet<double>>& out) const {
  Matrix12d block = Matrix12d::Zero();
  if (c_k != 0.0) block += c_k * interpolate_by_speed(speeds, stiffness, speed);
  if (c_c != 0.0) block += c_c * interpolate_by_speed(speeds, damping, speed);
  for (int i = 0; i < 12; ++i) {
    const int row = equations[static_cast<std::size_t>(i)];
    if (row < 0) continue;
    for (int j = 0; j < 12; ++j) {
      const int col = equations[static_cast<std::size_t>(j)];
      if (col >= 0 && block(i, j) != 0.0) out.emplace_back(row, col, block(i, j));
    }
  }
}

void SpeedDependentBearing::add_speed_derivative(double speed, const Eigen::VectorXd& q,
                                                 const Eigen::VectorXd& v, double scale,
                                                 Eigen::VectorXd& out) const {
  const Matrix12d dK = slope_by_speed(speeds, stiffness, speed);
  const Matrix12d dC = slope_by_speed(speeds, damping, speed);
  scatter12(equations, dK * gather12(equations, q) + dC * gather12(equations, v), scale, out);
}

SparseMatrix LinearSystem::K_at(double speed) const {
  return add_speed_bearings(*this, K, speed, true);
}

SparseMatrix LinearSystem::C_at(double speed) const {
  return add_speed_bearings(*this, C, speed, false);
}

Eigen::MatrixXd LinearSystem::damping_dense(double speed) const {
  Eigen::MatrixXd d = Eigen::MatrixXd(C_at(speed));
  if (speed != 0.0) d += speed * Eigen::MatrixXd(G);
  if (has_modal_damping()) {
    d += modal_basis * modal_coefficients.asDiagonal() * modal_basis.transpose();
  }
  return d;
}

Eigen::VectorXd LinearSystem::unit_load(int node, model::Component c) const {
  const int equation = dofs.dof(node, c);
  if (equation < 0) {
    throw InputError({}, fmt::format("node '{}'", dofs.node(node).name),
                     "a load on an unconstrained DOF",
                     fmt::format("a load on constrained DOF {}",
                                 model::kComponentNames[static_cast<std::size_t>(c)]));
  }
  Eigen::VectorXd f = Eigen::VectorXd::Zero(size());
  f(equation) = 1.0;
  return f;
}

namespace {

// The unbalances selected by name (all when `selected` is empty), with their node index.
std::vector<std::pair<const model::Unbalance*, int>> selected_unbalances(
    const model::Model& model, const LinearSystem& system,
    const std::vector<std::string>& selected) {
  std::vector<std::pair<const model::Unbalance*, int>> out;
  for (const std::string& name : selected) {
    const bool known = std::any_of(model.unbalances.begin(), model.unbalances.end(),
                                   [&](const model::Unbalance& u) { return u.name == name; });
    if (!known) {
      throw InputError({}, "unbalances", "the name of an unbalance in the model",
                       fmt::format("'{}'", name));
    }
  }
  for (std::size_t i = 0; i < model.unbalances.size(); ++i) {
    const model::Unbalance& u = model.unbalances[i];
    if (!selected.empty() && std::find(selected.begin(), selected.end(), u.name) == selected.end())
      continue;
    const int node =
        require_node(system.dofs, u.node, u.where, fmt::format("unbalances[{}].node", i));
    if (system.dofs.dof(node, model::Component::Ux) < 0 &&
        system.dofs.dof(node, model::Component::Uy) < 0)
      throw InputError(
          u.where, fmt::format("unbalances[{}].node", i),
          "a node with lateral DOFs (ux, uy): an unbalance force is lateral",
          fmt::format("'{}', whose ux and uy are constrained or left out by `dofs`", u.node),
          "set `dofs` (of the model or of the node's shaft) to include \"lateral\", "
          "or leave this unbalance out of the analysis (its `unbalances` key)");
    out.emplace_back(&u, node);
  }
  return out;
}

}  // namespace

Eigen::VectorXcd unbalance_load(const model::Model& model, const LinearSystem& system, double speed,
                                double order, const std::vector<std::string>& selected) {
  using namespace std::complex_literals;
  Eigen::VectorXcd f = Eigen::VectorXcd::Zero(system.size());
  for (const auto& [unbalance, node] : selected_unbalances(model, system, selected)) {
    const double ratio = system.dofs.node(node).speed_ratio;
    if (ratio == 0.0 || std::abs(std::abs(ratio) - order) > 1e-12) continue;
    const double omega = std::abs(ratio) * speed;
    // Forward-rotating force in the spin sense: F_x = m e w^2 e^{i phi}, F_y = -i F_x for spin
    // about +e3 (F_y(t) = m e w^2 sin(w t + phi)), mirrored (F_y = +i F_x) for negative spin.
    const std::complex<double> fx =
        unbalance->mass_eccentricity * omega * omega * std::exp(1i * unbalance->phase);
    const std::complex<double> fy = (ratio > 0 ? -1i : 1i) * fx;
    const int ex = system.dofs.dof(node, model::Component::Ux);
    const int ey = system.dofs.dof(node, model::Component::Uy);
    if (ex >= 0) f(ex) += fx;
    if (ey >= 0) f(ey) += fy;
  }
  return f;
}

std::vector<double> unbalance_orders(const model::Model& model, const LinearSystem& system,
                                     const std::vector<std::string>& selected) {
  std::vector<double> orders;
  for (const auto& [unbalance, node] : selected_unbalances(model, system, selected)) {
    const double order = std::abs(system.dofs.node(node).speed_ratio);
    if (order == 0.0) continue;
    const bool seen = std::any_of(orders.begin(), orders.end(),
                                  [&](double o) { return std::abs(o - order) <= 1e-12; });
    if (!seen) orders.push_back(order);
  }
  std::sort(orders.begin(), orders.end());
  return orders;
}

ModeFamilies mode_families(const LinearSystem& system, const Eigen::VectorXcd& shape) {
  ModeFamilies f;
  const Eigen::VectorXd mass = system.M.diagonal();
  for (int i = 0; i < system.size() && i < shape.size(); ++i) {
    const double energy = mass(i) * std::norm(shape(i));
    if (system.dofs.is_generalized(i)) {
      f.body += energy;
      continue;
    }
    switch (system.dofs.dof_component(i)) {
      case model::Component::Uz:
        f.axial += energy;
        break;
      case model::Component::Rz:
        f.torsional += energy;
        break;
      default:
        f.lateral += energy;
        break;
    }
  }
  const double total = f.lateral + f.axial + f.torsional + f.body;
  if (total > 0) {
    f.lateral /= total;
    f.axial /= total;
    f.torsional /= total;
    f.body /= total;
  }
  return f;
}

SparseMatrix body_coordinates(const LinearSystem& system, const Superelement& body) {
  const std::string key = fmt::format("superelement '{}'", body.name);
  std::vector<int> point_nodes;
  for (std::size_t p = 0; p < body.points.size(); ++p)
    point_nodes.push_back(
        require_node(system.dofs, body.points[p].node, {}, fmt::format("{}.points[{}]", key, p)));
  int first = -1;
  for (const GeneralizedRange& g : system.dofs.generalized())
    if (g.name == body.name && g.count == body.n_generalized) first = g.first;
  if (first < 0 && body.n_generalized > 0)
    throw InputError(
        {}, key, "a body joined to this system (its generalised coordinates)",
        fmt::format("no range '{}' of {} generalised coordinates", body.name, body.n_generalized));
  std::vector<int> equations;
  const Eigen::MatrixXd T = body_map(system.dofs, body, point_nodes, first, equations);
  Triplets triplets;
  for (Eigen::Index c = 0; c < T.cols(); ++c) {
    const int e = equations[static_cast<std::size_t>(c)];
    if (e < 0) continue;
    for (Eigen::Index r = 0; r < T.rows(); ++r)
      if (T(r, c) != 0.0) triplets.emplace_back(static_cast<int>(r), e, T(r, c));
  }
  SparseMatrix B(body.size(), system.size());
  B.setFromTriplets(triplets.begin(), triplets.end());
  B.makeCompressed();
  return B;
}

}  // namespace geardyn::fe
