#pragma once
// Thinning a long record for a plot without hiding its peaks.
#include <Eigen/Dense>
#include <cstddef>
#include <vector>

namespace geardyn::analyses {

/// At most about max_points points that keep the envelope of (x, y): per bucket its minimum and
/// maximum, in x order. A record of at most max_points points is copied as it is.
void envelope(const std::vector<double>& x, const Eigen::Ref<const Eigen::VectorXd>& y,
              std::vector<double>& xo, std::vector<double>& yo, std::size_t max_points = 4000);

}  // namespace geardyn::analyses
