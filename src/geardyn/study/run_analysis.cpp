#include "geardyn/study/run_analysis.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <chrono>
#include <optional>
#include <stdexcept>
#include <string_view>

#include "geardyn/analysis/campbell.hpp"
#include "geardyn/analysis/harmonic.hpp"
#include "geardyn/analysis/modal.hpp"
#include "geardyn/analysis/system_builder.hpp"
#include "geardyn/analysis/unbalance.hpp"
#include "geardyn/component/solid_analyses.hpp"
#include "geardyn/core/error.hpp"
#include "geardyn/forcedan/damper_analysis.hpp"
#include "geardyn/forcedan/forced_analyses.hpp"
#include "geardyn/gearan/gear_analyses.hpp"
#include "geardyn/model/parse.hpp"
#include "geardyn/study/sweep.hpp"
#include "geardyn/transient/transient_analysis.hpp"

namespace geardyn::study {

std::string analysis_type_name(model::AnalysisType type) {
  switch (type) {
    case model::AnalysisType::Modal:
      return "modal";
    case model::AnalysisType::Campbell:
      return "campbell";
    case model::AnalysisType::Harmonic:
      return "harmonic";
    case model::AnalysisType::Unbalance:
      return "unbalance";
    case model::AnalysisType::Transient:
      return "transient";
    case model::AnalysisType::Sweep:
      return "sweep";
    case model::AnalysisType::SolidModal:
      return "solid_modal";
    case model::AnalysisType::CyclicModal:
      return "cyclic_modal";
    case model::AnalysisType::Reduction:
      return "reduction";
    case model::AnalysisType::GearPair:
      return "gear_pair";
    case model::AnalysisType::MeshForce:
      return "mesh_force";
    case model::AnalysisType::MeshHarmonics:
      return "mesh_harmonics";
    case model::AnalysisType::Correlation:
      return "correlation";
    case model::AnalysisType::CyclicForcedResponse:
      return "cyclic_forced_response";
    case model::AnalysisType::GearForcedResponse:
      return "gear_forced_response";
    case model::AnalysisType::DamperRingResponse:
      return "damper_ring_response";
  }
  return "unknown";
}

AnalysisOutput run_analysis(const model::Model& model, const fe::LinearSystem& system,
                            const model::Analysis& analysis, const RunContext& context) {
  if (!analysis.overrides.empty()) {
    // A variant of the model for this analysis only: rebuild it from the document with the
    // analysis's `set` entries applied (checked by the parser before any computation).
    if (context.document == nullptr)
      throw std::logic_error("run_analysis: an analysis with `set` needs the model document");
    model::ModelDocument variant = *context.document;
    for (const auto& o : analysis.overrides) model::apply_override(variant, o);
    const model::Model variant_model = model::build_model(variant);
    model::Analysis plain = analysis;
    plain.overrides.clear();
    RunContext variant_context = context;
    variant_context.document = &variant;
    // Solids built before the run come from the base model: a variant that changes a solid or
    // a material builds its own.
    for (const auto& o : analysis.overrides) {
      const std::size_t b = o.find_first_not_of(" \t");
      const std::string_view key =
          b == std::string::npos ? std::string_view() : std::string_view(o).substr(b);
      if (key.starts_with("solids") || key.starts_with("materials"))
        variant_context.solids = nullptr;
    }
    try {
      const fe::LinearSystem variant_system = analysis::build_system(variant_model);
      AnalysisOutput out = run_analysis(variant_model, variant_system, plain, variant_context);
      out.notes.push_back(
          fmt::format("Model variant for this analysis: {}.", fmt::join(analysis.overrides, ", ")));
      return out;
    } catch (const NumericalError& e) {
      AnalysisOutput out;
      out.name = analysis.name;
      out.type = analysis_type_name(analysis.type);
      out.status = Status::Failed;
      out.message = e.what();
      return out;
    }
  }
  Progress& progress = context.progress != nullptr ? *context.progress : null_progress();
  const auto start = std::chrono::steady_clock::now();
  AnalysisOutput out;
  // The solid component an analysis works on: built before the run, or here.
  std::optional<component::SolidComponent> built;
  auto solid_for = [&](const std::string& solid_name) -> const component::SolidComponent& {
    if (context.solids != nullptr) {
      auto it = context.solids->find(solid_name);
      if (it != context.solids->end()) return it->second;
    }
    const model::Solid* s = model.find_solid(solid_name);
    if (s == nullptr) throw std::logic_error("unresolved solid " + solid_name);
    built = component::build_solid(model, *s, progress);
    return *built;
  };
  try {
    switch (analysis.type) {
      case model::AnalysisType::Modal: {
        const auto& s = std::get<model::ModalSettings>(analysis.settings);
        out = analysis::modal_output(model, system, analysis::run_modal(system, s, progress),
                                     analysis.name);
        break;
      }
      case model::AnalysisType::Campbell: {
        const auto& s = std::get<model::CampbellSettings>(analysis.settings);
        out = analysis::campbell_output(
            model, system, analysis::run_campbell(model, system, s, progress), analysis.name);
        break;
      }
      case model::AnalysisType::Harmonic: {
        const auto& s = std::get<model::HarmonicSettings>(analysis.settings);
        out = analysis::harmonic_output(
            model, system, analysis::run_harmonic(model, system, s, progress), analysis.name);
        break;
      }
      case model::AnalysisType::Unbalance: {
        const auto& s = std::get<model::UnbalanceSettings>(analysis.settings);
        out = analysis::unbalance_output(
            model, system, analysis::run_unbalance(model, system, s, progress), analysis.name);
        break;
      }
      case model::AnalysisType::Transient: {
        const auto& s = std::get<model::TransientSettings>(analysis.settings);
        out = transient::transient_output(
            model, system, transient::run_transient(model, system, s, progress), analysis.name);
        break;
      }
      case model::AnalysisType::Sweep: {
        const auto& s = std::get<model::SweepSettings>(analysis.settings);
        if (context.document == nullptr)
          throw NumericalError(analysis.name, "a sweep needs the model document to rebuild points");
        out = sweep_output(run_sweep(*context.document, s, progress), s, analysis.name);
        break;
      }
      case model::AnalysisType::SolidModal: {
        const auto& s = std::get<model::SolidModalSettings>(analysis.settings);
        out = component::run_solid_modal(solid_for(s.solid), s, analysis.name, progress);
        break;
      }
      case model::AnalysisType::CyclicModal: {
        const auto& s = std::get<model::CyclicModalSettings>(analysis.settings);
        out = component::run_cyclic_modal(solid_for(s.solid), s, analysis.name, progress);
        break;
      }
      case model::AnalysisType::Reduction: {
        const auto& s = std::get<model::ReductionSettings>(analysis.settings);
        out = component::run_reduction(solid_for(s.solid), s, analysis.name, progress);
        break;
      }
      case model::AnalysisType::GearPair:
        out = gearan::run_gear_pair(model, std::get<model::GearPairSettings>(analysis.settings),
                                    analysis.name, progress);
        break;
      case model::AnalysisType::MeshForce:
        out = gearan::run_mesh_force(model, std::get<model::MeshForceSettings>(analysis.settings),
                                     analysis.name, progress);
        break;
      case model::AnalysisType::MeshHarmonics:
        out = gearan::run_mesh_harmonics(model,
                                         std::get<model::MeshHarmonicsSettings>(analysis.settings),
                                         analysis.name, progress);
        break;
      case model::AnalysisType::Correlation:
        out =
            gearan::run_correlation(model, std::get<model::CorrelationSettings>(analysis.settings),
                                    analysis.name, progress);
        break;
      case model::AnalysisType::CyclicForcedResponse: {
        const auto& s = std::get<model::CyclicForcedResponseSettings>(analysis.settings);
        out = forcedan::run_cyclic_forced_response(model, solid_for(s.solid), s, analysis.name,
                                                   progress);
        break;
      }
      case model::AnalysisType::DamperRingResponse: {
        const auto& s = std::get<model::DamperRingResponseSettings>(analysis.settings);
        out = forcedan::run_damper_ring_response(model, solid_for(s.solid), s, analysis.name,
                                                 progress);
        break;
      }
      case model::AnalysisType::GearForcedResponse:
        out = forcedan::run_gear_forced_response(
            model, system, std::get<model::GearForcedResponseSettings>(analysis.settings),
            analysis.name, progress);
        break;
    }
  } catch (const NumericalError& e) {
    out = AnalysisOutput{};
    out.status = Status::Failed;
    out.message = e.what();
  }
  out.name = analysis.name;
  out.type = analysis_type_name(analysis.type);
  out.run_time_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return out;
}

}  // namespace geardyn::study
