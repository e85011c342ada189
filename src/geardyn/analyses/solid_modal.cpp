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

}  // namespace

AnalysisOutput run_solid_modal(const assembly::SolidComponent& c, const SolidModalSettings& s,
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

}  // namespace geardyn::analyses
