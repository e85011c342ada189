#include "geardyn/analyses/solid_modal.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <memory>
#include <vector>

#include "geardyn/analyses/solid_helpers.hpp"
#include "geardyn/cyclic/replicate.hpp"
#include "geardyn/eig/symmetric_eigen.hpp"
#include "geardyn/meshio/vtu_writer.hpp"

namespace geardyn::analyses {

namespace {

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

/// The mode-shape files, or the note that a component without a mesh has none.
void add_shapes(AnalysisOutput& out, const assembly::SolidComponent& c, const SolidModalSettings& s,
                const SolidModalResult& r) {
  if (s.shapes <= 0) return;
  if (!c.has_mesh()) {
    out.notes.push_back(fmt::format(
        "Mode shapes are not written: solid '{}' (type \"{}\") has no mesh to draw them on.",
        c.name, c.kind()));
    return;
  }
  const solid::SolidSystem& system = r.wheel_system ? *r.wheel_system : c.system;
  const std::shared_ptr<const solid::Mesh> mesh =
      r.wheel_mesh ? r.wheel_mesh : std::make_shared<const solid::Mesh>(c.mesh);
  std::vector<meshio::Field> fields;
  std::vector<double> times;
  const int n = std::min<int>(s.shapes, static_cast<int>(r.modes.eigenvalues.size()));
  for (int j = 0; j < n; ++j) {
    meshio::Field field;
    field.name = fmt::format("mode_{}", j + 1);
    field.values = node_translations(system, mesh->num_nodes(), r.modes.eigenvectors.col(j));
    normalise(field.values);
    fields.push_back(std::move(field));
    times.push_back(r.frequency_hz[static_cast<std::size_t>(j)]);
  }
  add_shape_files(out, mesh, std::move(fields), std::move(times), "modes",
                  "Mode shapes (largest displacement 1)");
}

}  // namespace

SolidModalResult run_solid_modal(const model::Model& model, const SolidModalSettings& s,
                                 const Context& context) {
  const assembly::SolidComponent& c = context.solid(model, s.solid);
  const std::string& name = context.name();
  Progress& progress = context.progress();
  SolidModalResult r;
  Eigen::SparseMatrix<double> K, M;
  if (c.has_mesh() && s.full_wheel && c.sectors > 1) {
    progress.start(fmt::format("{}: replicating the sector", name), 0);
    cyclic::ReplicatedMesh rep = cyclic::replicate(c.mesh, c.sectors, c.interface_tolerance);
    progress.finish();
    auto mesh = std::make_shared<solid::Mesh>(std::move(rep.mesh));
    solid::AssemblyOptions ao;
    ao.threads = 0;
    ao.progress = &progress;
    auto system = std::make_shared<solid::SolidSystem>(solid::assemble(*mesh, ao));
    K = system->K;
    M = system->M;
    r.wheel_mesh = std::move(mesh);
    r.wheel_system = std::move(system);
    r.merged_nodes = rep.merged_nodes;
    r.worst_merge_gap = rep.worst_merge_gap;
  } else if (c.has_mesh()) {
    K = c.system.K;
    M = c.system.M;
  } else {
    K = c.stiffness();
    M = c.mass();
  }
  progress.start(fmt::format("{}: eigen-solve ({} DOFs)", name, K.rows()), 0);
  r.modes = solve_modes(K, M, s.n_modes, s.f_max, name);
  progress.finish();
  for (Eigen::Index j = 0; j < r.modes.eigenvalues.size(); ++j)
    r.frequency_hz.push_back(hz(r.modes.eigenvalues[j]));
  return r;
}

AnalysisOutput solid_modal_output(const model::Model& model, const SolidModalSettings& s,
                                  const SolidModalResult& r, const Context& context) {
  const assembly::SolidComponent& c = context.solid(model, s.solid);
  AnalysisOutput out;
  if (r.wheel_mesh)
    out.notes.push_back(fmt::format(
        "Full wheel: {} copies of the sector ({}), {} nodes, {} DOFs; {} interface nodes merged "
        "(largest gap {:.2e} m).",
        c.sectors, c.description, r.wheel_mesh->num_nodes(), r.wheel_system->num_dofs(),
        r.merged_nodes, r.worst_merge_gap));
  else
    out.notes.push_back(c.description);
  for (const auto& w : c.warnings) out.notes.push_back(w);

  Table t;
  t.name = "modes";
  t.title = "Natural frequencies";
  std::vector<double> mode, res;
  for (Eigen::Index j = 0; j < r.modes.eigenvalues.size(); ++j) {
    mode.push_back(static_cast<double>(j + 1));
    res.push_back(r.modes.residuals[j]);
  }
  t.add("mode", "", mode);
  t.add("frequency_hz", "Hz", r.frequency_hz);
  t.add("residual", "", res);
  out.tables.push_back(std::move(t));
  out.plots.push_back(frequency_plot("frequencies", "Natural frequencies", r.frequency_hz));
  out.notes.push_back(r.modes.brief_report());
  out.notes.push_back(trust_from_residual(r.modes.max_residual()));
  add_shapes(out, c, s, r);
  return out;
}

}  // namespace geardyn::analyses
