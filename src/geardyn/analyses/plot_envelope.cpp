#include "geardyn/analyses/plot_envelope.hpp"

#include <algorithm>

namespace geardyn::analyses {

void envelope(const std::vector<double>& x, const Eigen::Ref<const Eigen::VectorXd>& y,
              std::vector<double>& xo, std::vector<double>& yo, std::size_t max_points) {
  const std::size_t n = x.size();
  xo.clear();
  yo.clear();
  if (n <= max_points) {
    xo = x;
    yo.assign(y.data(), y.data() + n);
    return;
  }
  const std::size_t buckets = max_points / 2;
  for (std::size_t b = 0; b < buckets; ++b) {
    const std::size_t lo = b * n / buckets, hi = (b + 1) * n / buckets;
    std::size_t imin = lo, imax = lo;
    for (std::size_t i = lo; i < hi; ++i) {
      if (y[static_cast<Eigen::Index>(i)] < y[static_cast<Eigen::Index>(imin)]) imin = i;
      if (y[static_cast<Eigen::Index>(i)] > y[static_cast<Eigen::Index>(imax)]) imax = i;
    }
    for (std::size_t i : {std::min(imin, imax), std::max(imin, imax)}) {
      xo.push_back(x[i]);
      yo.push_back(y[static_cast<Eigen::Index>(i)]);
    }
  }
}

}  // namespace geardyn::analyses
