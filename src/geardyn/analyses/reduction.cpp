#include "geardyn/analyses/reduction.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <numbers>
#include <vector>

#include "geardyn/analyses/solid_helpers.hpp"
#include "geardyn/core/error.hpp"
#include "geardyn/core/version.hpp"
#include "geardyn/eig/symmetric_eigen.hpp"
#include "geardyn/reduce/craig_bampton.hpp"
#include "geardyn/reduce/frequency_comparison.hpp"
#include "geardyn/reduce/reduced_component_io.hpp"

namespace geardyn::analyses {

namespace {

constexpr double kTwoPi = 2.0 * std::numbers::pi;

}  // namespace

AnalysisOutput run_reduction(const assembly::SolidComponent& c, const ReductionSettings& s,
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
  if (s.method == ReductionMethod::CraigBampton) {
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
      s.method == ReductionMethod::Guyan ? "Guyan" : "Craig-Bampton", rc->n_masters(),
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

}  // namespace geardyn::analyses
