#include "commands.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <vector>

#include "geardyn/analyses/model_file.hpp"
#include "geardyn/analyses/run_analysis.hpp"
#include "geardyn/assembly/solid_component.hpp"
#include "geardyn/assembly/system_builder.hpp"
#include "geardyn/core/error.hpp"
#include "geardyn/core/progress.hpp"
#include "geardyn/io/results_writer.hpp"
#include "geardyn/io/sha256.hpp"
#include "geardyn/model/parse.hpp"
#include "geardyn/model/schema.hpp"
#include "geardyn/report/html_report.hpp"

namespace geardyn::app {
namespace {

model::Model load_model(const std::string& path, const std::vector<std::string>& overrides,
                        model::ModelDocument& document) {
  document = analyses::load_document(path);
  for (const auto& o : overrides) model::apply_override(document, o);
  return model::build_model(document);
}

std::string format_cell(const Column& c, std::size_t row) {
  if (c.text) return c.texts[row];
  return fmt::format("{:.6g}", c.numbers[row]);
}

// A compact view of a table on the terminal: the answer to the user's question at a glance.
void print_table(const Table& table, std::size_t max_rows, std::size_t max_columns) {
  const std::size_t n_cols = std::min(table.columns.size(), max_columns);
  std::vector<std::size_t> width(n_cols);
  const std::size_t n_rows = std::min(table.rows(), max_rows);
  for (std::size_t j = 0; j < n_cols; ++j) {
    width[j] = table.columns[j].name.size();
    for (std::size_t i = 0; i < n_rows; ++i)
      width[j] = std::max(width[j], format_cell(table.columns[j], i).size());
  }
  std::string line = "    ";
  for (std::size_t j = 0; j < n_cols; ++j)
    line += fmt::format("{:>{}}  ", table.columns[j].name, width[j]);
  std::printf("%s\n", line.c_str());
  for (std::size_t i = 0; i < n_rows; ++i) {
    line = "    ";
    for (std::size_t j = 0; j < n_cols; ++j)
      line += fmt::format("{:>{}}  ", format_cell(table.columns[j], i), width[j]);
    std::printf("%s\n", line.c_str());
  }
  if (table.rows() > n_rows || table.columns.size() > n_cols)
    std::printf("    (%zu rows x %zu columns in %s.csv)\n", table.rows(), table.columns.size(),
                table.name.c_str());
}

// Says how an analysis ended: its status line and first table (unless quiet), and on stderr
// why it is not ok. Returns whether it is ok.
bool tell_outcome(const AnalysisOutput& out, bool say) {
  if (say)
    std::printf("\n[%s] %s: %s (%.2f s)\n", out.type.c_str(), out.name.c_str(),
                std::string(to_string(out.status)).c_str(), out.run_time_s);
  if (out.status == Status::Unstable) {
    // Computed, but what a steady state means is void: said as loudly as a failure.
    std::fprintf(stderr, "error: analysis '%s' is unstable: %s\n", out.name.c_str(),
                 out.message.c_str());
    return false;
  }
  if (out.status != Status::Ok) {
    std::fprintf(stderr, "error: analysis '%s' failed: %s\n", out.name.c_str(),
                 out.message.c_str());
    return false;
  }
  if (say && !out.tables.empty()) print_table(out.tables.front(), 12, 9);
  return true;
}

}  // namespace

std::filesystem::path default_output_dir(const std::string& model_path) {
  // results/<model file name>; a file called just "model" (every example's model.toml) is
  // named by its folder instead, so two models never share a default results folder by name.
  const std::filesystem::path path = std::filesystem::absolute(model_path).lexically_normal();
  std::string name = path.stem().string();
  const std::string folder = path.parent_path().filename().string();
  if (name == "model" && !folder.empty()) name = folder;
  return std::filesystem::path("results") / name;
}

int command_run(const RunOptions& options, int argc, char** argv) {
  model::ModelDocument document;
  const model::Model m = load_model(options.model_path, options.overrides, document);

  // Every name in --only must exist: a typo must not silently run nothing.
  for (const auto& name : options.only)
    if (m.find_analysis(name) == nullptr)
      throw InputError({options.model_path, 0, 0}, "--only", "the name of an analysis in the model",
                       fmt::format("'{}'", name));

  namespace fs = std::filesystem;
  const fs::path outdir = options.output_dir.empty() ? default_output_dir(options.model_path)
                                                     : fs::path(options.output_dir);

  std::unique_ptr<Progress> progress;
  if (options.quiet)
    progress = std::make_unique<NullProgress>();
  else
    progress = std::make_unique<StderrProgress>();

  RunInfo info;
  info.model_path = options.model_path;
  info.model_sha256 = io::sha256_file(options.model_path);
  info.model_title = m.title;
  for (int i = 0; i < argc; ++i) info.command_line += (i ? " " : "") + std::string(argv[i]);

  std::vector<const model::Analysis*> selected;
  for (const auto& a : m.analyses)
    if (options.only.empty()
            ? a.enabled
            : std::find(options.only.begin(), options.only.end(), a.name) != options.only.end())
      selected.push_back(&a);
  std::vector<std::string> not_run;
  for (const auto* a : selected) not_run.push_back(a->name);

  // The results folder is checked (and locked) before anything is computed: a folder geardyn
  // may not replace, one it cannot create, or one holding a user's file where an analysis would
  // be written is bad input found at once, not after every analysis has run.
  std::unique_ptr<io::ResultsWriter> writer;
  try {
    writer = std::make_unique<io::ResultsWriter>(outdir, info);
    writer->check(not_run);
  } catch (const std::exception& e) {
    throw InputError({options.model_path, 0, 0}, "--output",
                     "a results folder geardyn can write (new, empty, or an earlier geardyn "
                     "results folder)",
                     e.what());
  }

  // Solid components are read, generated and checked before anything runs: a bad mesh is bad
  // input (exit 2), found before any result is written.
  // Gear pairs (geometry, contact ratio, STE files) and measured files likewise.
  const assembly::SolidComponents solids = assembly::build_solids(m, *progress);
  analyses::check_inputs(m, solids);

  std::vector<AnalysisOutput> outputs;
  bool failed = false, build_failed = false;
  fe::LinearSystem system;
  std::vector<assembly::CoupledSolid> coupled;
  try {
    if (!m.shafts.empty() || !m.nodes.empty())
      system = assembly::build_system(m, &solids, coupled, *progress);
  } catch (const NumericalError& e) {
    AnalysisOutput out;
    out.name = "build";
    out.type = "build";
    out.status = Status::Failed;
    out.message = e.what();
    outputs.push_back(out);
    build_failed = failed = true;
  }

  // -q: errors only (stderr); without it, a summary of each analysis on stdout.
  const bool say = !options.quiet;
  if (say)
    std::printf("geardyn: %s — %d nodes, %d DOFs\n",
                m.title.empty() ? options.model_path.c_str() : m.title.c_str(),
                system.dofs.num_nodes(), system.size());
  for (const auto& [solid_name, solid] : solids) {
    if (!say) continue;
    std::printf("solid %s: %s\n", solid_name.c_str(), solid.description.c_str());
    // What the reader skipped (unsupported Nastran cards, ...) is said where it is seen, not
    // only in the manifest.
    for (const auto& w : solid.warnings)
      std::fprintf(stderr, "warning: solid '%s': %s\n", solid_name.c_str(), w.c_str());
  }

  // Results are kept as they come: each analysis is written when it finishes, with a manifest
  // and report that say which analyses are still to come, so a later failure or a kill keeps
  // the finished ones.
  if (build_failed) not_run.clear();
  writer->begin(not_run);
  for (const auto& kept : writer->kept_files())
    std::fprintf(stderr, "note: kept '%s' in the results folder (not written by geardyn)\n",
                 kept.c_str());
  auto keep = [&](const AnalysisOutput& out) {
    progress->start(fmt::format("{}: writing results", out.name), 0);  // VTU series take a while
    writer->add(out);
    std::erase(not_run, out.name);
    info.not_run = not_run;
    writer->add_report(report::render_html(info, outputs));
    progress->finish();
  };
  if (build_failed) keep(outputs.back());
  for (std::size_t i = 0; !build_failed && i < selected.size(); ++i) {
    const model::Analysis& a = *selected[i];
    // Which analysis is running, as it starts (progress of its long phases follows).
    if (say)
      std::fprintf(stderr, "analysis %zu/%zu: %s (%s)\n", i + 1, selected.size(), a.name.c_str(),
                   a.type.c_str());
    analyses::Context context(m, a);
    context.with_document(&document).with_progress(progress.get()).with_solids(&solids);
    if (!m.shafts.empty() || !m.nodes.empty())
      context.with_system(&system).with_coupled_solids(&coupled);
    outputs.push_back(analyses::run_analysis(m, a, context).output);
    const AnalysisOutput& out = outputs.back();
    if (!tell_outcome(out, say)) failed = true;
    keep(out);
  }
  if (outputs.empty()) writer->add_report(report::render_html(info, outputs));
  writer->commit();
  if (say)
    std::printf("\nResults: %s\nReport: %s\n", fs::absolute(outdir).string().c_str(),
                fs::absolute(outdir / "report.html").string().c_str());
  return failed ? 1 : 0;
}

int command_check(const std::string& model_path, const std::vector<std::string>& overrides) {
  model::ModelDocument document;
  const model::Model m = load_model(model_path, overrides, document);
  std::size_t elements = 0;
  for (const auto& s : m.shafts)
    for (const auto& e : s.elements) elements += static_cast<std::size_t>(e.divisions);
  // Meshes are read and checked too (inverted elements, missing sets, bad cards).
  const assembly::SolidComponents solids = assembly::build_solids(m);
  analyses::check_inputs(m, solids);
  std::printf(
      "%s: ok — %zu shafts (%zu beam elements), %zu disks, %zu bearings, %zu gear meshes, "
      "%zu solids, %zu gear pairs, %zu analyses\n",
      model_path.c_str(), m.shafts.size(), elements, m.disks.size(), m.bearings.size(),
      m.gear_meshes.size(), m.solids.size(), m.gear_pairs.size(), m.analyses.size());
  for (const auto& [solid_name, solid] : solids) {
    std::printf("  solid %s: %s\n", solid_name.c_str(), solid.description.c_str());
    for (const auto& w : solid.warnings) std::printf("    warning: %s\n", w.c_str());
  }
  return 0;
}

int command_schema() {
  std::fputs(analyses::schema_markdown().c_str(), stdout);
  return 0;
}

}  // namespace geardyn::app
