#pragma once
// tooth_contact's comparison with a test rig: the measured TE at the mesh orders over torque
// (`measured_te_file`, docs/input-files.md §3a) against the computed TE harmonics
// (te_harmonics), point by point: ratio and dB difference per (torque, order), the computed
// amplitude interpolated linearly in torque between the analysis' torques; the table
// `te_correlation`, the measured points on the TE-versus-torque plot, and a note.
#include <optional>
#include <string>
#include <vector>

#include "geardyn/analyses/context.hpp"
#include "geardyn/analyses/tooth_contact.hpp"
#include "geardyn/core/table.hpp"
#include "geardyn/gear/te_rig_csv.hpp"
#include "geardyn/model/model.hpp"

namespace geardyn::analyses {

/// Reads `file` (relative to the model file). InputError at `measured_te_file` when it does not
/// exist, at the file's line and column for a bad cell (gear::parse_te_rig_csv).
gear::TeRigFile read_measured_te(const model::Model& model, const std::string& file,
                                 const Context& context);

/// Checks made before anything runs: the file reads, and at least one of its points lies within
/// the computed torques `torques_nm` and at an order <= `orders` (InputError at
/// `measured_te_file` otherwise; points outside are reported as not compared).
void check_measured_te(const model::Model& model, const ToothContactSettings& settings,
                       const std::vector<double>& torques_nm, const Context& context);

/// The comparison of the settings' measured_te_file with `r.harmonics_m` (nullopt without one).
std::optional<gear::TeComparison> correlate_measured_te(const model::Model& model,
                                                        const ToothContactSettings& settings,
                                                        const ToothContactRunResult& r,
                                                        const Context& context);

/// Table `te_correlation`: one row per measured point, in the file's order.
Table te_correlation_table(const gear::TeComparison& c);

/// The measured points on the TE-versus-torque plot (pinion angle [urad], 0-peak), one marker
/// trace per mesh order.
void add_measured_te_traces(Plot& te_vs_torque, const gear::TeComparison& c);

/// The note: what was compared, the mean ratio, the largest dB difference, the linear fit, and
/// how far to trust them.
std::string te_correlation_note(const std::string& analysis, const gear::TeComparison& c);

}  // namespace geardyn::analyses
