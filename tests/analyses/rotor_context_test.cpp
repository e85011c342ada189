// The rotor analyses locate their input errors through the Context: the key path is the
// analysis's own ("analyses[0].<key>", as the parser names it) and the source location is the
// analysis's, whether the settings object lives in the model or was built in code.
#include <gtest/gtest.h>

#include <memory>
#include <string>

#include "geardyn/analyses/campbell.hpp"
#include "geardyn/analyses/harmonic.hpp"
#include "geardyn/analyses/modal.hpp"
#include "geardyn/analyses/transient.hpp"
#include "geardyn/analyses/unbalance.hpp"
#include "geardyn/core/error.hpp"
#include "geardyn/fe/linear_system.hpp"
#include "harmonic_test_support.hpp"

namespace geardyn::analyses {
namespace {

using namespace geardyn::harmonic_test;

// The Jeffcott model with one analysis (settings `settings`) at line 7 of "rotor.toml".
template <class S>
model::Model with_analysis(const std::string& type, const S& settings) {
  model::Model m = jeffcott(10.0, 1e6, 1e6, 100.0, 1e-4);
  m.source_file = "rotor.toml";
  model::Analysis a;
  a.name = "a";
  a.type = type;
  a.settings = std::unique_ptr<model::AnalysisSettings>(std::make_unique<S>(settings));
  a.where = SourceLocation{"rotor.toml", 7, 1};
  m.analyses.push_back(std::move(a));
  return m;
}

// Runs `run(model, context)` and checks the InputError's key path and line.
template <class Run>
void expect_located(const model::Model& m, const std::string& key, const Run& run) {
  const fe::LinearSystem system = fe::assemble(m);
  const Context context = Context(m, m.analyses[0]).with_system(&system);
  try {
    run(context);
    ADD_FAILURE() << "no InputError for " << key;
  } catch (const InputError& e) {
    EXPECT_EQ(e.key_path(), "analyses[0]." + key) << e.what();
    EXPECT_EQ(e.where().line, 7) << e.what();
  }
}

TEST(RotorContext, ModalCampbellErrorsAtTheAnalysisKeys) {
  ModalSettings modal;
  modal.n_modes = 0;
  const model::Model mm = with_analysis("modal", modal);
  expect_located(mm, "n_modes", [&](const Context& c) { run_modal(mm, modal, c); });

  CampbellSettings campbell;
  campbell.speeds = {100.0, 50.0};
  const model::Model mc = with_analysis("campbell", campbell);
  expect_located(mc, "speed_rpm[1]", [&](const Context& c) { run_campbell(mc, campbell, c); });
  campbell.speeds = {100.0};
  campbell.mac_threshold = 2.0;
  expect_located(mc, "mac_threshold", [&](const Context& c) { run_campbell(mc, campbell, c); });
}

TEST(RotorContext, HarmonicUnbalanceTransientErrorsAtTheAnalysisKeys) {
  HarmonicSettings harmonic = grid(0.0, 100.0, 10, false);
  harmonic.input_node = "disk";
  harmonic.sensors = {"nope"};
  const model::Model mh = with_analysis("harmonic", harmonic);
  expect_located(mh, "sensors", [&](const Context& c) { run_harmonic(mh, harmonic, c); });
  harmonic.sensors.clear();
  harmonic.f_max = -1.0;
  expect_located(mh, "frequency_stop_hz", [&](const Context& c) { run_harmonic(mh, harmonic, c); });

  UnbalanceSettings unbalance;
  unbalance.speeds = {100.0};
  unbalance.unbalances = {"nope"};
  const model::Model mu = with_analysis("unbalance", unbalance);
  expect_located(mu, "unbalances", [&](const Context& c) { run_unbalance(mu, unbalance, c); });
  unbalance.unbalances.clear();
  unbalance.sensors = {"nope"};
  expect_located(mu, "sensors", [&](const Context& c) { run_unbalance(mu, unbalance, c); });

  TransientSettings transient;
  transient.duration = 0.1;
  transient.time_step = 1e-3;
  transient.rho_infinity = 1.5;
  const model::Model mt = with_analysis("transient", transient);
  expect_located(mt, "rho_infinity", [&](const Context& c) { run_transient(mt, transient, c); });
}

}  // namespace
}  // namespace geardyn::analyses
