#pragma once
// The one list of analysis types (docs/architecture.md, "The analysis registry"). Everything that
// needs to know the analysis types reads it: dispatch (run_analysis), the model-file schema (keys,
// cross-key rules, checks; model_file.hpp), `geardyn schema` and docs/model-reference.md, the fuzz
// dictionary, and sweeps (the scalar outputs each type offers).
//
// An analysis type is written in its own files: <type>.hpp / <type>.cpp (settings, result,
// driver) and <type>_entry.cpp (its AnalysisType: keys, checks, runner, scalars), and listed by
// one line in registry.cpp. docs/architecture.md walks through adding one.
#include <functional>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "geardyn/analyses/context.hpp"
#include "geardyn/core/table.hpp"
#include "geardyn/model/schema.hpp"

namespace geardyn::analyses {

/// A scalar result an analysis type offers to a sweep (and to design studies): the `quantity`
/// of an [[analyses.outputs]] entry.
struct ScalarOutput {
  std::string name;     ///< e.g. "natural_frequency"
  std::string unit;     ///< of the value as tabulated, e.g. "Hz" ("": dimensionless)
  std::string meaning;  ///< one line for the reference
  /// Keys of [[analyses.outputs]] it reads: "mode", "sensor", "at_rpm", "at_hz".
  std::vector<std::string> parameters;
};

/// What an [[analyses.outputs]] entry asks of a result.
struct ScalarRequest {
  std::string quantity;  ///< a ScalarOutput name
  int mode = 1;          ///< 1-based (mode, critical speed, peak)
  std::string sensor;
  double at = 0.0;       ///< speed or frequency [rad/s] (amplitude_at)
  bool at_speed = true;  ///< `at` is a speed (at_rpm) rather than a frequency (at_hz)
};

/// What running an analysis gives: its output (tables, plots, notes, status) and its result,
/// which the type's `scalar` reads (null for types whose result is only their tables).
struct Outcome {
  AnalysisOutput output;
  std::shared_ptr<const void> result;
};

/// An analysis type.
struct AnalysisType {
  std::string name;  ///< `type = "..."` in the model file
  /// Its model-file declaration: help, settings, keys, cross-key rules, checks (built on first
  /// use, after the registry exists: a sweep's keys list the other types' scalars).
  std::function<model::AnalysisDeclaration()> declare;
  /// Checks that need the model's solids built (meshes, node sets) or its files read; may be
  /// empty. Throws InputError (bad input) located at the analysis's keys.
  std::function<void(const model::Model&, const model::Analysis&, const InputContext&)>
      check_inputs;
  /// Runs it. Numerical failures throw NumericalError; the runner records them.
  std::function<Outcome(const model::Model&, const model::Analysis&, const Context&)> run;
  /// The scalars it offers to a sweep, and how they are read from an Outcome (unit set to the
  /// value's unit). Empty: not a sweep target.
  std::vector<ScalarOutput> scalars;
  std::function<double(const Outcome&, const ScalarRequest&, std::string& unit)> scalar;
};

/// Every analysis type, in the order of the reference.
const std::vector<AnalysisType>& registry();

/// The type called `name`, or null.
const AnalysisType* find_analysis_type(std::string_view name);

/// The type of `analysis` (std::logic_error if the registry has none: the parser makes only
/// registered types).
const AnalysisType& type_of(const model::Analysis& analysis);

/// Makes an AnalysisType's `declare` entry: the declaration of type `name` with settings S.
template <class S>
model::AnalysisDeclaration declaration(std::string name, std::string help) {
  model::AnalysisDeclaration d;
  d.name = std::move(name);
  d.help = std::move(help);
  d.make_settings = [] { return std::make_unique<S>(); };
  return d;
}

/// Typed wrapper of a driver: `run` returns {output, result R}.
template <class R>
Outcome outcome(AnalysisOutput output, R result) {
  return {std::move(output), std::make_shared<const R>(std::move(result))};
}

/// The `run` of an AnalysisType from its driver (solving: model, settings, context -> result R)
/// and its post-processing (-> AnalysisOutput): every type's runner has this shape.
template <class S, class R>
auto runner(R (*solve)(const model::Model&, const S&, const Context&),
            AnalysisOutput (*output)(const model::Model&, const S&, const R&, const Context&)) {
  return [solve, output](const model::Model& m, const model::Analysis& a, const Context& c) {
    const S& s = a.settings_of<S>();
    R r = solve(m, s, c);
    AnalysisOutput out = output(m, s, r, c);
    return outcome(std::move(out), std::move(r));
  };
}

/// The result of an Outcome made by outcome<R> (std::logic_error if it holds none).
template <class R>
const R& result_of(const Outcome& o) {
  if (!o.result) throw std::logic_error("this analysis keeps no result for scalar outputs");
  return *static_cast<const R*>(o.result.get());
}

}  // namespace geardyn::analyses
