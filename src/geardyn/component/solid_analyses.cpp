#include "geardyn/component/solid_analyses.hpp"

#include <fmt/format.h>

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <numbers>
#include <set>

#include "geardyn/core/error.hpp"
#include "geardyn/core/version.hpp"
#include "geardyn/cyclic/cyclic_campbell.hpp"
#include "geardyn/cyclic/cyclic_symmetry.hpp"
#include "geardyn/cyclic/replicate.hpp"
#include "geardyn/eig/symmetric_eigen.hpp"
#include "geardyn/meshio/gmsh_view_writer.hpp"
#include "geardyn/meshio/vtu_writer.hpp"
#include "geardyn/reduce/craig_bampton.hpp"
#include "geardyn/reduce/frequency_comparison.hpp"
#include "geardyn/reduce/interface_reduction.hpp"
#include "geardyn/reduce/reduced_component_io.hpp"

namespace geardyn::component {

namespace {

constexpr double kTwoPi = 2.0 * std::numbers::pi;

double hz(double lambda) { return std::sqrt(std::max(lambda, 0.0)) / kTwoPi; }

/// Translations (ux, uy, uz per node) of the mesh from a solution on the assembled DOFs.
std::vector<double> node_translations(const solid::SolidSystem& system, int num_nodes,
                                      const Eigen::VectorXd& u) {
  const Eigen::VectorXd all = system.recovery * u;
  std::vector<double> out(static_cast<std::size_t>(num_nodes) * 3, 0.0);
  for (int n = 0; n < num_nodes; ++n) {
    if (system.node_dofs[static_cast<std::size_t>(n)] < 3) continue;
    const int offset = system.node_offset[static_cast<std::size_t>(n)];
    for (int c = 0; c < 3; ++c) out[static_cast<std::size_t>(n) * 3 + c] = all[offset + c];
  }
  return out;
}

/// Scales a nodal field to a largest displacement magnitude of 1.
void normalise(std::vector<double>& values) {
  double peak = 0.0;
  for (std::size_t i = 0; i + 2 < values.size(); i += 3)
    peak = std::max(peak, std::hypot(values[i], values[i + 1], values[i + 2]));
  if (peak > 0.0)
    for (double& v : values) v /= peak;
}

/// The mode-shape files: a VTU series (ParaView) and one Gmsh file with a view per mode.
void add_shape_files(AnalysisOutput& out, std::shared_ptr<const solid::Mesh> mesh,
                     std::vector<meshio::Field> fields, std::vector<double> frequencies,
                     const std::string& stem, const std::string& what) {
  if (fields.empty()) return;
  auto shared_fields = std::make_shared<const std::vector<meshio::Field>>(std::move(fields));
  auto times = std::make_shared<const std::vector<double>>(std::move(frequencies));
  out.files.push_back(
      {stem + ".pvd",
       fmt::format("{} for ParaView: a .pvd collection of {}_<k>.vtu files, time = frequency [Hz]",
                   what, stem),
       [mesh, shared_fields, times](const std::filesystem::path& path) {
         std::vector<std::vector<meshio::Field>> states;
         for (const auto& f : *shared_fields) states.push_back({f});
         meshio::write_vtu_series(path, *mesh, states, *times);
       }});
  out.files.push_back({stem + ".msh", fmt::format("{} as Gmsh post-processing views", what),
                       [mesh, shared_fields](const std::filesystem::path& path) {
                         meshio::write_gmsh_views(path, *mesh, *shared_fields);
                       }});
}

eig::SymmetricEigenResult solve_modes(const Eigen::SparseMatrix<double>& K,
                                      const Eigen::SparseMatrix<double>& M, int n_modes,
                                      double f_max, const std::string& name) {
  eig::SymmetricEigenOptions o;
  o.n_modes = std::min<int>(n_modes, static_cast<int>(K.rows()));
  if (!std::isnan(f_max)) {
    o.band_max = f_max * f_max;
    o.band_min = -1e-3 * o.band_max;
  }
  eig::SymmetricEigenResult r = eig::solve_symmetric(K, M, o);
  if (r.status != Status::Ok)
    throw NumericalError(name, fmt::format("eigen-solve: {} ({})", r.message, r.brief_report()));
  return r;
}

Plot frequency_plot(const std::string& plot_name, const std::string& title,
                    const std::vector<double>& f) {
  Plot p;
  p.name = plot_name;
  p.title = title;
  p.x_label = "mode";
  p.y_label = "frequency [Hz]";
  Trace t;
  t.name = "natural frequency";
  t.mode = Trace::Mode::Markers;
  for (std::size_t i = 0; i < f.size(); ++i) {
    t.x.push_back(static_cast<double>(i + 1));
    t.y.push_back(f[i]);
  }
  p.traces.push_back(std::move(t));
  return p;
}

/// The DOFs of the nodes of `sets` that have any (nodes fully fixed or eliminated by a rigid
/// element have none and are skipped: they cannot be masters).
std::vector<int> master_dofs(const SolidComponent& c, const std::vector<std::string>& sets) {
  std::vector<int> out;
  for (const auto& set : sets)
    for (int node : c.mesh.node_sets.at(set))
      for (int comp = 0; comp < 6; ++comp)
        if (const int d = c.system.node_dof(node, comp); d >= 0) out.push_back(d);
  std::sort(out.begin(), out.end());
  out.erase(std::unique(out.begin(), out.end()), out.end());
  return out;
}

std::string trust_from_residual(double residual) {
  return fmt::format(
      "Largest backward error of the eigenpairs {:.1e}: the frequencies are exact for the "
      "discrete model to about that relative accuracy; the discretisation error of the mesh is "
      "not included (check it by refining the mesh).",
      residual);
}

}  // namespace

// ---------------------------------------------------------------------------------------------
// solid_modal

AnalysisOutput run_solid_modal(const SolidComponent& c, const model::SolidModalSettings& s,
                               const std::string& name, Progress& progress) {
  AnalysisOutput out;
  auto mesh = std::make_shared<solid::Mesh>();
  solid::SolidSystem full_system;
  const solid::SolidSystem* system = &c.system;
  Eigen::SparseMatrix<double> K, M;
  if (!c.has_mesh()) {
    K = c.stiffness();
    M = c.mass();
    out.notes.push_back(c.description);
  } else if (s.full_wheel && c.sectors > 1) {
    progress.start(fmt::format("{}: replicating the sector", name), 0);
    cyclic::ReplicatedMesh rep = cyclic::replicate(c.mesh, c.sectors, c.interface_tolerance);
    progress.finish();
    *mesh = std::move(rep.mesh);
    solid::AssemblyOptions ao;
    ao.threads = 0;
    ao.progress = &progress;
    full_system = solid::assemble(*mesh, ao);
    system = &full_system;
    K = full_system.K;
    M = full_system.M;
    out.notes.push_back(fmt::format(
        "Full wheel: {} copies of the sector ({}), {} nodes, {} DOFs; {} interface nodes merged "
        "(largest gap {:.2e} m).",
        c.sectors, c.description, mesh->num_nodes(), full_system.num_dofs(), rep.merged_nodes,
        rep.worst_merge_gap));
  } else {
    *mesh = c.mesh;
    K = c.system.K;
    M = c.system.M;
    out.notes.push_back(c.description);
  }
  for (const auto& w : c.warnings) out.notes.push_back(w);

  progress.start(fmt::format("{}: eigen-solve ({} DOFs)", name, K.rows()), 0);
  const eig::SymmetricEigenResult r = solve_modes(K, M, s.n_modes, s.f_max, name);
  progress.finish();

  Table t;
  t.name = "modes";
  t.title = "Natural frequencies";
  std::vector<double> mode, f, res;
  for (Eigen::Index j = 0; j < r.eigenvalues.size(); ++j) {
    mode.push_back(static_cast<double>(j + 1));
    f.push_back(hz(r.eigenvalues[j]));
    res.push_back(r.residuals[j]);
  }
  t.add("mode", "", mode);
  t.add("frequency_hz", "Hz", f);
  t.add("residual", "", res);
  out.tables.push_back(std::move(t));
  out.plots.push_back(frequency_plot("frequencies", "Natural frequencies", f));
  out.notes.push_back(r.brief_report());
  out.notes.push_back(trust_from_residual(r.max_residual()));

  if (!c.has_mesh() && s.shapes > 0)
    out.notes.push_back(fmt::format(
        "Mode shapes are not written: solid '{}' (type \"{}\") has no mesh to draw them on.",
        c.name, c.kind()));
  if (c.has_mesh() && s.shapes > 0) {
    std::vector<meshio::Field> fields;
    std::vector<double> times;
    const int n = std::min<int>(s.shapes, static_cast<int>(r.eigenvalues.size()));
    for (int j = 0; j < n; ++j) {
      meshio::Field field;
      field.name = fmt::format("mode_{}", j + 1);
      field.values = node_translations(*system, mesh->num_nodes(), r.eigenvectors.col(j));
      normalise(field.values);
      fields.push_back(std::move(field));
      times.push_back(f[static_cast<std::size_t>(j)]);
    }
    add_shape_files(out, mesh, std::move(fields), std::move(times), "modes",
                    "Mode shapes (largest displacement 1)");
  }
  return out;
}

// ---------------------------------------------------------------------------------------------
// cyclic_modal

namespace {

/// The ids of the left and right interface nodes of a pairing.
std::pair<std::vector<long>, std::vector<long>> pair_ids(const cyclic::SectorInterfaces& i) {
  std::vector<long> left, right;
  for (const auto& p : i.pairs) {
    left.push_back(p.left_node_id);
    right.push_back(p.right_node_id);
  }
  return {left, right};
}

cyclic::InterfaceOptions interface_options(const SolidComponent& c) {
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

}  // namespace

AnalysisOutput run_cyclic_modal(const SolidComponent& c, const model::CyclicModalSettings& s,
                                const std::string& name, Progress& progress) {
  AnalysisOutput out;
  out.notes.push_back(c.description);
  for (const auto& w : c.warnings) out.notes.push_back(w);
  const int N = c.sectors;

  // The sector the cyclic solve works on: the assembled mesh, its Craig-Bampton reduction, or a
  // reduced component from a file.
  const std::vector<solid::DofInfo> mesh_dofs = c.dofs();
  const cyclic::SectorInterfaces mesh_interfaces =
      cyclic::find_interfaces(mesh_dofs, interface_options(c));
  out.notes.push_back(fmt::format(
      "Sector interfaces: {} node pairs, worst mismatch {:.2e} m (tolerance {:.2e} m) at left "
      "node {}.",
      mesh_interfaces.pairs.size(), mesh_interfaces.worst_mismatch, mesh_interfaces.tolerance_used,
      mesh_interfaces.worst_left_node));
  const auto [left_ids, right_ids] = pair_ids(mesh_interfaces);

  std::optional<reduce::ReducedComponent> cb;
  std::vector<solid::DofInfo> dofs = mesh_dofs;
  Eigen::SparseMatrix<double> K = c.stiffness(), M = c.mass();
  if (s.reduction != model::ReductionMethod::None) {
    if (c.is_reduced())
      throw InputError({}, "reduction",
                       "reduction = \"none\" for a reduced component (it is reduced already)",
                       fmt::format("a further reduction of solid '{}'", c.name));
    std::vector<long> master_ids = left_ids;
    master_ids.insert(master_ids.end(), right_ids.begin(), right_ids.end());
    std::vector<std::vector<int>> lists = {reduce::select_dofs(mesh_dofs, master_ids),
                                           master_dofs(c, s.master_sets)};
    reduce::CraigBamptonOptions o;
    o.n_modes = s.reduction == model::ReductionMethod::Guyan ? 0 : s.cb_modes;
    progress.start(fmt::format("{}: Craig-Bampton reduction of the sector", name), 0);
    cb = reduce::craig_bampton(K, M, mesh_dofs, reduce::merge_dofs(lists), o, c.source_sha256,
                               kVersion, progress);
    progress.finish();
    dofs = cb->reduced_dofs();
    K = cb->K.sparseView();
    M = cb->M.sparseView();
    out.notes.push_back(fmt::format(
        "Sector reduced by {}: {} physical masters (interfaces{}) + {} fixed-interface modes "
        "(up to {:.1f} Hz) from {} DOFs.",
        s.reduction == model::ReductionMethod::Guyan ? "Guyan" : "Craig-Bampton", cb->n_masters(),
        s.master_sets.empty() ? "" : " and master sets", cb->n_modal,
        cb->n_modal > 0 ? cb->fixed_interface_hz[cb->n_modal - 1] : 0.0, mesh_dofs.size()));
  }

  cyclic::InterfaceOptions io = interface_options(c);
  io.left_nodes = left_ids;
  io.right_nodes = right_ids;
  const cyclic::CyclicSector sector(dofs, cyclic::find_interfaces(dofs, io));

  std::vector<int> nds = s.nodal_diameters;
  if (nds.empty())
    for (int h = 0; h <= N / 2; ++h) nds.push_back(h);

  cyclic::CyclicModesResult modes;
  if (s.interface_modes > 0) {
    const std::set<long> left_set(left_ids.begin(), left_ids.end());
    modes.n_sectors = N;
    modes.status = Status::Ok;
    progress.start(fmt::format("{}: interface-mode reduction and solve per nodal diameter", name),
                   nds.size());
    for (std::size_t k = 0; k < nds.size(); ++k) {
      modes.diameters.push_back(
          tran_modes(K, M, sector, left_set, nds[k], s.n_modes, s.interface_modes, name));
      progress.update(k + 1);
    }
    progress.finish();
    out.notes.push_back(fmt::format(
        "Interface-mode (Tran) reduction: the left-interface DOFs of each nodal diameter are "
        "replaced by its {} lowest interface modes.",
        s.interface_modes));
  } else {
    cyclic::CyclicModesOptions o;
    o.nodal_diameters = nds;
    o.eigen.n_modes = s.n_modes;
    modes = cyclic::solve_cyclic_modes(K, M, sector, o, progress);
    if (modes.status != Status::Ok) throw NumericalError(name, modes.message);
  }
  out.notes.push_back(modes.brief_report());
  double worst = 0.0;
  for (const auto& d : modes.diameters) worst = std::max(worst, d.eigen.max_residual());
  out.notes.push_back(trust_from_residual(worst));
  out.tables.push_back(modes.table());
  out.plots.push_back(nd_plot(modes));

  // Rotating-frame Campbell diagram and resonance speeds.
  if (!s.speeds.empty()) {
    cyclic::CyclicCampbellOptions co;
    co.n_sectors = N;
    co.max_engine_order = s.max_engine_order > 0 ? s.max_engine_order : 2 * N;
    const double rpm_min = s.speeds.front() * 60.0 / kTwoPi;
    const double rpm_max = s.speeds.back() * 60.0 / kTwoPi;
    const Table all = cyclic::cyclic_campbell(cyclic::frequency_lines(modes), co);
    Table resonances = rows_in_range(all, rpm_min, rpm_max);
    resonances.title =
        fmt::format("Resonance speeds between {:.0f} and {:.0f} rpm", rpm_min, rpm_max);
    out.plots.push_back(campbell_plot(modes, resonances, rpm_min, rpm_max, co.max_engine_order));
    out.tables.push_back(std::move(resonances));
  }

  // Check against the replicated full wheel (the same mesh, no cyclic symmetry).
  if (s.compare_full && !c.has_mesh())
    out.notes.push_back(fmt::format(
        "compare_full skipped: solid '{}' (type \"{}\") has no mesh to replicate into the full "
        "wheel.",
        c.name, c.kind()));
  if (s.compare_full && c.has_mesh()) {
    std::set<int> solved(nds.begin(), nds.end());
    if (static_cast<int>(solved.size()) != N / 2 + 1) {
      out.notes.push_back("compare_full needs every nodal diameter; the check was skipped.");
    } else {
      progress.start(fmt::format("{}: full 360 deg model", name), 0);
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
      const eig::SymmetricEigenResult fr = solve_modes(full.K, full.M, n_compare, eig::kNaN, name);
      progress.finish();
      Table t;
      t.name = "cyclic_vs_full";
      t.title = "Cyclic symmetry versus the full 360 deg model of the same mesh";
      std::vector<double> mode, f_full, f_cyc, nd, err;
      double worst_err = 0.0;
      for (int j = 0; j < n_compare && j < fr.eigenvalues.size(); ++j) {
        mode.push_back(j + 1);
        f_full.push_back(hz(fr.eigenvalues[j]));
        f_cyc.push_back(cyc[static_cast<std::size_t>(j)].first);
        nd.push_back(cyc[static_cast<std::size_t>(j)].second);
        const double e = (f_cyc.back() - f_full.back()) / std::max(f_full.back(), 1e-3);
        err.push_back(e);
        worst_err = std::max(worst_err, std::abs(e));
      }
      t.add("mode", "", mode);
      t.add("full_hz", "Hz", f_full);
      t.add("cyclic_hz", "Hz", f_cyc);
      t.add("nodal_diameter", "", nd);
      t.add("relative_error", "", err);
      out.tables.push_back(std::move(t));
      out.notes.push_back(fmt::format(
          "Full 360 deg model ({} DOFs): the first {} frequencies agree with the cyclic ones "
          "(double modes counted twice) within {:.1e} relative.",
          full.num_dofs(), mode.size(), worst_err));
    }
  }

  // Full-wheel mode shapes (mesh components only).
  if (c.has_mesh() && s.shapes > 0) {
    const cyclic::CyclicSector mesh_sector(mesh_dofs, mesh_interfaces);
    cyclic::ReplicatedMesh rep = cyclic::replicate(c.mesh, N, c.interface_tolerance);
    auto wheel = std::make_shared<solid::Mesh>(std::move(rep.mesh));
    std::vector<meshio::Field> fields;
    std::vector<double> times;
    constexpr std::size_t kMaxFields = 40;
    for (const auto& d : modes.diameters) {
      const int n = std::min<int>(s.shapes, static_cast<int>(d.frequency_hz.size()));
      for (int j = 0; j < n && fields.size() < kMaxFields; ++j) {
        Eigen::VectorXcd u0 = d.sector_shapes.col(j);
        if (cb) {
          const Eigen::MatrixXd re = reduce::expand(*cb, u0.real());
          const Eigen::MatrixXd im = reduce::expand(*cb, u0.imag());
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
    add_shape_files(
        out, wheel, std::move(fields), std::move(times), "wheel_modes",
        "Full-wheel mode shapes per nodal diameter (real part, largest displacement 1)");
  }
  return out;
}

// ---------------------------------------------------------------------------------------------
// reduction

AnalysisOutput run_reduction(const SolidComponent& c, const model::ReductionSettings& s,
                             const std::string& name, Progress& progress) {
  if (!c.has_mesh())
    throw InputError({}, "solid",
                     "a mesh component: masters are chosen by the node sets of its mesh",
                     fmt::format("solid '{}' of type \"{}\"", c.name, c.kind()));
  if (s.master_sets.empty())
    throw InputError({}, "master_sets",
                     "at least one node set of masters (interfaces, connection, contact, "
                     "excitation or sensor nodes)",
                     "none");
  AnalysisOutput out;
  out.notes.push_back(c.description);
  for (const auto& w : c.warnings) out.notes.push_back(w);
  const auto& dofs = c.system.dofs;
  const std::vector<int> masters = master_dofs(c, s.master_sets);

  reduce::CraigBamptonOptions o;
  if (s.method == model::ReductionMethod::CraigBampton) {
    if (!std::isnan(s.f_max))
      o.frequency_max_hz = s.f_max / kTwoPi;
    else
      o.n_modes = s.n_modes;
  }
  progress.start(fmt::format("{}: reduction", name), 0);
  auto rc = std::make_shared<reduce::ReducedComponent>(reduce::craig_bampton(
      c.system.K, c.system.M, dofs, masters, o, c.source_sha256, kVersion, progress));
  progress.finish();

  progress.start(fmt::format("{}: full-model reference modes", name), 0);
  const int n_full = std::min<int>(s.compare_modes, rc->size());
  const eig::SymmetricEigenResult full =
      solve_modes(c.system.K, c.system.M, n_full, eig::kNaN, name);
  progress.finish();
  const Eigen::VectorXd reduced = reduce::reduced_eigenvalues(*rc);
  Table cmp = reduce::compare_frequencies(full.eigenvalues, reduced);
  double worst = 0.0;
  for (double e : cmp.column("error_pct").numbers) worst = std::max(worst, std::abs(e));
  cmp.title = "Reduced versus full model frequencies";
  out.notes.push_back(fmt::format(
      "{}: {} masters ({} DOFs of {} node sets) + {} fixed-interface modes = {} coordinates, "
      "from {} DOFs. The first {} frequencies are within {:.3f} % of the full model.",
      s.method == model::ReductionMethod::Guyan ? "Guyan" : "Craig-Bampton", rc->n_masters(),
      masters.size(), s.master_sets.size(), rc->n_modal, rc->size(), dofs.size(), cmp.rows(),
      worst));
  out.tables.push_back(cmp);

  Plot err;
  err.name = "reduction_error";
  err.title = "Frequency error of the reduced model";
  err.x_label = "mode";
  err.y_label = "error [%]";
  Trace te;
  te.name = "reduced - full";
  te.mode = Trace::Mode::LinesMarkers;
  te.x = cmp.column("mode").numbers;
  te.y = cmp.column("error_pct").numbers;
  err.traces.push_back(std::move(te));
  out.plots.push_back(std::move(err));

  if (rc->n_modal > 0) {
    std::vector<int> counts = s.convergence;
    if (counts.empty())
      for (int n : {0, rc->n_modal / 8, rc->n_modal / 4, rc->n_modal / 2, rc->n_modal})
        if (counts.empty() || n > counts.back()) counts.push_back(n);
    Table conv =
        reduce::convergence_table(*rc, full.eigenvalues, counts, static_cast<int>(cmp.rows()));
    conv.title = "Convergence as fixed-interface modes are added";
    Plot p;
    p.name = "convergence";
    p.title = conv.title;
    p.x_label = "fixed-interface modes";
    p.y_label = "largest error [%]";
    p.y_log = true;
    Trace t;
    t.name = fmt::format("first {} modes", cmp.rows());
    t.mode = Trace::Mode::LinesMarkers;
    t.x = conv.column("n_modes").numbers;
    t.y = conv.column("max_error_pct").numbers;
    for (double& y : t.y) y = std::max(std::abs(y), 1e-12);
    p.traces.push_back(std::move(t));
    out.plots.push_back(std::move(p));
    out.tables.push_back(std::move(conv));
  }
  if (s.save)
    out.files.push_back(
        {name + ".h5",
         "Reduced component (HDF5, docs/reduced-component-format.md); load it "
         "with a [[solids]] entry of type \"reduced\"",
         [rc](const std::filesystem::path& path) { reduce::save_reduced(path.string(), *rc); }});
  out.notes.push_back(full.brief_report());
  return out;
}

}  // namespace geardyn::component
