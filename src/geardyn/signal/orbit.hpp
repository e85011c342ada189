#pragma once
// Elliptical orbit of a node from the complex amplitudes of its two lateral displacements,
//   x(t) = Re(X e^{i w t}),  y(t) = Re(Y e^{i w t})    (x, y along e1, e2 of the node frame).
// Split z = x + i y into a forward and a backward rotating circle,
//   z(t) = A_f e^{i w t} + A_b e^{-i w t},  A_f = (X + i Y) / 2,  A_b = (conj X + i conj Y) / 2,
// then major semi-axis = |A_f| + |A_b|, minor = | |A_f| - |A_b| |, the major axis is inclined at
// (arg A_f + arg A_b) / 2 from e1, and the point turns from e1 towards e2 (positive sense about
// e3) when |A_f| > |A_b|.
// Reference: Lee, C.-W., Vibration Analysis of Rotors, Kluwer 1993, ch. 2 (directional
// (forward/backward) decomposition of whirl orbits); Friswell et al., Dynamics of Rotating
// Machines, CUP 2010, sec. 3.5.
#include <complex>
#include <string_view>

namespace geardyn::signal {

/// Sense in which the orbit is travelled, relative to the positive sense about e3 (from e1
/// towards e2). Straight: a line (or no motion), |A_f| = |A_b| within 1e-9 of the major axis.
enum class Whirl { Forward, Backward, Straight };

constexpr std::string_view to_string(Whirl w) {
  switch (w) {
    case Whirl::Forward:
      return "forward";
    case Whirl::Backward:
      return "backward";
    case Whirl::Straight:
      return "straight";
  }
  return "straight";
}

/// The sense opposite to `w` (Straight stays Straight): for a shaft spinning in the negative
/// sense about e3, geometric Forward is backward whirl relative to the spin.
constexpr Whirl reversed(Whirl w) {
  return w == Whirl::Forward ? Whirl::Backward : w == Whirl::Backward ? Whirl::Forward : w;
}

struct Orbit {
  double major = 0.0;           ///< major semi-axis, in the units of X and Y
  double minor = 0.0;           ///< minor semi-axis (>= 0)
  double inclination = 0.0;     ///< angle of the major axis from e1 towards e2 [rad], (-pi/2, pi/2]
  double forward_radius = 0.0;  ///< |A_f|
  double backward_radius = 0.0;   ///< |A_b|
  Whirl whirl = Whirl::Straight;  ///< geometric sense about e3
};

/// Orbit of the phasors X (along e1) and Y (along e2).
Orbit orbit_from_phasors(std::complex<double> X, std::complex<double> Y);

}  // namespace geardyn::signal
