#pragma once
// Internal to the gear-pair analyses (gear_pair, mesh_force, mesh_harmonics, correlation): the
// pieces more than one of their drivers uses. Not part of the analyses' interface.
#include <string>
#include <vector>

#include "geardyn/core/table.hpp"

namespace geardyn::analyses {

/// Speed [rpm] of `omega` [rad/s].
double to_rpm(double omega);

/// A speed [rpm] for messages, "<value> rpm".
std::string rpm_text(double rpm);

/// `v` times `factor`, element by element.
std::vector<double> scaled(const std::vector<double>& v, double factor);

/// A plot trace of y over x.
Trace line(std::string name, std::vector<double> x, std::vector<double> y,
           Trace::Mode mode = Trace::Mode::Lines, std::string dash = {});

}  // namespace geardyn::analyses
