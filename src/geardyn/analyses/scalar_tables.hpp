#pragma once
// Scalar outputs read back from an analysis's result tables: the natural frequency of a mode
// (tables "modes" / "undamped_modes"), a critical speed ("critical_speeds"), the peak of a
// sensor's response and its location, and the amplitude at a speed or frequency ("frf" /
// "response"). The modal, campbell, harmonic and unbalance types use it as their `scalar`.
#include <string>

#include "geardyn/analyses/registry.hpp"

namespace geardyn::analyses {

/// The scalar `spec` of `outcome`, with its unit; std::runtime_error when the tables lack it
/// (the sweep reports that point as failed).
double scalar_from_tables(const Outcome& outcome, const ScalarRequest& spec, std::string& unit);

}  // namespace geardyn::analyses
