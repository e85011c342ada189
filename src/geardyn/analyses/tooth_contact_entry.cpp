// The `type = "tooth_contact"` analysis in the registry: its model-file keys and their rules,
// its checks, how it runs and what it offers to sweeps.
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "geardyn/analyses/common_checks.hpp"
#include "geardyn/analyses/common_keys.hpp"
#include "geardyn/analyses/registry.hpp"
#include "geardyn/analyses/tooth_contact.hpp"
#include "geardyn/analyses/tooth_contact_correlation.hpp"
#include "geardyn/model/schema_builder.hpp"

namespace geardyn::analyses {
namespace {

using namespace model::keys;  // NOLINT: the declaration table reads as a table
using model::Analysis;

constexpr model::Unit kTorque{"N m", 1.0};

void check(const Analysis& a, const std::string& path, const model::ModelCheck& check) {
  GearPairUse use;
  use.pair = &a.settings_of<ToothContactSettings>().pair;
  check_gear_pair_use(a, path, check, use);
}

void check_inputs(const model::Model& m, const Analysis& a, const InputContext& c) {
  const auto& s = a.settings_of<ToothContactSettings>();
  const auto tc = build_tooth_contact_model(m, pair_index(m, s.pair));
  if (2 * s.orders >= tc->options.positions)
    throw c.error("orders",
                  fmt::format("mesh orders below half the {} positions per mesh cycle of "
                              "[gear_pairs.contact] (Nyquist)",
                              tc->options.positions),
                  std::to_string(s.orders), "raise gear_pairs.contact.positions or lower orders");
  check_measured_te(m, s,
                    s.torques.empty() ? std::vector<double>{tc->pair.pair->torque} : s.torques, c);
}

const ToothContactRunResult& result(const Outcome& o) {
  return result_of<ToothContactRunResult>(o);
}

const gear::ToothContactResult& torque_of(const ToothContactRunResult& r, const ScalarRequest& q) {
  if (q.mode < 1 || static_cast<std::size_t>(q.mode) > r.torques.size())
    throw std::runtime_error(
        fmt::format("{}: mode = {} asks for torque {}, but the analysis has {}", q.quantity, q.mode,
                    q.mode, r.torques.size()));
  return r.torques[static_cast<std::size_t>(q.mode - 1)];
}

double scalar(const Outcome& o, const ScalarRequest& q, std::string& unit) {
  const ToothContactRunResult& r = result(o);
  if (q.quantity == "te_correlation_mean_ratio" || q.quantity == "te_correlation_max_difference") {
    if (!r.te_correlation)
      throw std::runtime_error(q.quantity + ": the analysis has no measured_te_file");
    const bool ratio = q.quantity == "te_correlation_mean_ratio";
    unit = ratio ? std::string() : std::string("dB");
    return ratio ? r.te_correlation->mean_ratio : r.te_correlation->max_abs_db;
  }
  if (q.quantity == "te_harmonic") {
    unit = std::string("m");
    if (q.mode < 1 || static_cast<std::size_t>(q.mode) > r.harmonics_m.front().size())
      throw std::runtime_error(fmt::format("te_harmonic: mode = {} is not among the {} orders",
                                           q.mode, r.harmonics_m.front().size()));
    return r.harmonics_m.front()[static_cast<std::size_t>(q.mode - 1)];
  }
  const gear::ToothContactResult& t = torque_of(r, q);
  if (q.quantity == "te_peak_peak") {
    unit = std::string("m");
    const auto [lo, hi] = std::minmax_element(t.te_m.begin(), t.te_m.end());
    return *hi - *lo;
  }
  if (q.quantity == "face_load_factor") {
    unit.clear();
    return t.face_load_factor;
  }
  if (q.quantity == "mesh_stiffness") {
    unit = std::string("N/m");
    double sum = 0.0;
    for (double k : t.stiffness_tangent_n_per_m) sum += k;
    return sum / static_cast<double>(t.stiffness_tangent_n_per_m.size());
  }
  if (q.quantity == "pattern_centre_face" || q.quantity == "pattern_centre_profile") {
    unit.clear();
    const auto [xi, eta] = gear::pattern_centre(*r.model->contact, t);
    return q.quantity == "pattern_centre_face" ? eta : xi;
  }
  throw std::runtime_error(fmt::format("tooth_contact offers no scalar '{}'", q.quantity));
}

std::vector<model::Field> keys() {
  return {
      gear_pair_name_key().to_settings(&ToothContactSettings::pair),
      numbers("torques", kTorque, "Torques on gear 1, increasing (a TE-vs-torque map for several).")
          .gt(0)
          .increasing()
          .note("the pair's torque")
          .to_settings(&ToothContactSettings::torques),
      integer("orders", "TE harmonics at mesh orders 1..orders.")
          .def("5")
          .ge(1)
          .le(100)
          .to_settings(&ToothContactSettings::orders),
      number("distribution_torque", kTorque,
             "Torque whose load distribution over the flank is written (the nearest computed).")
          .gt(0)
          .note("the pair's torque if computed, else the largest")
          .to_settings(&ToothContactSettings::distribution_torque),
      text("measured_te_file",
           "A test rig's TE at the mesh orders over torque (CSV: torque_nm, mesh_order, "
           "amplitude_0_peak_um or another convention and unit, docs/input-files.md) compared "
           "point by point with the computed harmonics (table te_correlation) and overlaid on "
           "the TE-versus-torque plot.")
          .note("no comparison")
          .to_settings(&ToothContactSettings::measured_te_file),
  };
}

}  // namespace

AnalysisType tooth_contact_analysis() {
  AnalysisType type;
  type.name = "tooth_contact";
  type.declare = [] {
    auto d = declaration<ToothContactSettings>(
        "tooth_contact",
        "Loaded tooth contact analysis of a spur, helical, bevel or hypoid pair (slice model; "
        "bevel and hypoid pairs through their virtual cylindrical pair): transmission "
        "error and its mesh-order harmonics per torque, mesh stiffness, load sharing, load "
        "distribution over the flank, contact pressure, face-load factor K_Hbeta.");
    d.fields = keys();
    d.check = check;
    return d;
  };
  type.check_inputs = check_inputs;
  type.run = runner(run_tooth_contact, tooth_contact_output);
  type.scalars = {
      {"te_peak_peak",
       "m",
       "Peak-to-peak loaded TE along the line of action at torque `mode`.",
       {"mode"}},
      {"te_harmonic", "m", "0-peak TE amplitude at mesh order `mode`, first torque.", {"mode"}},
      {"face_load_factor", "", "Face-load factor K_Hbeta at torque `mode`.", {"mode"}},
      {"mesh_stiffness", "N/m", "Mean tangent mesh stiffness at torque `mode`.", {"mode"}},
      {"pattern_centre_face",
       "",
       "Contact pattern centre along the face at torque `mode`: load-weighted mean of 2 y / b - "
       "1 (-1: y = 0, a bevel pair's toe; +1: y = b, its heel).",
       {"mode"}},
      {"pattern_centre_profile",
       "",
       "Contact pattern centre on the pinion's profile at torque `mode`: load-weighted mean of "
       "its normalised roll angle (-1: start of active profile, +1: tip).",
       {"mode"}},
      {"te_correlation_mean_ratio",
       "",
       "Mean of measured / computed TE harmonic over the compared points of measured_te_file.",
       {}},
      {"te_correlation_max_difference",
       "dB",
       "Largest |20 log10(measured / computed)| over the compared points of measured_te_file.",
       {}},
  };
  type.scalar = scalar;
  return type;
}

}  // namespace geardyn::analyses
