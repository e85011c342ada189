#include "geardyn/analyses/sector_excitation.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <set>

#include "geardyn/analyses/pair_model.hpp"
#include "geardyn/analyses/tooth_force.hpp"
#include "geardyn/core/error.hpp"
#include "geardyn/core/units.hpp"
#include "geardyn/core/version.hpp"

namespace geardyn::analyses {

namespace {

using Complex = std::complex<double>;
constexpr double kRpm = 60.0 / units::kTwoPi;  // rpm per rad/s

/// The node of `set` nearest to the set's centroid (one point per set).
int central_node(const solid::Mesh& mesh, const std::vector<int>& set) {
  Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
  for (int n : set) centroid += mesh.coords[static_cast<std::size_t>(n)];
  centroid /= static_cast<double>(set.size());
  int best = set.front();
  for (int n : set)
    if ((mesh.coords[static_cast<std::size_t>(n)] - centroid).norm() <
        (mesh.coords[static_cast<std::size_t>(best)] - centroid).norm())
      best = n;
  return best;
}

}  // namespace

std::string set_list(const solid::Mesh& mesh) {
  std::string out;
  for (const auto& [set_name, nodes] : mesh.node_sets)
    out += (out.empty() ? "" : ", ") + fmt::format("\"{}\"", set_name);
  return out;
}

SectorPoints sector_points(const Context& context, const assembly::SolidComponent& c,
                           const CyclicForcedResponseSettings& s) {
  if (!c.has_mesh())
    throw context.error("solid",
                        "a mesh solid (mesh file or generated sector): the excitation and sensor "
                        "node sets are read from its mesh",
                        fmt::format("solid '{}' of type \"{}\"", c.name, c.kind()),
                        "use the mesh it was reduced from; reduction = \"craig_bampton\" reduces "
                        "the sector in the analysis");
  const solid::Mesh& mesh = c.mesh;
  SectorPoints p;
  auto it = mesh.node_sets.find(s.excitation_set);
  if (it == mesh.node_sets.end() || it->second.empty())
    throw context.error(
        "excitation_set",
        fmt::format("a non-empty node set of solid '{}' ({})", c.name, set_list(mesh)),
        fmt::format("\"{}\"", s.excitation_set));
  for (int n : it->second) {
    for (int comp = 0; comp < 3; ++comp)
      if (c.system.node_dof(n, comp) < 0)
        throw context.error(
            "excitation_set", "excitation nodes that are free to move (ux, uy, uz not fixed)",
            fmt::format("node {} of set \"{}\" with {} fixed",
                        mesh.node_ids[static_cast<std::size_t>(n)], s.excitation_set,
                        model::kComponentNames[static_cast<std::size_t>(comp)]));
    const Eigen::Vector3d& x = mesh.coords[static_cast<std::size_t>(n)];
    if (std::hypot(x.x(), x.y()) < 1e-12)
      throw context.error(
          "excitation_set",
          "excitation nodes off the z axis (the tooth load directions are radial "
          "and tangential there)",
          fmt::format("node {} on the axis", mesh.node_ids[static_cast<std::size_t>(n)]));
    p.excitation.push_back(n);
  }

  std::vector<std::pair<std::string, int>> points;  // name stem, node index
  for (std::size_t k = 0; k < s.sensor_sets.size(); ++k) {
    auto st = mesh.node_sets.find(s.sensor_sets[k]);
    if (st == mesh.node_sets.end() || st->second.empty())
      throw context.error(
          fmt::format("sensor_sets[{}]", k),
          fmt::format("a non-empty node set of solid '{}' ({})", c.name, set_list(mesh)),
          fmt::format("\"{}\"", s.sensor_sets[k]));
    points.emplace_back(s.sensor_sets[k], central_node(mesh, st->second));
  }
  for (std::size_t k = 0; k < s.sensor_nodes.size(); ++k) {
    const auto id = static_cast<long>(s.sensor_nodes[k]);
    auto found = std::find(mesh.node_ids.begin(), mesh.node_ids.end(), id);
    if (found == mesh.node_ids.end())
      throw context.error(
          fmt::format("sensor_nodes[{}]", k),
          fmt::format("a node id of solid '{}' (ids {} .. {})", c.name,
                      *std::min_element(mesh.node_ids.begin(), mesh.node_ids.end()),
                      *std::max_element(mesh.node_ids.begin(), mesh.node_ids.end())),
          std::to_string(id));
    points.emplace_back(fmt::format("node{}", id), static_cast<int>(found - mesh.node_ids.begin()));
  }
  for (const auto& [stem, node] : points)
    for (model::Component comp : s.sensor_components) {
      const int ci = static_cast<int>(comp);
      if (c.system.node_dof(node, ci) < 0)
        throw context.error("sensor_components",
                            fmt::format("components the sensor node has and that are not fixed "
                                        "(solid nodes carry ux, uy, uz)"),
                            fmt::format("{} at node {} ({})", model::kComponentNames[ci],
                                        mesh.node_ids[static_cast<std::size_t>(node)], stem));
      p.sensors.push_back({fmt::format("{}_{}", stem, model::kComponentNames[ci]),
                           mesh.node_ids[static_cast<std::size_t>(node)], ci});
    }
  for (const auto& [stem, node] : points) p.sensor_nodes.push_back(node);
  for (std::size_t k = 0; k < s.master_sets.size(); ++k)
    if (!mesh.node_sets.count(s.master_sets[k]))
      throw context.error(fmt::format("master_sets[{}]", k),
                          fmt::format("a node set of solid '{}' ({})", c.name, set_list(mesh)),
                          fmt::format("\"{}\"", s.master_sets[k]));
  return p;
}

SolvedSector solved_sector(const assembly::SolidComponent& c, const CyclicForcedResponseSettings& s,
                           std::vector<long> masters, const std::string& masters_are,
                           const Context& context, const Eigen::SparseMatrix<double>* mass) {
  Progress& progress = context.progress();
  SolvedSector out;
  out.dofs = c.dofs();
  out.K = c.stiffness();
  out.M = mass ? *mass : c.mass();
  if (s.reduction != ReductionMethod::CraigBampton) return out;
  for (const auto& set : s.master_sets)
    for (int n : c.mesh.node_sets.at(set))
      if (c.system.node_dof(n, 0) >= 0 || c.system.node_dof(n, 1) >= 0 ||
          c.system.node_dof(n, 2) >= 0)
        masters.push_back(c.mesh.node_ids[static_cast<std::size_t>(n)]);
  std::sort(masters.begin(), masters.end());
  masters.erase(std::unique(masters.begin(), masters.end()), masters.end());
  std::set<long> with_dofs;  // nodes of fixed faces (e.g. a clamped bore) have none
  for (const auto& d : out.dofs)
    if (d.component >= 0) with_dofs.insert(d.node_id);
  std::erase_if(masters, [&](long id) { return !with_dofs.count(id); });
  reduce::CraigBamptonOptions o;
  o.n_modes = s.cb_modes;
  progress.start(fmt::format("{}: Craig-Bampton reduction of the sector", context.name()), 0);
  out.cb = reduce::craig_bampton(out.K, out.M, out.dofs, reduce::select_dofs(out.dofs, masters), o,
                                 c.source_sha256, kVersion, progress);
  progress.finish();
  const reduce::ReducedComponent& cb = *out.cb;
  out.note = fmt::format(
      "Sector reduced by Craig-Bampton: {} physical masters ({}{}) + {} fixed-interface modes "
      "(up to {:.1f} Hz) from {} DOFs; loads are projected and sensor values recovered through "
      "the reduction basis.",
      cb.n_masters(), masters_are, s.master_sets.empty() ? "" : ", master sets", cb.n_modal,
      cb.n_modal > 0 ? cb.fixed_interface_hz[cb.n_modal - 1] : 0.0, out.dofs.size());
  out.dofs = cb.reduced_dofs();
  out.K = cb.K.sparseView();
  out.M = cb.M.sparseView();
  return out;
}

LoadFrame load_frame(const Eigen::Vector3d& x, bool apex_below) {
  const Eigen::Vector3d e_r = Eigen::Vector3d(x.x(), x.y(), 0.0).normalized();
  const Eigen::Vector3d e_theta = Eigen::Vector3d::UnitZ().cross(e_r);
  const Eigen::Vector3d e_z = Eigen::Vector3d::UnitZ();
  return {-e_theta, -e_r, apex_below ? e_z : Eigen::Vector3d(-e_z)};
}

Plot amplitude_plot(std::string plot_name, std::string title) {
  Plot p;
  p.name = std::move(plot_name);
  p.title = std::move(title);
  p.x_label = "speed [rpm]";
  p.y_label = "amplitude [m or rad]";
  p.y_log = true;
  return p;
}

Trace curve(std::string trace_name, const std::vector<double>& x, std::vector<double> y,
            std::string dash) {
  Trace t;
  t.name = std::move(trace_name);
  t.x = x;
  t.y = std::move(y);
  // A log axis cannot show zeros (a sensor DOF at rest for one pattern).
  for (double& v : t.y) v = std::max(v, 1e-300);
  t.dash = std::move(dash);
  return t;
}

std::string tooth_force_harmonics(const model::Model& model, const Context& context,
                                  const CyclicForcedResponseSettings& s,
                                  std::vector<OrderForce>& orders, const std::string& orders_key) {
  Progress& progress = context.progress();
  const analyses::PairModel pm =
      analyses::build_pair_model(model, analyses::pair_index(model, s.pair));
  analyses::ToothForceOptions o;
  o.gear = s.gear;
  o.model = s.model;
  o.contact_loss = s.contact_loss;
  o.window_shift = s.window_shift;
  o.contact_ratio = s.contact_ratio;
  const double gear1_per_solid =
      s.gear == 1 ? 1.0 : static_cast<double>(pm.pair->teeth2) / pm.pair->teeth1;
  // The infinite-inertia force does not depend on speed: any speed gives it.
  o.speed = s.model == MeshForceModel::Dynamic ? s.harmonics_speed : s.speeds[0] * gear1_per_solid;
  progress.start(fmt::format("{}: tooth-force harmonics", context.name()), 0);
  const analyses::ToothForceRevolution rev =
      analyses::tooth_force_over_revolution(pm, o, context.name());
  progress.finish();
  std::vector<int> ks;
  int highest_order = 0;
  for (const auto& f : orders) {
    ks.push_back(f.engine_order);
    highest_order = std::max(highest_order, f.engine_order);
  }
  if (2 * highest_order >= static_cast<int>(rev.tooth.size()))
    throw context.error(
        orders_key,
        fmt::format("orders below {} (half the samples of one revolution)", rev.tooth.size() / 2),
        std::to_string(highest_order));
  const std::vector<gear::HarmonicComponents> comps = rev.components(ks);
  for (std::size_t j = 0; j < orders.size(); ++j) {
    orders[j].tangential = comps[j].tangential;
    orders[j].radial = comps[j].radial;
    orders[j].axial = comps[j].axial;
  }
  return fmt::format(
      "Tooth-force harmonics of gear {} of pair '{}' (N = {} teeth) as mesh_harmonics computes "
      "them: {} mesh model{}, dynamic factor {:.4f}; tooth-load window CR = {:.4f}, shift {:.4g} "
      "pitches; static tangential force {:.6g} N, radial / tangential = {:.4f}, axial / "
      "tangential = {:.4f} ({} flank). The harmonics are used at every speed of the range{}.",
      s.gear, s.pair, rev.teeth,
      s.model == MeshForceModel::Dynamic ? "dynamic" : "infinite-inertia",
      s.model == MeshForceModel::Dynamic
          ? fmt::format(" at gear 1 speed {:.6g} rpm", s.harmonics_speed * kRpm)
          : std::string(),
      rev.mesh.dynamic_factor, rev.contact_ratio, s.window_shift, rev.member.tangential_n,
      rev.directions.radial_per_tangential, rev.directions.axial_per_tangential,
      gear::to_string(rev.flank),
      s.model == MeshForceModel::Dynamic
          ? " (the dynamic mesh force is taken at harmonics_rpm only)"
          : " (the infinite-inertia force does not depend on speed)");
}

std::vector<response::ToothLoad> order_loads(const assembly::SolidComponent& c,
                                             const SectorPoints& points,
                                             const CyclicForcedResponseSettings& s,
                                             const OrderForce& f, double scale) {
  const double share = 1.0 / static_cast<double>(points.excitation.size());
  Eigen::Vector3d direction = Eigen::Vector3d::Zero();
  if (s.force_direction)
    direction =
        Eigen::Vector3d((*s.force_direction)[0], (*s.force_direction)[1], (*s.force_direction)[2])
            .normalized();
  std::vector<response::ToothLoad> loads;
  for (int n : points.excitation) {
    const LoadFrame e = load_frame(c.mesh.coords[static_cast<std::size_t>(n)], s.apex_below);
    response::ToothLoad l;
    l.node_id = c.mesh.node_ids[static_cast<std::size_t>(n)];
    if (!s.pair.empty())
      l.force = scale * share *
                (f.tangential * e.tangential.cast<Complex>() + f.radial * e.radial.cast<Complex>() +
                 f.axial * e.axial.cast<Complex>());
    else
      l.force = (scale * share * f.amplitude) *
                (s.force_direction ? direction : e.tangential).cast<Complex>();
    loads.push_back(l);
  }
  return loads;
}

}  // namespace geardyn::analyses
