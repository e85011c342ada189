#pragma once
// A test oracle: scalar outputs read back from an analysis's result tables (the natural
// frequency of a mode from "modes" / "undamped_modes", a critical speed from "critical_speeds",
// the peak of a sensor's response, its location, and the amplitude at a speed or frequency from
// "frf" / "response"). Sweeps read this way before the analyses declared typed scalars; the
// tests check that the typed scalars give the same numbers bit for bit.
#include <string>

#include "geardyn/analyses/registry.hpp"

namespace geardyn::analyses {

/// The scalar `spec` of `outcome`, with its unit; std::runtime_error when the tables lack it
/// (the sweep reports that point as failed).
double scalar_from_tables(const Outcome& outcome, const ScalarRequest& spec, std::string& unit);

}  // namespace geardyn::analyses
