#include "geardyn/analyses/nonlinear_elements.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>

#include "geardyn/analyses/mesh_force_map.hpp"
#include "geardyn/assembly/system_builder.hpp"
#include "geardyn/drivetrain/builder.hpp"
#include "geardyn/drivetrain/placement.hpp"
#include "geardyn/eig/symmetric_eigen.hpp"
#include "geardyn/elements/gap_contact.hpp"
#include "geardyn/hbm/element_library.hpp"
#include "geardyn/hbm/gear_mesh_element.hpp"
#include "geardyn/hbm/squeeze_film_element.hpp"

namespace geardyn::analyses {
namespace {

/// Physical coordinates beyond this many DOFs make the dense balance slow: ask for modes.
constexpr int kMaxPhysicalDofs = 600;

Eigen::MatrixXd dense(const fe::SparseMatrix& A) { return Eigen::MatrixXd(A); }

using model::NonlinearElementKind;
using model::NonlinearElementSpec;

const char* kind_name(NonlinearElementKind k) {
  switch (k) {
    case NonlinearElementKind::Jenkins:
      return "jenkins";
    case NonlinearElementKind::Coulomb:
      return "coulomb";
    case NonlinearElementKind::FrictionContact:
      return "friction_contact";
    case NonlinearElementKind::Polynomial:
      return "polynomial";
    case NonlinearElementKind::Cubic:
      return "cubic";
    case NonlinearElementKind::Unilateral:
      return "unilateral";
    case NonlinearElementKind::Contact:
      return "contact";
    case NonlinearElementKind::GearMesh:
      return "gear_mesh";
    case NonlinearElementKind::SqueezeFilm:
      return "squeeze_film";
  }
  return "?";
}

Eigen::Vector3d vec(const model::DrivetrainVec3& v) { return {v[0], v[1], v[2]}; }

// The rows of an element between node1 and node2 along `directions` (one row each).
Eigen::MatrixXd two_node_rows(const NonlinearElementSpec& e, const fe::LinearSystem& system,
                              const std::vector<Eigen::Vector3d>& directions, bool rotation,
                              const std::string& path) {
  const int rows = static_cast<int>(directions.size());
  drivetrain::PlacementBuilder b(system.dofs, rows);
  const int n2 = system.dofs.node_index(e.node2);
  const int n1 = e.node1.empty() ? -1 : system.dofs.node_index(e.node1);
  for (int r = 0; r < rows; ++r) {
    b.add_projection(r, n2, rotation, directions[static_cast<std::size_t>(r)], 1.0);
    b.add_projection(r, n1, rotation, directions[static_cast<std::size_t>(r)], -1.0);
    if (b.row_empty(r))
      throw InputError(e.where, path + ".node2",
                       "ends whose motion along the element's direction is not constrained on "
                       "both sides",
                       fmt::format("'{}'{} fixed along [{:.3g}, {:.3g}, {:.3g}]", e.node2,
                                   e.node1.empty() ? " and ground" : " and '" + e.node1 + "'",
                                   directions[static_cast<std::size_t>(r)].x(),
                                   directions[static_cast<std::size_t>(r)].y(),
                                   directions[static_cast<std::size_t>(r)].z()),
                       "the element would act on nothing: free a DOF of one end");
  }
  const drivetrain::PlacedElement placed = b.finish(nullptr, kind_name(e.kind), e.name);
  Eigen::MatrixXd B = Eigen::MatrixXd::Zero(rows, system.size());
  for (std::size_t k = 0; k < placed.equations.size(); ++k)
    B.col(placed.equations[k]) = placed.B.col(static_cast<Eigen::Index>(k));
  return B;
}

std::size_t mesh_index(const model::Model& model, const std::string& name) {
  for (std::size_t i = 0; i < model.gear_meshes.size(); ++i)
    if (model.gear_meshes[i].name == name) return i;
  throw std::logic_error("unknown gear mesh " + name);  // the parser checked the name
}

// The law of a gear_mesh element: its mesh's stiffness and unloaded TE over one mesh cycle
// (the first cycle of the map's period when the map spans the hunting period), the mesh's
// damping and the element's backlash.
std::shared_ptr<const hbm::NonlinearElement> gear_mesh_law(const model::Model& model,
                                                           const NonlinearElementSpec& e) {
  const std::size_t index = mesh_index(model, e.gear_mesh);
  const elements::MeshForceMap map = mesh_force_map(model, index);
  const int per_cycle = std::max(1, map.angles() / std::max(1, map.mesh_cycles));
  hbm::GearMeshBacklashParameters p;
  p.stiffness.values.resize(static_cast<std::size_t>(per_cycle));
  p.unloaded_te.values.resize(static_cast<std::size_t>(per_cycle));
  for (int i = 0; i < per_cycle; ++i) {
    p.stiffness.values[static_cast<std::size_t>(i)] = map.stiffness_at_node(i);
    p.unloaded_te.values[static_cast<std::size_t>(i)] =
        map.unloaded_te_m[static_cast<std::size_t>(i)];
  }
  p.backlash = std::isnan(e.backlash) ? std::numeric_limits<double>::infinity() : e.backlash;
  p.damping = model.gear_meshes[index].damping;
  return std::make_shared<hbm::GearMeshBacklash>(e.name, p);
}

std::shared_ptr<const hbm::NonlinearElement> law_of(const model::Model& model,
                                                    const NonlinearElementSpec& e,
                                                    const std::string& path) {
  const hbm::ElementSource source{e.where, path};
  switch (e.kind) {
    case NonlinearElementKind::Jenkins:
      return std::make_shared<hbm::JenkinsElementHb>(
          e.name, hbm::JenkinsElement{e.stiffness, e.slip_force}, source);
    case NonlinearElementKind::Coulomb:
      return std::make_shared<hbm::TanhCoulomb>(e.name, e.slip_force, e.regularisation_velocity,
                                                source);
    case NonlinearElementKind::FrictionContact: {
      hbm::FrictionContact c;
      c.tangential_directions = std::isnan(e.tangent2[0]) ? 1 : 2;
      c.normal_stiffness = e.normal_stiffness;
      c.tangential_stiffness = e.tangential_stiffness;
      c.friction_coefficient = e.friction_coefficient;
      c.normal_preload = e.normal_preload;
      return std::make_shared<hbm::FrictionContactHb>(e.name, c, hbm::ContactMarchOptions{},
                                                      source);
    }
    case NonlinearElementKind::Polynomial: {
      std::map<int, double> c;
      for (std::size_t k = 0; k < e.powers.size(); ++k)
        c[static_cast<int>(e.powers[k])] += e.coefficients[k];
      return std::make_shared<hbm::PolynomialSpring>(e.name, c, source);
    }
    case NonlinearElementKind::Cubic:
      return std::make_shared<hbm::PolynomialSpring>(
          e.name, std::map<int, double>{{3, e.stiffness}}, source);
    case NonlinearElementKind::Unilateral:
      return std::make_shared<hbm::UnilateralSpringHb>(e.name, e.stiffness, e.gap, e.damping,
                                                       source);
    case NonlinearElementKind::Contact: {
      const elements::LawSource law_source{e.law.where, path + ".law"};
      const auto stop = std::make_shared<elements::GapContact>(elements::GapContact::stop(
          e.name, e.gap, drivetrain::make_contact_law(e.law, law_source), law_source));
      return std::make_shared<hbm::ForceElementAdapter>(e.name, stop, source);
    }
    case NonlinearElementKind::GearMesh:
      return gear_mesh_law(model, e);
    case NonlinearElementKind::SqueezeFilm: {
      hbm::SqueezeFilmParameters p;
      p.radius = e.radius;
      p.length = e.length;
      p.clearance = e.clearance;
      p.viscosity = e.viscosity;
      p.film = e.cavitated ? hbm::SqueezeFilm::pi : hbm::SqueezeFilm::two_pi;
      return std::make_shared<hbm::SqueezeFilmDamper>(e.name, p);
    }
  }
  throw std::logic_error("unknown nonlinear element kind");
}

// The placement rows of an element (one per coordinate of its law).
Eigen::MatrixXd rows_of(const model::Model& model, const fe::LinearSystem& system,
                        const NonlinearElementSpec& e, const std::string& path) {
  if (e.kind == NonlinearElementKind::GearMesh) {
    const drivetrain::MeshRows rows =
        drivetrain::mesh_rows(model, system, mesh_index(model, e.gear_mesh));
    Eigen::MatrixXd B = Eigen::MatrixXd::Zero(1, system.size());
    for (std::size_t k = 0; k < rows.equations.size(); ++k)
      B(0, rows.equations[k]) += rows.coefficients[k];
    return B;
  }
  std::vector<Eigen::Vector3d> directions{vec(e.direction)};
  if (e.kind == NonlinearElementKind::FrictionContact) {
    directions.push_back(vec(e.tangent));
    if (!std::isnan(e.tangent2[0])) directions.push_back(vec(e.tangent2));
  }
  if (e.kind == NonlinearElementKind::SqueezeFilm) {
    const Eigen::Matrix3d frame =
        drivetrain::frame_with_axis(vec(e.direction), Eigen::Vector3d::UnitX());
    directions = {frame.col(0), frame.col(1)};
  }
  return two_node_rows(e, system, directions, e.rotation, path);
}

}  // namespace

std::vector<BuiltNonlinearElement> build_nonlinear_elements(const model::Model& model,
                                                            const fe::LinearSystem& system,
                                                            const Context& /*context*/) {
  std::vector<BuiltNonlinearElement> out;
  for (std::size_t i = 0; i < model.nonlinear_elements.size(); ++i) {
    const NonlinearElementSpec& e = model.nonlinear_elements[i];
    const std::string path = fmt::format("nonlinear_elements[{}]", i);
    BuiltNonlinearElement b;
    b.name = e.name;
    b.kind = kind_name(e.kind);
    b.element = law_of(model, e, path);
    b.B = rows_of(model, system, e, path);
    if (e.kind == NonlinearElementKind::GearMesh)
      b.mesh_teeth = model.gear_meshes[mesh_index(model, e.gear_mesh)].teeth1;
    out.push_back(std::move(b));
  }
  return out;
}

NonlinearCoordinates nonlinear_coordinates(const fe::LinearSystem& system, double speed,
                                           int n_modes, const Context& context) {
  NonlinearCoordinates c;
  const int n = system.size();
  if (n_modes == 0) {
    if (n > kMaxPhysicalDofs)
      throw context.error("n_modes",
                          fmt::format("a number of modes (the model has {} DOFs; the "
                                      "physical form is dense, for up to {} DOFs)",
                                      n, kMaxPhysicalDofs),
                          "0 (physical DOFs)",
                          "n_modes = 20 to 60 usually suffices: modes well above H x the "
                          "highest frequency");
    c.M = dense(system.M);
    c.K = dense(system.K_at(speed));
    c.C = system.damping_dense(speed);
    if (system.K_loss.nonZeros() > 0) c.K_loss = dense(system.K_loss);
    c.basis = Eigen::MatrixXd::Identity(n, n);
    return c;
  }
  if (n_modes > n)
    throw context.error("n_modes", fmt::format("at most the model's {} DOFs", n),
                        fmt::format("{}", n_modes));
  eig::SymmetricEigenOptions o;
  o.n_modes = n_modes;
  const fe::SparseMatrix K = system.K_at(speed);
  const auto modes = eig::solve_symmetric(K, system.M, o);
  if (modes.status != Status::Ok)
    throw NumericalError(context.name(), "the modes of the linear structure: " + modes.message);
  const Eigen::MatrixXd& Phi = modes.eigenvectors;
  c.modal = true;
  c.basis = Phi;
  c.M = Eigen::MatrixXd::Identity(Phi.cols(), Phi.cols());
  c.K = modes.eigenvalues.asDiagonal();
  c.highest_mode = std::sqrt(std::max(modes.eigenvalues.maxCoeff(), 0.0));
  // Phi^T (C(W) + W G + modal damping) Phi without forming an n x n dense matrix.
  const fe::SparseMatrix CW = system.C_at(speed) + speed * system.G;
  c.C = Phi.transpose() * (CW * Phi);
  if (system.has_modal_damping()) {
    const Eigen::MatrixXd BtPhi = system.modal_basis.transpose() * Phi;
    c.C += BtPhi.transpose() * system.modal_coefficients.asDiagonal() * BtPhi;
  }
  if (system.K_loss.nonZeros() > 0) c.K_loss = Phi.transpose() * (system.K_loss * Phi);
  return c;
}

SensorRows nonlinear_sensor_rows(const model::Model& model, const fe::LinearSystem& system,
                                 const std::vector<std::string>& names, const Context& context) {
  SensorRows r;
  std::vector<const model::Sensor*> chosen;
  for (const auto& sensor : model.sensors)
    if (names.empty() || std::find(names.begin(), names.end(), sensor.name) != names.end())
      chosen.push_back(&sensor);
  r.rows = Eigen::MatrixXd::Zero(static_cast<Eigen::Index>(chosen.size()), system.size());
  for (std::size_t k = 0; k < chosen.size(); ++k) {
    const model::Sensor& sensor = *chosen[k];
    if (!sensor.solid.empty())
      throw context.error("sensors", "sensors on rotor or point nodes",
                          fmt::format("\"{}\" on solid '{}'", sensor.name, sensor.solid));
    const int eq = system.dofs.dof(system.dofs.node_index(sensor.node), sensor.dof);
    if (eq < 0)
      throw context.error("sensors", "sensors on DOFs that are not constrained",
                          fmt::format("\"{}\" on a constrained DOF", sensor.name));
    r.rows(static_cast<Eigen::Index>(k), eq) = 1.0;
    r.names.push_back(sensor.name);
    r.rotational.push_back(static_cast<int>(sensor.dof) >= 3);
  }
  return r;
}

hbm::ElementSystem placed_element_system(const NonlinearCoordinates& c,
                                         const std::vector<BuiltNonlinearElement>& elements,
                                         const Eigen::MatrixXd& F) {
  hbm::ElementSystem sys;
  sys.M = c.M;
  sys.C = c.C;
  sys.K = c.K;
  sys.K_loss = c.K_loss;
  for (const auto& e : elements) sys.elements.push_back({e.element, e.name, e.B * c.basis});
  if (F.size() == 0) return sys;
  const Eigen::MatrixXd Fq = c.basis.transpose() * F;  // n_coordinates x 3
  sys.excitation_harmonics = 1;
  sys.excitation.resize(Fq.rows() * 3);
  for (Eigen::Index d = 0; d < Fq.rows(); ++d) sys.excitation.segment(d * 3, 3) = Fq.row(d);
  return sys;
}

const fe::LinearSystem& nonlinear_structure(const model::Model& model, const Context& context,
                                            fe::LinearSystem& own) {
  const bool replaced =
      std::any_of(model.nonlinear_elements.begin(), model.nonlinear_elements.end(),
                  [](const auto& e) { return e.kind == NonlinearElementKind::GearMesh; });
  if (!replaced) return context.system();
  own = assembly::build_system(without_replaced_mesh_springs(model), context.solids(),
                               context.progress());
  return own;
}

model::Model without_replaced_mesh_springs(const model::Model& model) {
  model::Model m = model;
  for (const auto& e : model.nonlinear_elements)
    if (e.kind == NonlinearElementKind::GearMesh) {
      model::GearMesh& g = m.gear_meshes[mesh_index(model, e.gear_mesh)];
      g.stiffness = 0.0;
      g.damping = 0.0;
    }
  return m;
}

}  // namespace geardyn::analyses
