#include "geardyn/analyses/run_analysis.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <chrono>
#include <string_view>

#include "geardyn/analyses/cyclic_forced_response.hpp"
#include "geardyn/analyses/model_file.hpp"
#include "geardyn/analyses/pair_model.hpp"
#include "geardyn/assembly/solid_component.hpp"
#include "geardyn/assembly/system_builder.hpp"
#include "geardyn/core/error.hpp"
#include "geardyn/fe/dof_map.hpp"
#include "geardyn/fe/gear_mesh_element.hpp"
#include "geardyn/model/parse.hpp"

namespace geardyn::analyses {
namespace {

/// True when a `set` entry changes a solid or a material: the solids built for the base model
/// do not apply to the variant.
bool changes_solids(const std::vector<std::string>& overrides) {
  for (const auto& o : overrides) {
    const std::size_t b = o.find_first_not_of(" \t");
    const std::string_view key =
        b == std::string::npos ? std::string_view() : std::string_view(o).substr(b);
    if (key.starts_with("solids") || key.starts_with("materials")) return true;
  }
  return false;
}

/// The outcome of an analysis that failed with `message`.
Outcome failed(std::string message) {
  Outcome out;
  out.output.status = Status::Failed;
  out.output.message = std::move(message);
  return out;
}

/// The analysis on its variant of the model (its `set` entries applied to the document).
Outcome run_variant(const model::Model& model, const model::Analysis& analysis,
                    const Context& context) {
  if (context.document() == nullptr)
    throw std::logic_error("run_analysis: an analysis with `set` needs the model document");
  model::ModelDocument variant = *context.document();
  for (const auto& o : analysis.overrides) model::apply_override(variant, o);
  const model::Model variant_model = model::build_model(variant);
  const model::Analysis* plain = variant_model.find_analysis(analysis.name);
  if (plain == nullptr) throw std::logic_error("run_analysis: variant lost its analysis");
  model::Analysis without_set = *plain;
  without_set.overrides.clear();
  try {
    const bool needs_rotor = declaration_of(type_of(analysis)).needs_rotor;
    fe::LinearSystem variant_system;
    std::vector<assembly::CoupledSolid> coupled;
    if (needs_rotor) variant_system = assembly::build_system(variant_model, nullptr, coupled);
    Context variant_context(model, analysis);
    variant_context.with_progress(&context.progress())
        .with_document(&variant)
        .with_solids(changes_solids(analysis.overrides) ? nullptr : context.solids());
    if (needs_rotor) variant_context.with_system(&variant_system).with_coupled_solids(&coupled);
    Outcome out = run_analysis(variant_model, without_set, variant_context);
    out.output.notes.push_back(
        fmt::format("Model variant for this analysis: {}.", fmt::join(analysis.overrides, ", ")));
    return out;
  } catch (const NumericalError& e) {  // building the variant's system
    Outcome out = failed(e.what());
    out.output.name = analysis.name;
    out.output.type = analysis.type;
    return out;
  }
}

}  // namespace

Outcome run_analysis(const model::Model& model, const model::Analysis& analysis,
                     const Context& context) {
  if (!analysis.overrides.empty()) return run_variant(model, analysis, context);
  const auto start = std::chrono::steady_clock::now();
  Outcome out;
  try {
    out = type_of(analysis).run(model, analysis, context);
  } catch (const NumericalError& e) {
    out = failed(e.what());
  } catch (const InputError&) {
    throw;  // bad input: the whole run stops with exit 2 before writing results
  } catch (const std::exception& e) {
    // An error no check anticipated must not take the finished analyses down with it.
    out =
        failed(fmt::format("{} (an error geardyn's checks did not anticipate; the other "
                           "analyses ran; please report it with the model file)",
                           e.what()));
  }
  out.output.name = analysis.name;
  out.output.type = analysis.type;
  out.output.run_time_s =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return out;
}

namespace {

// The gear meshes' geometry (base radii against the nodes' centre distance, speed ratios and
// tooth counts): bad input that run finds when it assembles the rotor system, found by check
// too. Unknown or repeated gear nodes are left to the assembly's own messages.
void check_gear_meshes(const model::Model& model) {
  if (model.gear_meshes.empty()) return;
  const fe::DofMap dofs = fe::DofMap::build(model);
  for (std::size_t i = 0; i < model.gear_meshes.size(); ++i) {
    const model::GearMesh& mesh = model.gear_meshes[i];
    const int n1 = dofs.find_node(mesh.gear1), n2 = dofs.find_node(mesh.gear2);
    if (n1 < 0 || n2 < 0 || n1 == n2) continue;
    fe::gear_mesh_geometry(mesh, dofs.node(n1), dofs.node(n2), fmt::format("gear_meshes[{}]", i));
  }
}

}  // namespace

void check_inputs(const model::Model& model, const assembly::SolidComponents& solids) {
  // The model's components first (the solids' joints, every gear mesh and pair), then each
  // analysis's own checks (node sets, tooth-load windows, measured files).
  assembly::check_solid_sets(model, solids);
  check_gear_meshes(model);
  check_gear_pairs(model);
  for (const auto& a : model.analyses) {
    const AnalysisType& type = type_of(a);
    if (!type.check_inputs) continue;
    Context context(model, a);
    context.with_solids(&solids);
    type.check_inputs(model, a, context);
  }
}

}  // namespace geardyn::analyses
