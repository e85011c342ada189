#include "geardyn/analyses/gear_whine.hpp"

#include <fmt/format.h>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <complex>
#include <stdexcept>
#include <vector>

#include "geardyn/acoustics/radiation.hpp"
#include "geardyn/analyses/forced_helpers.hpp"
#include "geardyn/analyses/pair_model.hpp"
#include "geardyn/analyses/tooth_force.hpp"
#include "geardyn/assembly/solid_coupling.hpp"
#include "geardyn/core/error.hpp"
#include "geardyn/core/units.hpp"
#include "geardyn/gear/load_window.hpp"

namespace geardyn::analyses {

namespace {

using Complex = std::complex<double>;

const model::Solid* find_solid(const model::Model& model, const std::string& name) {
  for (const model::Solid& s : model.solids)
    if (s.name == name) return &s;
  return nullptr;
}

/// The radiating surface of the housing and its translations as a function of the system's
/// equations `equations` (3 rows per surface node).
struct HousingSurface {
  acoustics::Surface surface;
  std::vector<int> equations;  ///< system equations the body coordinates depend on
  Eigen::MatrixXd recovery;    ///< 3 n_surface x equations.size()
};

/// The mesh nodes of the radiating set (empty: all nodes); InputError at radiating_set when the
/// mesh has no such set.
std::vector<int> radiating_nodes(const assembly::SolidComponent& built, const GearWhineSettings& s,
                                 const Context& context) {
  if (s.radiating_set.empty()) return {};
  const auto it = built.mesh.node_sets.find(s.radiating_set);
  if (it == built.mesh.node_sets.end()) {
    std::string names;
    for (const auto& [name, nodes] : built.mesh.node_sets)
      names += (names.empty() ? "" : ", ") + name;
    throw context.error("radiating_set",
                        fmt::format("a node set of solid '{}' ({})", s.radiating_solid,
                                    names.empty() ? "its mesh has none" : names),
                        fmt::format("'{}'", s.radiating_set));
  }
  return it->second;
}

/// The exterior faces of the radiating set; InputError when the set is not on the exterior.
acoustics::Surface radiating_surface(const assembly::SolidComponent& built,
                                     const GearWhineSettings& s, const Context& context) {
  try {
    return acoustics::exterior_surface(built.mesh, radiating_nodes(built, s, context));
  } catch (const std::invalid_argument& e) {
    throw context.error(
        "radiating_set",
        fmt::format("a node set on the exterior surface of solid '{}' (whole element faces)",
                    s.radiating_solid),
        e.what(), "name a set of the housing's outer skin, or leave radiating_set out");
  }
}

HousingSurface housing_surface(const model::Model& model, const GearWhineSettings& s,
                               const fe::LinearSystem& system, const Context& context) {
  const model::Solid* spec = find_solid(model, s.radiating_solid);
  const assembly::SolidComponent& built = context.solid(model, s.radiating_solid);
  HousingSurface h;
  h.surface = radiating_surface(built, s, context);
  // The reduction joined to the system (kept by the runner; else rebuilt: it is deterministic).
  const assembly::CoupledSolid* kept = context.coupled_solid(s.radiating_solid);
  const assembly::CoupledSolid coupled =
      kept != nullptr ? assembly::CoupledSolid{}
                      : assembly::couple_solid(model, *spec, built, context.progress());
  const assembly::CoupledSolid& used = kept != nullptr ? *kept : coupled;
  const Eigen::SparseMatrix<double> B = fe::body_coordinates(system, used.body);
  std::vector<int> column_of(static_cast<std::size_t>(system.size()), -1);
  for (Eigen::Index c = 0; c < B.outerSize(); ++c)
    if (B.col(c).nonZeros() > 0) {
      column_of[static_cast<std::size_t>(c)] = static_cast<int>(h.equations.size());
      h.equations.push_back(static_cast<int>(c));
    }
  Eigen::MatrixXd Bsub =
      Eigen::MatrixXd::Zero(B.rows(), static_cast<Eigen::Index>(h.equations.size()));
  for (Eigen::Index c = 0; c < B.outerSize(); ++c)
    for (Eigen::SparseMatrix<double>::InnerIterator it(B, c); it; ++it)
      Bsub(it.row(), column_of[static_cast<std::size_t>(c)]) = it.value();
  h.recovery = assembly::node_translations(used, h.surface.nodes) * Bsub;
  return h;
}

/// Radiated power per speed and order from the modal coordinates of the response (q = Phi eta):
/// the surface recovery composed with the housing's rows of the basis, so each speed and order
/// costs O(basis^2).
WhineRadiation radiate(const HousingSurface& h, const GearWhineSettings& s,
                       const response::RotorForcedResult& r, Progress& progress) {
  WhineRadiation out;
  out.solid = s.radiating_solid;
  out.surface_set = s.radiating_set;
  out.surface = h.surface;
  out.surface_nodes = static_cast<int>(h.surface.nodes.size());
  out.surface_faces = static_cast<int>(h.surface.faces.size());
  out.area_m2 = h.surface.area();
  out.radiator_radius_m = std::isnan(s.radiator_radius)
                              ? acoustics::equivalent_sphere_radius(out.area_m2)
                              : s.radiator_radius;
  const acoustics::Air air{s.air_density, s.speed_of_sound};
  Eigen::MatrixXd rows(static_cast<Eigen::Index>(h.equations.size()), r.basis.cols());
  for (std::size_t e = 0; e < h.equations.size(); ++e)
    rows.row(static_cast<Eigen::Index>(e)) = r.basis.row(h.equations[e]);
  const acoustics::ErpOperator erp(h.surface, h.recovery * rows);
  const Eigen::Index ns = r.speeds.size();
  const auto no = static_cast<Eigen::Index>(r.harmonics.size());
  out.erp_w.resize(ns, no);
  out.radiator_w.resize(ns, no);
  out.mean_velocity_ms.resize(ns, no);
  const auto omega_of = [&](Eigen::Index i, Eigen::Index j) {
    return r.harmonics[static_cast<std::size_t>(j)].order * r.mesh_frequency_per_speed *
           r.speeds[i];
  };
  progress.start("radiated power", static_cast<std::size_t>(ns));
  for (Eigen::Index i = 0; i < ns; ++i) {
    for (Eigen::Index j = 0; j < no; ++j) {
      const Eigen::VectorXcd eta = r.coordinates[static_cast<std::size_t>(j)].col(i);
      out.erp_w(i, j) = erp.power(eta, omega_of(i, j), air, s.radiation_efficiency);
      out.mean_velocity_ms(i, j) = erp.mean_normal_velocity(eta, omega_of(i, j));
      out.radiator_w(i, j) = acoustics::spherical_radiator_power(
          out.mean_velocity_ms(i, j), out.radiator_radius_m, omega_of(i, j), air);
    }
    progress.update(static_cast<std::size_t>(i + 1));
  }
  progress.finish();
  out.erp_total_w = out.erp_w.rowwise().sum();
  out.radiator_total_w = out.radiator_w.rowwise().sum();
  // Per-face maps at the asked speeds (the nearest computed speed), else at the loudest one.
  std::vector<Eigen::Index> map_rows;
  for (double w : s.map_speeds) {
    Eigen::Index best = 0;
    (r.speeds.array() - w).abs().minCoeff(&best);
    map_rows.push_back(best);
  }
  if (map_rows.empty()) {
    Eigen::Index best = 0;
    out.erp_total_w.maxCoeff(&best);
    map_rows.push_back(best);
  }
  for (Eigen::Index i : map_rows) {
    Eigen::VectorXd faces =
        Eigen::VectorXd::Zero(static_cast<Eigen::Index>(h.surface.faces.size()));
    for (Eigen::Index j = 0; j < no; ++j) {
      const Eigen::VectorXcd eta = r.coordinates[static_cast<std::size_t>(j)].col(i);
      faces += acoustics::face_erp(h.surface, erp.normal_velocity(eta, omega_of(i, j)), air,
                                   s.radiation_efficiency);
    }
    out.map_speeds.push_back(r.speeds[i]);
    out.face_erp_w.push_back(std::move(faces));
  }
  return out;
}

/// The pair's TE harmonics over one mesh cycle, 0-peak, and the mesh-order forces.
void excitation(const model::Model& model, const GearWhineSettings& s, GearWhineResult& g,
                response::RotorForcedSettings& rs) {
  const PairModel pm = build_pair_model(model, pair_index(model, s.pair));
  const std::vector<Complex> f = blocked_mesh_force_harmonics(pm, s.max_mesh_order);
  for (int p = 1; p <= s.max_mesh_order; ++p)
    rs.harmonics.push_back({p, f[static_cast<std::size_t>(p - 1)]});
  g.static_force_n = pm.static_force_n;
  g.ste_source = pm.ste_source_label();
  const std::vector<double>& ste = pm.ste->ste_m();
  const Eigen::Map<const Eigen::VectorXd> samples(ste.data(),
                                                  static_cast<Eigen::Index>(ste.size()));
  g.te_peak_to_peak_m = samples.maxCoeff() - samples.minCoeff();
  std::vector<int> orders;
  for (int p = 1; p <= s.max_mesh_order; ++p) orders.push_back(p);
  for (const gear::EngineOrderHarmonic& e : gear::engine_order_harmonics(samples, orders)) {
    g.te_amplitude_m.push_back(e.amplitude);
    g.te_phase_rad.push_back(e.phase_rad);
  }
}

void accelerations(GearWhineResult& g, const response::PeakOptions& peaks) {
  const response::RotorForcedResult& r = g.response;
  const Eigen::Index ns = r.speeds.size();
  const auto nsens = static_cast<Eigen::Index>(r.sensors.size());
  g.acceleration_sum = Eigen::MatrixXd::Zero(ns, nsens);
  Eigen::MatrixXd squares = Eigen::MatrixXd::Zero(ns, nsens);
  for (std::size_t h = 0; h < r.harmonics.size(); ++h) {
    const Eigen::ArrayXd omega =
        r.harmonics[h].order * r.mesh_frequency_per_speed * r.speeds.array();
    Eigen::MatrixXcd a = r.displacement[h];
    for (Eigen::Index i = 0; i < ns; ++i) a.row(i) *= -omega[i] * omega[i];
    const Eigen::MatrixXd amp = a.cwiseAbs();
    g.acceleration_sum += amp;
    squares += amp.cwiseAbs2();
    response::append_speed_peaks(g.acceleration_peaks, r.speeds, amp, static_cast<int>(h), peaks);
    g.acceleration.push_back(std::move(a));
  }
  g.acceleration_rms = (0.5 * squares).cwiseSqrt();
  if (r.harmonics.size() > 1)
    response::append_speed_peaks(g.acceleration_peaks, r.speeds, g.acceleration_sum, -1, peaks);
  std::stable_sort(g.acceleration_peaks.begin(), g.acceleration_peaks.end(),
                   [](const auto& a, const auto& b) { return a.sensor < b.sensor; });
}

}  // namespace

std::size_t GearWhineResult::sensor_index(const std::string& name) const {
  return requested_sensor(response.sensors, name);
}

Eigen::VectorXd GearWhineResult::sound_power_level_db() const {
  return radiation.erp_total_w.unaryExpr(
      [](double p) { return acoustics::sound_power_level_db(p); });
}

Eigen::VectorXd GearWhineResult::sound_pressure_level_db(const GearWhineSettings& s) const {
  return radiation.erp_total_w.unaryExpr(
      [&](double p) { return acoustics::sound_pressure_level_db(p, s.distance, s.directivity); });
}

GearWhineResult run_gear_whine(const model::Model& model, const GearWhineSettings& s,
                               const Context& context) {
  const fe::LinearSystem& system = context.system();
  GearWhineResult g;
  response::RotorForcedSettings rs;
  rs.gear_mesh = s.gear_mesh.empty() ? model.gear_meshes.front().name : s.gear_mesh;
  excitation(model, s, g, rs);
  rs.sensors = response::rotor_sensors(model, system, s.sensors);
  rs.speeds = Eigen::Map<const Eigen::VectorXd>(s.speeds.data(),
                                                static_cast<Eigen::Index>(s.speeds.size()));
  rs.method = response::RotorForcedMethod::ModalReduced;
  rs.n_modes = s.n_modes;
  rs.residual_vectors = s.residual_vectors;
  HousingSurface housing;
  if (!s.radiating_solid.empty()) {
    housing = housing_surface(model, s, system, context);
    rs.keep_coordinates = true;
  }
  g.response = response::run_mesh_forced_response(model, system, rs, context.progress());
  if (g.response.displacement.size() != g.response.harmonics.size())
    throw NumericalError(context.name(), fmt::format("the mesh-order response was not computed: {}",
                                                     g.response.message));
  accelerations(g, rs.peaks);
  if (!s.radiating_solid.empty()) {
    g.has_radiation = true;
    g.radiation = radiate(housing, s, g.response, context.progress());
  }
  return g;
}

void check_gear_whine_inputs(const model::Model& model, const GearWhineSettings& s,
                             const Context& context) {
  const PairModel pm = build_pair_model(model, pair_index(model, s.pair));
  try {
    (void)blocked_mesh_force_harmonics(pm, s.max_mesh_order);
  } catch (const InputError& e) {
    throw context.error("max_mesh_order", "a mesh order below half the STE samples per mesh cycle",
                        e.found(), "give more samples per cycle (the pair's ste_samples)");
  }
  if (s.radiating_solid.empty()) return;
  const model::Solid* spec = find_solid(model, s.radiating_solid);
  if (spec == nullptr || spec->spiders.empty())
    throw context.error("radiating_solid",
                        "a [[solids]] entry joined to the rotor by [[solids.spiders]]",
                        fmt::format("'{}'{}", s.radiating_solid,
                                    spec == nullptr ? " (no such solid)" : " (it has no spiders)"));
  const assembly::SolidComponent& built = context.solid(model, s.radiating_solid);
  if (!built.has_mesh() || built.sectors != 1)
    throw context.error("radiating_solid", "a solid with a mesh of the whole body (sectors = 1)",
                        fmt::format("'{}' of type {}{}", s.radiating_solid, built.kind(),
                                    built.sectors != 1 ? fmt::format(", {} sectors", built.sectors)
                                                       : std::string()));
  (void)radiating_surface(built, s, context);
}

}  // namespace geardyn::analyses
