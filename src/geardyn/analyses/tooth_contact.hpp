#pragma once
// tooth_contact: loaded tooth contact analysis (LTCA) of one cylindrical gear pair by the slice
// model (docs/theory.md §15): transmission error over the mesh cycle per torque and its
// harmonics at the mesh orders, mesh stiffness (secant and tangent), load sharing between the
// tooth pairs, load distribution over the flank, peak contact pressure and the face-load factor
// K_Hbeta, from the pair's geometry, its flank modifications ([gear_pairs.flank1/2]), the slice
// model and misalignment ([gear_pairs.contact]).
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "geardyn/analyses/context.hpp"
#include "geardyn/analyses/pair_model.hpp"
#include "geardyn/analyses/tooth_contact_misalignment.hpp"
#include "geardyn/gear/slice_compliance.hpp"
#include "geardyn/gear/te_rig_csv.hpp"
#include "geardyn/gear/tooth_compliance.hpp"
#include "geardyn/gear/tooth_contact.hpp"
#include "geardyn/model/model.hpp"

namespace geardyn::analyses {

struct ToothContactSettings : model::SettingsOf<ToothContactSettings> {
  std::string pair;             ///< empty: the model's only pair
  std::vector<double> torques;  ///< pinion torques [N m] (empty: the pair's torque)
  int orders = 5;               ///< TE harmonics at mesh orders 1..orders
  /// Torque of the load-distribution table [N m] (NaN: the pair's torque if among `torques`,
  /// else the largest).
  double distribution_torque = std::numeric_limits<double>::quiet_NaN();
  /// A rig's TE at the mesh orders over torque (docs/input-files.md §3a), as written (relative
  /// to the model file); empty: no comparison.
  std::string measured_te_file;
};

/// The LTCA problem of a model's pair: the gear library's inputs built from the model keys.
/// Default slice coupling length per normal module (bevel: mean normal module of the virtual
/// pair): the decay length of the FE route's face influence line for standard-rack steel teeth,
/// 2.51 m_n (docs/theory.md §15.8, tests/gear/fe_compliance_slow_test.cpp).
inline constexpr double kCouplingLengthPerModule = 2.5;

struct ToothContactModel {
  PairModel pair;
  gear::FlankModification pinion, wheel;
  gear::ToothContactOptions options;
  std::unique_ptr<gear::ToothCompliance> teeth;
  std::unique_ptr<gear::ContactCompliance> compliance;  ///< SliceCompliance or FeCompliance
  std::unique_ptr<gear::ToothContact> contact;
  double misalignment_m = 0.0;  ///< f_ma used at the pair's torque (misalignment.at(T_pair))
  /// Slice coupling length of the analytic route [m]: contact.coupling_length, or without it
  /// kCouplingLengthPerModule m_n (the FE calibration, docs/theory.md §15.8).
  double coupling_length_m = 0.0;
  ContactMisalignment misalignment;  ///< given and from the rotor's deflection
};

/// Builds and checks the LTCA of pair `index`. Throws InputError at the pair's keys.
std::shared_ptr<ToothContactModel> build_tooth_contact_model(const model::Model& model,
                                                             std::size_t index);
/// The same from the pair's geometry already built (`pm`'s STE is not used).
std::shared_ptr<ToothContactModel> build_tooth_contact_model(const model::Model& model,
                                                             const PairModel& pm);

/// The STE of pair `pm` from its loaded tooth contact analysis at the pair's torque: the loaded
/// TE over the first mesh cycle with the unloaded TE as e_g (so that F_s / (e - e_g) is the
/// secant mesh stiffness), after ste_shift, resampled to ste_samples when given. InputError at
/// the pair when the contact analysis fails there.
gear::SteCurve contact_ste(const model::Model& model, const PairModel& pm);

struct ToothContactRunResult {
  std::shared_ptr<ToothContactModel> model;
  std::vector<gear::ToothContactResult> torques;  ///< in the order of the settings' torques
  std::size_t distribution_index = 0;             ///< which torque's distribution is written
  std::vector<std::vector<double>> harmonics_m;   ///< per torque: 0-peak TE at orders 1..n
  /// Per torque: 0-peak amplitude of the tangent mesh stiffness at orders 1..n [N/m].
  std::vector<std::vector<double>> stiffness_harmonics_n_per_m;
  /// The measured_te_file against harmonics_m (tooth_contact_correlation.hpp).
  std::optional<gear::TeComparison> te_correlation;
};

ToothContactRunResult run_tooth_contact(const model::Model& model,
                                        const ToothContactSettings& settings,
                                        const Context& context);

AnalysisOutput tooth_contact_output(const model::Model& model, const ToothContactSettings& settings,
                                    const ToothContactRunResult& result, const Context& context);

}  // namespace geardyn::analyses
