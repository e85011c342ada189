#pragma once
// What an analysis gets besides the model and its settings: who it is (name, key path, source
// location: the one way its InputErrors are located), progress, the model document (a sweep or
// a `set` variant rebuilds the model from it), and what was built before it ran (the rotor's
// linear system, the solid components).
#include <map>
#include <memory>
#include <mutex>
#include <string>
#include <string_view>
#include <vector>

#include "geardyn/assembly/solid_component.hpp"
#include "geardyn/core/error.hpp"
#include "geardyn/core/progress.hpp"
#include "geardyn/fe/linear_system.hpp"
#include "geardyn/model/model.hpp"

namespace geardyn::model {
class ModelDocument;
}
namespace geardyn::assembly {
struct CoupledSolid;
}

namespace geardyn::analyses {

class Context {
 public:
  /// The context of analysis `analysis` of `model` (its index there gives the key path).
  Context(const model::Model& model, const model::Analysis& analysis);
  /// A context for settings built in code (no analysis table): key path "analysis".
  explicit Context(std::string name, std::string key_path = "analysis", SourceLocation where = {});

  const std::string& name() const { return name_; }
  /// "analyses[3]" (as the parser names it).
  const std::string& key_path() const { return key_path_; }
  /// "analyses[3].<key>".
  std::string key(std::string_view key) const;
  const SourceLocation& where() const { return where_; }
  /// An InputError at key `key` of this analysis.
  InputError error(std::string_view key, std::string expected, std::string found,
                   std::string hint = {}) const;

  Progress& progress() const { return progress_ != nullptr ? *progress_ : null_progress(); }
  const model::ModelDocument* document() const { return document_; }
  /// The rotor's linear system (std::logic_error if the runner built none).
  const fe::LinearSystem& system() const;
  bool has_system() const { return system_ != nullptr; }
  const assembly::SolidComponents* solids() const { return solids_; }
  /// The reduction of joined solid `solid_name` that the system was built with, or null when
  /// the runner kept none (the caller may rebuild it: assembly::couple_solid is deterministic).
  const assembly::CoupledSolid* coupled_solid(const std::string& solid_name) const;
  /// The solid component `solid_name` of `model`: built before the run, or built here once.
  const assembly::SolidComponent& solid(const model::Model& model,
                                        const std::string& solid_name) const;

  Context& with_progress(Progress* p) {
    progress_ = p;
    return *this;
  }
  Context& with_document(const model::ModelDocument* d) {
    document_ = d;
    return *this;
  }
  Context& with_system(const fe::LinearSystem* s) {
    system_ = s;
    return *this;
  }
  Context& with_solids(const assembly::SolidComponents* s) {
    solids_ = s;
    return *this;
  }
  /// The joined solids' reductions the system (with_system) was built with.
  Context& with_coupled_solids(const std::vector<assembly::CoupledSolid>* c) {
    coupled_ = c;
    return *this;
  }

 private:
  std::string name_;
  std::string key_path_;
  SourceLocation where_;
  Progress* progress_ = nullptr;
  const model::ModelDocument* document_ = nullptr;
  const fe::LinearSystem* system_ = nullptr;
  const assembly::SolidComponents* solids_ = nullptr;
  const std::vector<assembly::CoupledSolid>* coupled_ = nullptr;
  /// Solids built on demand (not prebuilt): shared by copies of this context.
  struct Built {
    std::mutex mutex;
    std::map<std::string, std::unique_ptr<assembly::SolidComponent>> solids;
  };
  std::shared_ptr<Built> built_ = std::make_shared<Built>();
};

/// The sensors an analysis reports: all of the model's when `names` is empty, else those named
/// (in that order). An unknown name is an InputError at the analysis's `sensors` key.
std::vector<const model::Sensor*> select_sensors(const model::Model& model,
                                                 const std::vector<std::string>& names,
                                                 const Context& context);

/// The context of checks made before anything runs (check_inputs): the same locating helpers,
/// and the solids built so far.
using InputContext = Context;

}  // namespace geardyn::analyses
