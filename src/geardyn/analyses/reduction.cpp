#include "geardyn/analyses/reduction.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <vector>

#include "geardyn/analyses/solid_helpers.hpp"
#include "geardyn/core/error.hpp"
#include "geardyn/core/units.hpp"
#include "geardyn/core/version.hpp"
#include "geardyn/eig/symmetric_eigen.hpp"
#include "geardyn/reduce/craig_bampton.hpp"
#include "geardyn/reduce/frequency_comparison.hpp"
#include "geardyn/reduce/reduced_component_io.hpp"

namespace geardyn::analyses {

namespace {

/// Masters by node sets need a mesh, and at least one set.
void check_inputs(const assembly::SolidComponent& c, const ReductionSettings& s,
                  const Context& context) {
  if (!c.has_mesh())
    throw context.error("solid",
                        "a mesh component: masters are chosen by the node sets of its mesh",
                        fmt::format("solid '{}' of type \"{}\"", c.name, c.kind()));
  if (s.master_sets.empty())
    throw context.error("master_sets",
                        "at least one node set of masters (interfaces, connection, contact, "
                        "excitation or sensor nodes)",
                        "none");
}

Plot error_plot(const ReductionResult& r, const Table& cmp) {
  Plot err;
  err.name = "reduction_error";
  err.title = "Frequency error of the reduced model";
  err.x_label = "mode";
  err.y_label = "error [%]";
  Trace te;
  te.name = "reduced - full";
  te.mode = Trace::Mode::LinesMarkers;
  te.x = cmp.column("mode").numbers;
  te.y = r.error_pct;
  err.traces.push_back(std::move(te));
  return err;
}

/// The convergence table and plot as fixed-interface modes are added.
void add_convergence(AnalysisOutput& out, const ReductionSettings& s, const ReductionResult& r,
                     std::size_t n_compared) {
  const reduce::ReducedComponent& rc = *r.reduced;
  std::vector<int> counts, dropped;
  for (int n : s.convergence) (n <= rc.n_modal ? counts : dropped).push_back(n);
  // The reduction may find fewer fixed-interface modes than reduced_modes asked for (a small
  // interior, or a frequency limit): the counts beyond them are left out and said so.
  if (!dropped.empty())
    out.notes.push_back(fmt::format(
        "Convergence table: the counts {} exceed the {} fixed-interface modes the reduction "
        "found and are left out.",
        fmt::join(dropped, ", "), rc.n_modal));
  if (counts.empty())
    for (int n : {0, rc.n_modal / 8, rc.n_modal / 4, rc.n_modal / 2, rc.n_modal})
      if (counts.empty() || n > counts.back()) counts.push_back(n);
  // A reduced model with n fixed-interface modes has masters + n coordinates, so it can be
  // compared on at most that many modes.
  const int smallest = *std::min_element(counts.begin(), counts.end());
  const int n_compare = std::min(static_cast<int>(n_compared), rc.n_masters() + smallest);
  if (n_compare < 1) return;
  if (n_compare < static_cast<int>(n_compared))
    out.notes.push_back(
        fmt::format("Convergence table: compared on the first {} modes (the reduced model with {} "
                    "fixed-interface modes has only {} coordinates).",
                    n_compare, smallest, rc.n_masters() + smallest));
  Table conv = reduce::convergence_table(rc, r.full.eigenvalues, counts, n_compare);
  conv.title = "Convergence as fixed-interface modes are added";
  Plot p;
  p.name = "convergence";
  p.title = conv.title;
  p.x_label = "fixed-interface modes";
  p.y_label = "largest error [%]";
  p.y_log = true;
  Trace t;
  t.name = fmt::format("first {} modes", n_compare);
  t.mode = Trace::Mode::LinesMarkers;
  t.x = conv.column("n_modes").numbers;
  t.y = conv.column("max_error_pct").numbers;
  for (double& y : t.y) y = std::max(std::abs(y), 1e-12);
  p.traces.push_back(std::move(t));
  out.plots.push_back(std::move(p));
  out.tables.push_back(std::move(conv));
}

}  // namespace

ReductionResult run_reduction(const model::Model& model, const ReductionSettings& s,
                              const Context& context) {
  const assembly::SolidComponent& c = context.solid(model, s.solid);
  check_inputs(c, s, context);
  const std::string& name = context.name();
  Progress& progress = context.progress();
  const auto& dofs = c.system.dofs;
  const std::vector<int> masters = master_dofs(c, s.master_sets);

  ReductionResult r;
  reduce::CraigBamptonOptions o;
  if (s.method == ReductionMethod::CraigBampton) {
    if (!std::isnan(s.f_max)) {
      o.frequency_max_hz = s.f_max / units::kTwoPi;
    } else {
      // More modes than the interior has cannot be known before the masters are chosen: all
      // interior modes are kept (the reduction is then exact) and the note says so.
      const int n_interior = static_cast<int>(c.system.K.rows()) - static_cast<int>(masters.size());
      o.n_modes = std::min(s.n_modes, std::max(n_interior, 0));
      if (s.n_modes > o.n_modes) r.modes_asked_beyond_interior = s.n_modes;
    }
  }
  r.master_dofs = static_cast<int>(masters.size());
  progress.start(fmt::format("{}: reduction", name), 0);
  auto rc = std::make_shared<const reduce::ReducedComponent>(reduce::craig_bampton(
      c.system.K, c.system.M, dofs, masters, o, c.source_sha256, kVersion, progress));
  progress.finish();
  r.reduced = rc;

  progress.start(fmt::format("{}: full-model reference modes", name), 0);
  const int n_full = std::min<int>(s.compare_modes, rc->size());
  r.full = solve_modes(c.system.K, c.system.M, n_full, eig::kNaN, name);
  progress.finish();
  r.reduced_eigenvalues = reduce::reduced_eigenvalues(*rc);
  const Table cmp = reduce::compare_frequencies(r.full.eigenvalues, r.reduced_eigenvalues);
  r.full_hz = cmp.column("full_hz").numbers;
  r.reduced_hz = cmp.column("reduced_hz").numbers;
  r.error_pct = cmp.column("error_pct").numbers;
  for (double e : r.error_pct) r.max_error_pct = std::max(r.max_error_pct, std::abs(e));
  return r;
}

AnalysisOutput reduction_output(const model::Model& model, const ReductionSettings& s,
                                const ReductionResult& r, const Context& context) {
  const assembly::SolidComponent& c = context.solid(model, s.solid);
  const reduce::ReducedComponent& rc = *r.reduced;
  AnalysisOutput out;
  out.notes.push_back(c.description);
  for (const auto& w : c.warnings) out.notes.push_back(w);
  Table cmp = reduce::compare_frequencies(r.full.eigenvalues, r.reduced_eigenvalues);
  cmp.title = "Reduced versus full model frequencies";
  out.notes.push_back(fmt::format(
      "{}: {} masters ({} DOFs of {} node sets) + {} fixed-interface modes = {} coordinates, "
      "from {} DOFs. The first {} frequencies are within {:.3f} % of the full model.",
      s.method == ReductionMethod::Guyan ? "Guyan" : "Craig-Bampton", rc.n_masters(), r.master_dofs,
      s.master_sets.size(), rc.n_modal, rc.size(), c.system.dofs.size(), cmp.rows(),
      r.max_error_pct));
  if (r.modes_asked_beyond_interior > 0)
    out.notes.push_back(fmt::format(
        "reduced_modes = {} exceeds the {} interior DOFs left by the masters: all {} "
        "fixed-interface modes are kept, so the reduced model is exact and no smaller than the "
        "full one; a smaller reduced_modes gives a real reduction.",
        r.modes_asked_beyond_interior, rc.n_modal, rc.n_modal));
  out.tables.push_back(cmp);
  out.plots.push_back(error_plot(r, cmp));
  if (rc.n_modal > 0) add_convergence(out, s, r, cmp.rows());
  if (s.save) {
    std::shared_ptr<const reduce::ReducedComponent> saved = r.reduced;
    out.files.push_back({context.name() + ".h5",
                         "Reduced component (HDF5, docs/reduced-component-format.md); load it "
                         "with a [[solids]] entry of type \"reduced\"",
                         [saved](const std::filesystem::path& path) {
                           reduce::save_reduced(path.string(), *saved);
                         }});
  }
  out.notes.push_back(r.full.brief_report());
  return out;
}

}  // namespace geardyn::analyses
