#include "geardyn/analyses/cyclic_modal.hpp"

#include <fmt/format.h>

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <complex>
#include <limits>
#include <memory>
#include <set>
#include <utility>

#include "geardyn/analyses/solid_helpers.hpp"
#include "geardyn/core/error.hpp"
#include "geardyn/core/units.hpp"
#include "geardyn/core/version.hpp"
#include "geardyn/cyclic/cyclic_campbell.hpp"
#include "geardyn/cyclic/cyclic_symmetry.hpp"
#include "geardyn/cyclic/replicate.hpp"
#include "geardyn/eig/symmetric_eigen.hpp"
#include "geardyn/meshio/vtu_writer.hpp"
#include "geardyn/reduce/craig_bampton.hpp"
#include "geardyn/reduce/interface_reduction.hpp"

namespace geardyn::analyses {

namespace {

using units::kTwoPi;

/// The ids of the left and right interface nodes of a pairing.
std::pair<std::vector<long>, std::vector<long>> pair_ids(const cyclic::SectorInterfaces& i) {
  std::vector<long> left, right;
  for (const auto& p : i.pairs) {
    left.push_back(p.left_node_id);
    right.push_back(p.right_node_id);
  }
  return {left, right};
}

cyclic::InterfaceOptions interface_options(const assembly::SolidComponent& c) {
  cyclic::InterfaceOptions o;
  o.n_sectors = c.sectors;
  o.tolerance = c.interface_tolerance;
  return o;
}

/// Modes of one nodal diameter after interface-mode reduction of the (reduced) sector.
cyclic::NodalDiameterModes tran_modes(const Eigen::SparseMatrix<double>& K,
                                      const Eigen::SparseMatrix<double>& M,
                                      const cyclic::CyclicSector& sector,
                                      const std::set<long>& left_ids, int h, int n_modes,
                                      int interface_modes, const std::string& name) {
  const Eigen::MatrixXcd Kh = Eigen::MatrixXcd(sector.reduce(K, h));
  const Eigen::MatrixXcd Mh = Eigen::MatrixXcd(sector.reduce(M, h));
  std::vector<int> iface;
  const auto& reduced = sector.reduced_dofs();
  for (std::size_t j = 0; j < reduced.size(); ++j) {
    const solid::DofInfo& d = sector.dofs()[static_cast<std::size_t>(reduced[j])];
    if (d.component >= 0 && left_ids.count(d.node_id)) iface.push_back(static_cast<int>(j));
  }
  const int n_iface = std::min<int>(interface_modes, static_cast<int>(iface.size()));
  const auto tran = reduce::interface_mode_reduction<std::complex<double>>(Kh, Mh, iface, n_iface);
  Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXcd> es(tran.K, tran.M);
  if (es.info() != Eigen::Success)
    throw NumericalError(name, fmt::format("nodal diameter {}: the dense Hermitian eigen-solve "
                                           "of the interface-reduced sector failed",
                                           h));
  const int n = std::min<int>(n_modes, static_cast<int>(es.eigenvalues().size()));
  cyclic::NodalDiameterModes m;
  m.nodal_diameter = h;
  m.multiplicity = (h == 0 || 2 * h == sector.n_sectors()) ? 1 : 2;
  m.eigen.status = Status::Ok;
  m.eigen.method_used = eig::Method::Dense;
  m.eigen.factorization = "dense (interface-mode reduced)";
  m.eigen.eigenvalues = es.eigenvalues().head(n);
  m.eigen.eigenvectors = es.eigenvectors().leftCols(n);
  m.eigen.residuals.resize(n);
  m.eigen.requested = n_modes;
  m.eigen.converged = n;
  const double nk = tran.K.cwiseAbs().colwise().sum().maxCoeff();
  const double nm = tran.M.cwiseAbs().colwise().sum().maxCoeff();
  m.frequency_hz.resize(n);
  m.sector_shapes.resize(sector.num_dofs(), n);
  for (int j = 0; j < n; ++j) {
    const double lambda = m.eigen.eigenvalues[j];
    const Eigen::VectorXcd phi = m.eigen.eigenvectors.col(j);
    m.eigen.residuals[j] = (tran.K * phi - lambda * (tran.M * phi)).norm() /
                           ((nk + std::abs(lambda) * nm) * phi.norm());
    m.frequency_hz[j] = hz(lambda);
    m.sector_shapes.col(j) = sector.expand(tran.transformation * phi, h);
  }
  return m;
}

Plot nd_plot(const cyclic::CyclicModesResult& r) {
  Plot p;
  p.name = "nodal_diameter_diagram";
  p.title = "Natural frequency versus nodal diameter";
  p.x_label = "nodal diameter";
  p.y_label = "frequency [Hz]";
  int max_modes = 0;
  for (const auto& d : r.diameters)
    max_modes = std::max(max_modes, static_cast<int>(d.frequency_hz.size()));
  for (int m = 0; m < max_modes; ++m) {
    Trace t;
    t.name = fmt::format("mode {}", m + 1);
    t.mode = Trace::Mode::LinesMarkers;
    for (const auto& d : r.diameters)
      if (m < d.frequency_hz.size()) {
        t.x.push_back(d.nodal_diameter);
        t.y.push_back(d.frequency_hz[m]);
      }
    p.traces.push_back(std::move(t));
  }
  return p;
}

Plot campbell_plot(const cyclic::CyclicModesResult& r, const Table& resonances, double rpm_min,
                   double rpm_max, int max_order) {
  Plot p;
  p.name = "campbell_rotating_frame";
  p.title = "Campbell diagram in the rotating frame";
  p.x_label = "speed [rpm]";
  p.y_label = "frequency [Hz]";
  double f_top = 0.0;
  for (int k = 1; k <= max_order; ++k) {
    Trace t;
    t.name = fmt::format("EO {}", k);
    t.dash = "dot";
    t.x = {rpm_min, rpm_max};
    t.y = {k * rpm_min / 60.0, k * rpm_max / 60.0};
    f_top = std::max(f_top, t.y[1]);
    p.traces.push_back(std::move(t));
  }
  for (const auto& d : r.diameters)
    for (Eigen::Index m = 0; m < d.frequency_hz.size(); ++m) {
      if (d.frequency_hz[m] > f_top * 1.05) continue;
      Trace t;
      t.name = fmt::format("ND {} mode {}", d.nodal_diameter, m + 1);
      t.x = {rpm_min, rpm_max};
      t.y = {d.frequency_hz[m], d.frequency_hz[m]};
      p.traces.push_back(std::move(t));
    }
  Trace res;
  res.name = "resonances";
  res.mode = Trace::Mode::Markers;
  if (resonances.rows() > 0) {
    const auto& speed = resonances.column("resonance_speed_rpm").numbers;
    const auto& f = resonances.column("frequency_hz").numbers;
    const auto& nd = resonances.column("nodal_diameter").numbers;
    const auto& eo = resonances.column("engine_order").numbers;
    for (std::size_t i = 0; i < speed.size(); ++i) {
      res.x.push_back(speed[i]);
      res.y.push_back(f[i]);
      res.hover.push_back(fmt::format("ND {} EO {}", nd[i], eo[i]));
    }
  }
  p.traces.push_back(std::move(res));
  return p;
}

/// Keeps the rows of a resonance table whose speed lies in [lo, hi].
Table rows_in_range(const Table& t, double lo, double hi) {
  const auto& speed = t.column("resonance_speed_rpm").numbers;
  Table out;
  out.name = t.name;
  out.title = t.title;
  for (const auto& col : t.columns) {
    Column c;
    c.name = col.name;
    c.unit = col.unit;
    c.text = col.text;
    for (std::size_t i = 0; i < speed.size(); ++i) {
      if (speed[i] < lo - 1e-9 * hi || speed[i] > hi * (1 + 1e-12)) continue;
      if (col.text)
        c.texts.push_back(col.texts[i]);
      else
        c.numbers.push_back(col.numbers[i]);
    }
    out.columns.push_back(std::move(c));
  }
  return out;
}

/// The Craig-Bampton (or Guyan) reduction of the sector: both interfaces and the master sets
/// kept physical.
std::shared_ptr<const reduce::ReducedComponent> reduce_sector(
    const assembly::SolidComponent& c, const CyclicModalSettings& s,
    const std::vector<solid::DofInfo>& mesh_dofs, const std::vector<long>& left_ids,
    const std::vector<long>& right_ids, const Context& context) {
  if (c.is_reduced())
    throw context.error("reduction",
                        "reduction = \"none\" for a reduced component (it is reduced already)",
                        fmt::format("a further reduction of solid '{}'", c.name));
  std::vector<long> master_ids = left_ids;
  master_ids.insert(master_ids.end(), right_ids.begin(), right_ids.end());
  std::vector<std::vector<int>> lists = {reduce::select_dofs(mesh_dofs, master_ids),
                                         master_dofs(c, s.master_sets)};
  reduce::CraigBamptonOptions o;
  o.n_modes = s.reduction == ReductionMethod::Guyan ? 0 : s.cb_modes;
  Progress& progress = context.progress();
  progress.start(fmt::format("{}: Craig-Bampton reduction of the sector", context.name()), 0);
  auto cb = std::make_shared<const reduce::ReducedComponent>(
      reduce::craig_bampton(c.stiffness(), c.mass(), mesh_dofs, reduce::merge_dofs(lists), o,
                            c.source_sha256, kVersion, progress));
  progress.finish();
  return cb;
}

/// The modes of each nodal diameter of the sector (K, M): directly, or after interface-mode
/// (Tran) reduction per nodal diameter.
cyclic::CyclicModesResult solve_diameters(const Eigen::SparseMatrix<double>& K,
                                          const Eigen::SparseMatrix<double>& M,
                                          const cyclic::CyclicSector& sector,
                                          const std::vector<long>& left_ids,
                                          const std::vector<int>& nds, int n_sectors,
                                          const CyclicModalSettings& s, const Context& context) {
  Progress& progress = context.progress();
  if (s.interface_modes <= 0) {
    cyclic::CyclicModesOptions o;
    o.nodal_diameters = nds;
    o.eigen.n_modes = s.n_modes;
    cyclic::CyclicModesResult modes = cyclic::solve_cyclic_modes(K, M, sector, o, progress);
    if (modes.status != Status::Ok) throw NumericalError(context.name(), modes.message);
    return modes;
  }
  const std::set<long> left_set(left_ids.begin(), left_ids.end());
  cyclic::CyclicModesResult modes;
  modes.n_sectors = n_sectors;
  modes.status = Status::Ok;
  progress.start(
      fmt::format("{}: interface-mode reduction and solve per nodal diameter", context.name()),
      nds.size());
  for (std::size_t k = 0; k < nds.size(); ++k) {
    modes.diameters.push_back(
        tran_modes(K, M, sector, left_set, nds[k], s.n_modes, s.interface_modes, context.name()));
    progress.update(k + 1);
  }
  progress.finish();
  return modes;
}

/// compare_full: the replicated 360 deg mesh solved without cyclic symmetry, its lowest
/// frequencies against the cyclic ones (double modes counted twice), when every nodal diameter
/// was solved.
CyclicFullComparison compare_with_full_wheel(const assembly::SolidComponent& c,
                                             const cyclic::CyclicModesResult& modes,
                                             const std::vector<int>& nds, const Context& context) {
  CyclicFullComparison out;
  const int N = c.sectors;
  const std::set<int> solved(nds.begin(), nds.end());
  if (static_cast<int>(solved.size()) != N / 2 + 1) return out;
  Progress& progress = context.progress();
  progress.start(fmt::format("{}: full 360 deg model", context.name()), 0);
  const cyclic::ReplicatedMesh rep = cyclic::replicate(c.mesh, N, c.interface_tolerance);
  solid::AssemblyOptions ao;
  ao.threads = 0;
  const solid::SolidSystem full = solid::assemble(rep.mesh, ao);
  std::vector<std::pair<double, int>> cyc;  // (frequency, nodal diameter) with multiplicity
  double f_cut = std::numeric_limits<double>::infinity();
  for (const auto& d : modes.diameters) {
    for (Eigen::Index j = 0; j < d.frequency_hz.size(); ++j)
      for (int k = 0; k < d.multiplicity; ++k)
        cyc.emplace_back(d.frequency_hz[j], d.nodal_diameter);
    f_cut = std::min(f_cut, d.frequency_hz[d.frequency_hz.size() - 1]);
  }
  std::sort(cyc.begin(), cyc.end());
  int n_compare = 0;
  while (n_compare < static_cast<int>(cyc.size()) &&
         cyc[static_cast<std::size_t>(n_compare)].first <= f_cut * (1 + 1e-9))
    ++n_compare;
  const eig::SymmetricEigenResult fr =
      solve_modes(full.K, full.M, n_compare, eig::kNaN, context.name());
  progress.finish();
  out.done = true;
  out.full_dofs = static_cast<int>(full.num_dofs());
  for (int j = 0; j < n_compare && j < fr.eigenvalues.size(); ++j) {
    out.full_hz.push_back(hz(fr.eigenvalues[j]));
    out.cyclic_hz.push_back(cyc[static_cast<std::size_t>(j)].first);
    out.nodal_diameter.push_back(cyc[static_cast<std::size_t>(j)].second);
    const double e =
        (out.cyclic_hz.back() - out.full_hz.back()) / std::max(out.full_hz.back(), 1e-3);
    out.relative_error.push_back(e);
    out.worst_error = std::max(out.worst_error, std::abs(e));
  }
  return out;
}

/// The notes on the sector: the component, its interfaces and its reductions.
void add_sector_notes(AnalysisOutput& out, const assembly::SolidComponent& c,
                      const CyclicModalSettings& s, const CyclicModalResult& r) {
  out.notes.push_back(c.description);
  for (const auto& w : c.warnings) out.notes.push_back(w);
  const cyclic::SectorInterfaces& mi = r.mesh_interfaces;
  out.notes.push_back(fmt::format(
      "Sector interfaces: {} node pairs, worst mismatch {:.2e} m (tolerance {:.2e} m) at left "
      "node {}.",
      mi.pairs.size(), mi.worst_mismatch, mi.tolerance_used, mi.worst_left_node));
  if (r.reduction) {
    const reduce::ReducedComponent& cb = *r.reduction;
    out.notes.push_back(fmt::format(
        "Sector reduced by {}: {} physical masters (interfaces{}) + {} fixed-interface modes "
        "(up to {:.1f} Hz) from {} DOFs.",
        s.reduction == ReductionMethod::Guyan ? "Guyan" : "Craig-Bampton", cb.n_masters(),
        s.master_sets.empty() ? "" : " and master sets", cb.n_modal,
        cb.n_modal > 0 ? cb.fixed_interface_hz[cb.n_modal - 1] : 0.0, r.mesh_dofs));
  }
  if (s.interface_modes > 0)
    out.notes.push_back(fmt::format(
        "Interface-mode (Tran) reduction: the left-interface DOFs of each nodal diameter are "
        "replaced by its {} lowest interface modes.",
        s.interface_modes));
}

/// The rotating-frame Campbell diagram and the resonance speeds in the speed range.
void add_campbell(AnalysisOutput& out, int n_sectors, const CyclicModalSettings& s,
                  const cyclic::CyclicModesResult& modes) {
  cyclic::CyclicCampbellOptions co;
  co.n_sectors = n_sectors;
  co.max_engine_order = s.max_engine_order > 0 ? s.max_engine_order : 2 * n_sectors;
  const double rpm_min = s.speeds.front() * 60.0 / kTwoPi;
  const double rpm_max = s.speeds.back() * 60.0 / kTwoPi;
  const Table all = cyclic::cyclic_campbell(cyclic::frequency_lines(modes), co);
  Table resonances = rows_in_range(all, rpm_min, rpm_max);
  resonances.title =
      fmt::format("Resonance speeds between {:.0f} and {:.0f} rpm", rpm_min, rpm_max);
  out.plots.push_back(campbell_plot(modes, resonances, rpm_min, rpm_max, co.max_engine_order));
  out.tables.push_back(std::move(resonances));
}

/// The compare_full table and note (or why the check was skipped).
void add_comparison(AnalysisOutput& out, const assembly::SolidComponent& c,
                    const CyclicFullComparison& f) {
  if (!c.has_mesh()) {
    out.notes.push_back(fmt::format(
        "compare_full skipped: solid '{}' (type \"{}\") has no mesh to replicate into the full "
        "wheel.",
        c.name, c.kind()));
    return;
  }
  if (!f.done) {
    out.notes.push_back("compare_full needs every nodal diameter; the check was skipped.");
    return;
  }
  Table t;
  t.name = "cyclic_vs_full";
  t.title = "Cyclic symmetry versus the full 360 deg model of the same mesh";
  std::vector<double> mode;
  for (std::size_t j = 0; j < f.full_hz.size(); ++j) mode.push_back(static_cast<double>(j + 1));
  t.add("mode", "", mode);
  t.add("full_hz", "Hz", f.full_hz);
  t.add("cyclic_hz", "Hz", f.cyclic_hz);
  t.add("nodal_diameter", "", f.nodal_diameter);
  t.add("relative_error", "", f.relative_error);
  out.tables.push_back(std::move(t));
  out.notes.push_back(fmt::format(
      "Full 360 deg model ({} DOFs): the first {} frequencies agree with the cyclic ones "
      "(double modes counted twice) within {:.1e} relative.",
      f.full_dofs, mode.size(), f.worst_error));
}

/// Full-wheel mode shapes (mesh components only): each nodal diameter's sector shapes, expanded
/// from the reduction and around the wheel.
void add_wheel_shapes(AnalysisOutput& out, const assembly::SolidComponent& c,
                      const CyclicModalSettings& s, const CyclicModalResult& r) {
  const int N = c.sectors;
  const cyclic::CyclicSector mesh_sector(c.dofs(), r.mesh_interfaces);
  cyclic::ReplicatedMesh rep = cyclic::replicate(c.mesh, N, c.interface_tolerance);
  auto wheel = std::make_shared<solid::Mesh>(std::move(rep.mesh));
  std::vector<meshio::Field> fields;
  std::vector<double> times;
  constexpr std::size_t kMaxFields = 40;
  for (const auto& d : r.modes.diameters) {
    const int n = std::min<int>(s.shapes, static_cast<int>(d.frequency_hz.size()));
    for (int j = 0; j < n && fields.size() < kMaxFields; ++j) {
      Eigen::VectorXcd u0 = d.sector_shapes.col(j);
      if (r.reduction) {
        const Eigen::MatrixXd re = reduce::expand(*r.reduction, u0.real());
        const Eigen::MatrixXd im = reduce::expand(*r.reduction, u0.imag());
        u0 = re.col(0).cast<std::complex<double>>() +
             std::complex<double>(0.0, 1.0) * im.col(0).cast<std::complex<double>>();
      }
      meshio::Field field;
      field.name = fmt::format("nd{}_mode{}", d.nodal_diameter, j + 1);
      field.values.assign(static_cast<std::size_t>(wheel->num_nodes()) * 3, 0.0);
      for (int sec = 0; sec < N; ++sec) {
        const Eigen::VectorXd us = mesh_sector.expand_to_sector(u0, d.nodal_diameter, sec).real();
        const std::vector<double> v = node_translations(c.system, c.mesh.num_nodes(), us);
        const auto& map = rep.node_map[static_cast<std::size_t>(sec)];
        for (std::size_t i = 0; i < map.size(); ++i)
          for (int k = 0; k < 3; ++k)
            field.values[static_cast<std::size_t>(map[i]) * 3 + k] = v[i * 3 + k];
      }
      normalise(field.values);
      fields.push_back(std::move(field));
      times.push_back(d.frequency_hz[j]);
    }
  }
  add_shape_files(out, wheel, std::move(fields), std::move(times), "wheel_modes",
                  "Full-wheel mode shapes per nodal diameter (real part, largest displacement 1)");
}

}  // namespace

CyclicModalResult run_cyclic_modal(const model::Model& model, const CyclicModalSettings& s,
                                   const Context& context) {
  const assembly::SolidComponent& c = context.solid(model, s.solid);
  const int N = c.sectors;
  CyclicModalResult r;

  // The sector the cyclic solve works on: the assembled mesh, its Craig-Bampton reduction, or a
  // reduced component from a file.
  const std::vector<solid::DofInfo> mesh_dofs = c.dofs();
  r.mesh_dofs = mesh_dofs.size();
  r.mesh_interfaces = cyclic::find_interfaces(mesh_dofs, interface_options(c));
  const auto [left_ids, right_ids] = pair_ids(r.mesh_interfaces);

  std::vector<solid::DofInfo> dofs = mesh_dofs;
  Eigen::SparseMatrix<double> K = c.stiffness(), M = c.mass();
  if (s.reduction != ReductionMethod::None) {
    r.reduction = reduce_sector(c, s, mesh_dofs, left_ids, right_ids, context);
    dofs = r.reduction->reduced_dofs();
    K = r.reduction->K.sparseView();
    M = r.reduction->M.sparseView();
  }

  cyclic::InterfaceOptions io = interface_options(c);
  io.left_nodes = left_ids;
  io.right_nodes = right_ids;
  const cyclic::CyclicSector sector(dofs, cyclic::find_interfaces(dofs, io));

  r.nodal_diameters = s.nodal_diameters;
  if (r.nodal_diameters.empty())
    for (int h = 0; h <= N / 2; ++h) r.nodal_diameters.push_back(h);
  r.modes = solve_diameters(K, M, sector, left_ids, r.nodal_diameters, N, s, context);
  for (const auto& d : r.modes.diameters)
    for (Eigen::Index j = 0; j < d.frequency_hz.size(); ++j)
      r.frequency_hz.push_back(d.frequency_hz[j]);
  std::sort(r.frequency_hz.begin(), r.frequency_hz.end());

  // Check against the replicated full wheel (the same mesh, no cyclic symmetry).
  if (s.compare_full && c.has_mesh())
    r.full = compare_with_full_wheel(c, r.modes, r.nodal_diameters, context);
  return r;
}

AnalysisOutput cyclic_modal_output(const model::Model& model, const CyclicModalSettings& s,
                                   const CyclicModalResult& r, const Context& context) {
  const assembly::SolidComponent& c = context.solid(model, s.solid);
  AnalysisOutput out;
  add_sector_notes(out, c, s, r);
  out.notes.push_back(r.modes.brief_report());
  double worst = 0.0;
  for (const auto& d : r.modes.diameters) worst = std::max(worst, d.eigen.max_residual());
  out.notes.push_back(trust_from_residual(worst));
  out.tables.push_back(r.modes.table());
  out.plots.push_back(nd_plot(r.modes));
  if (!s.speeds.empty()) add_campbell(out, c.sectors, s, r.modes);
  if (s.compare_full) add_comparison(out, c, r.full);
  if (c.has_mesh() && s.shapes > 0) {
    // Expanding every shape around the wheel takes tens of seconds on a fine sector: shown.
    Progress& progress = context.progress();
    progress.start(fmt::format("{}: full-wheel mode shapes", context.name()), 0);
    add_wheel_shapes(out, c, s, r);
    progress.finish();
  }
  return out;
}

}  // namespace geardyn::analyses
