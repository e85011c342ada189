#pragma once
// The analytic compliance route of the loaded tooth contact analysis (docs/theory.md §15.3):
// each slice of a tooth pair has the pair's body compliance c(s) per unit face width at its
// path position (tooth_compliance.hpp: bending, shear, compression, fillet foundation of both
// teeth) and the slices of one tooth are coupled by a Pasternak (shear) layer,
//     k_w(y) d - k_c d'' = q,   k_w = 1 / c(s(y)),   k_c = lambda^2 mean(k_w),
// so that the deflection under a point load decays as exp(-|y - y0| / lambda) along the face
// (lambda = 0: independent Winkler slices). The layer spans the whole face width of the tooth,
// also where its contact line has left the path of contact (those slices carry no load but
// support their neighbours; their c is that of the nearest end of the path). Discretised on the
// slices by finite differences with free face ends.
// The flanks add the nonlinear Hertzian approach of tooth_compliance.hpp per slice.
// c(s) is tabulated at 1025 points of the path and interpolated linearly (it is smooth: the
// interpolation error is below 1e-6 relative, far inside the model's own accuracy), so a mesh
// cycle costs no quadrature.
#include <vector>

#include "geardyn/gear/tooth_compliance.hpp"
#include "geardyn/gear/tooth_contact.hpp"

namespace geardyn::gear {

/// The flanks' analytic Hertzian terms of `teeth` (Weber-Banaschek approach, Johnson's peak
/// pressure) under a body compliance that the derived class supplies: the slice route here and
/// the FE route (fe_compliance.hpp) share them. `teeth` must outlive the object.
class HertzianContactCompliance : public ContactCompliance {
 public:
  explicit HertzianContactCompliance(const ToothCompliance& teeth) : teeth_(&teeth) {}
  double hertz_approach(double s, double w) const final;
  double hertz_compliance(double s, double w) const final;
  double max_pressure(double s, double w) const final;

 protected:
  const ToothCompliance* teeth_;
};

class SliceCompliance final : public HertzianContactCompliance {
 public:
  /// `teeth` must outlive this object. coupling_length_m >= 0.
  SliceCompliance(const ToothCompliance& teeth, double coupling_length_m);

  Eigen::MatrixXd body_influence(const std::vector<double>& s, const std::vector<double>& y,
                                 double dy) const override;

 private:
  double body(double s) const;  // tabulated c(s), s clamped to the path

  double coupling_length_;
  double path_ = 0.0;
  std::vector<double> table_;
};

}  // namespace geardyn::gear
