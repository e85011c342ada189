#pragma once
// A squeeze-film damper (SFD) as a nonlinear element of harmonic balance and time integration
// (docs/theory.md §8; issue #18, `nonlinear_elements`): the short-bearing (Ocvirk) film of an
// open-ended, non-rotating journal (the damper's journal is kept from spinning by an
// anti-rotation pin or a squirrel cage), with the cavitated pi film or the full 2 pi film.
//
// Coordinates (n = 2): u = (x, y) [m], the journal centre's displacement from the housing centre
// in the damper plane; their rates v = (x', y') [m/s]. The element's force f is MINUS the film's
// force on the journal (see "Sign" below).
//
// Film: at the angle theta from the x axis, n = (cos theta, sin theta), the film thickness and
// its rate are h = c - u . n and dh/dt = -v . n (radial clearance c). The short-bearing Reynolds
// equation d/dz (h^3 / (12 mu) dp/dz) = dh/dt with p = 0 at the open ends z = +-L/2 gives
//   p(theta, z) = (6 mu / h^3) (dh/dt) (z^2 - L^2 / 4),   integral over z: P = -mu L^3 (dh/dt) /
//   h^3,
// and the film force on the journal -R integral P n dtheta, i.e.
//   F_film = -mu R L^3 integral_Theta n (n . v) / h^3 dtheta,
// over Theta = the whole circle (2 pi film, negative pressures sustained) or, pi film
// (half-Sommerfeld / Guembel cavitation: p < 0 set to 0), the half circle where the film is
// squeezed, v . n > 0, centred on the direction of v (it depends on v only, not on u).
//
// Sign: this class returns f = -F_film = mu R L^3 A(u) v (with the boundary of Theta fixed by
// v), A = integral_Theta n n^T / h^3 dtheta, the force the journal exerts on the film, which the
// structure's equation M q'' + C q' + K q + B^T f = f_ext wants (a damper: f . v >= 0).
//
// Closed forms. In the frame of the eccentricity (e = |u|, angle phi, r = u / e, psi = theta -
// phi, epsilon = e / c < 1) the integrals are integral sin^i psi cos^j psi / (1 - epsilon cos
// psi)^m dpsi over an arc, m = 3 for the force and m = 4 for its u-derivative; Sommerfeld's
// substitution 1 - epsilon cos psi = (1 - epsilon^2) / (1 + epsilon cos gamma) turns each into
// (1 - epsilon^2)^(i/2 - m + 1/2) integral sin^i gamma (cos gamma + epsilon)^j
// (1 + epsilon cos gamma)^(m - i - j - 1) dgamma, a trigonometric polynomial for i + j = m - 1,
// integrated exactly (no quadrature; regular at epsilon = 0). These are the standard short-bearing
// integrals (Booker's I_m^{i,j}) in closed form. A circular centred orbit (CCO) of radius e and
// whirl rate w (pi film) gives the classical
//   F_r = -2 mu R L^3 epsilon^2 w / (c^2 (1 - epsilon^2)^2),
//   F_t = -pi mu R L^3 epsilon w / (2 c^2 (1 - epsilon^2)^(3/2))
// (film forces on the journal, radial along r and tangential along the whirl), and the 2 pi film
// F_r = 0 and twice that F_t; the centred journal's small-motion damping is
// C = pi mu R L^3 / c^3 (2 pi film) and half of it for the pi film.
//
// Tangents (exact): df/dv = mu R L^3 A(u) (the arc's end points, moving with the direction of v,
// add nothing: the integrand n . v vanishes there) and
// df/du_k = 3 mu R L^3 integral_Theta n (n . v) n_k / h^4 dtheta. At v = 0 the pi film's force
// is 0 and not differentiable in v (f is positively homogeneous of degree one in v); its df/dv
// is then taken as mu R L^3 A_2pi(u) / 2, the mean of the one-sided tangents along v and -v
// (Theta(v) and Theta(-v) make up the circle), and df/du = 0.
//
// A journal at or beyond the clearance (epsilon >= 1: it touches the housing, the film force is
// infinite) is not a wrong input but a state the motion reached: pointwise throws NumericalError
// naming the eccentricity ratio, as for a non-finite u or v. The short-bearing theory holds for
// L / (2 R) <~ 0.5 and neglects fluid inertia (squeeze Reynolds number << 1).
//
// References: San Andres, "Squeeze film dampers: operation, models and technical issues",
// Modern Lubrication Theory, Notes 13, Texas A&M University (2010); Vance, "Rotordynamics of
// Turbomachinery", Wiley (1988) (the CCO forces); Booker, "A table of the journal-bearing
// integral", J. Basic Eng. 87 (1965) 533-535 (the integrals and Sommerfeld's substitution).
#include <string>

#include "geardyn/hbm/nonlinear_element.hpp"

namespace geardyn::hbm {

/// Cavitation model of a squeeze-film damper.
enum class SqueezeFilm {
  pi,     ///< cavitated (half-Sommerfeld): only the squeezed half of the film carries pressure
  two_pi  ///< full film: negative pressures sustained (a sealed, pressurised damper)
};

/// Geometry and lubricant of a squeeze-film damper.
struct SqueezeFilmParameters {
  double radius = 0.0;     ///< journal radius R [m] > 0
  double length = 0.0;     ///< land length L [m] > 0
  double clearance = 0.0;  ///< radial clearance c [m] > 0
  double viscosity = 0.0;  ///< dynamic viscosity mu [Pa s] > 0
  SqueezeFilm film = SqueezeFilm::pi;
};

/// The short-bearing squeeze-film damper of the header comment (u = (x, y), f = -F_film).
class SqueezeFilmDamper final : public PointwiseElement {
 public:
  /// Throws InputError (key `<name>.radius`, `.length`, `.clearance`, `.viscosity`) for a value
  /// not finite and > 0.
  SqueezeFilmDamper(std::string name, SqueezeFilmParameters parameters);

  int size() const override { return 2; }
  /// "squeeze-film damper '<name>' (pi film)" or "(2 pi film)".
  std::string describe() const override;
  /// f = mu R L^3 A(u) v and its exact tangents (header comment); theta and omega are not used
  /// (the law does not vary over the period). Throws NumericalError when |u| >= c or u, v are
  /// not finite.
  void pointwise(const Eigen::VectorXd& u, const Eigen::VectorXd& v, double theta, double omega,
                 ElementStep& out) const override;
  /// True: the film force is homogeneous of degree one in the velocity.
  bool velocity_dependent() const override { return true; }

  /// The small-motion damping of the centred journal [N s/m]: pi mu R L^3 / c^3 (2 pi film), half
  /// of it (pi film).
  double centred_damping() const;
  /// The parameters as given.
  const SqueezeFilmParameters& parameters() const { return parameters_; }

 private:
  std::string name_;
  SqueezeFilmParameters parameters_;
};

}  // namespace geardyn::hbm
