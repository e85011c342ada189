// geardyn: command-line program. Sub-commands: run, check, schema.
// Exit codes: 0 success, 1 an analysis failed numerically, 2 bad input or usage.
#include <fmt/format.h>

#include <CLI/CLI.hpp>
#include <cstdio>
#include <exception>
#include <string>
#include <vector>

#include "commands.hpp"
#include "geardyn/core/error.hpp"
#include "geardyn/core/version.hpp"

int main(int argc, char** argv) {
  CLI::App app{"geardyn: vibration and noise of geared rotor-bearing systems", "geardyn"};
  app.set_version_flag("--version", std::string("geardyn ") + geardyn::kVersion);
  app.require_subcommand(1);

  geardyn::app::RunOptions run_options;
  auto* run = app.add_subcommand("run", "Run every analysis of a model and write results");
  run->add_option("model", run_options.model_path, "Model file (TOML)")->required();
  run->add_option("-o,--output", run_options.output_dir,
                  "Results folder (default: results/<model file name>, or results/<its folder> for "
                  "a model.toml)");
  run->add_option("--set", run_options.overrides,
                  "Override a model value, e.g. --set bearings[0].kxx=2e7 (repeatable)");
  run->add_flag("-q,--quiet", run_options.quiet, "No progress output on stderr");
  run->add_option("--only", run_options.only, "Run only these analyses (by name)");

  std::string check_path;
  std::vector<std::string> check_overrides;
  auto* check = app.add_subcommand("check", "Validate a model file without running it");
  check->add_option("model", check_path, "Model file (TOML)")->required();
  check->add_option("--set", check_overrides, "Override a model value (repeatable)");

  app.add_subcommand("schema", "Print the model-file reference (Markdown)");

  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    const int code = app.exit(e);
    return code == 0 ? 0 : 2;
  }

  try {
    if (run->parsed()) return geardyn::app::command_run(run_options, argc, argv);
    if (check->parsed()) return geardyn::app::command_check(check_path, check_overrides);
    return geardyn::app::command_schema();
  } catch (const geardyn::InputError& e) {
    std::fprintf(stderr, "error: %s\n", e.what());
    return 2;
  } catch (const std::exception& e) {
    // Anything else (a numerical failure outside an analysis, an I/O error writing results):
    // a message and exit 1, never an abort.
    std::fprintf(stderr, "error: %s\n", e.what());
    return 1;
  } catch (...) {
    std::fprintf(stderr, "error: an unknown exception\n");
    return 1;
  }
}
