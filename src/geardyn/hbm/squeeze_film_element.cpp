#include "geardyn/hbm/squeeze_film_element.hpp"

#include <fmt/format.h>

#include <array>
#include <cmath>
#include <utility>

#include "geardyn/core/error.hpp"
#include "geardyn/core/units.hpp"

namespace geardyn::hbm {

namespace {

// S[a][b] = integral of sin^a cos^b over [g1, g2], a + b <= 3.
using TrigIntegrals = std::array<std::array<double, 4>, 4>;

// The antiderivatives of sin^a g cos^b g, a + b <= 3, at g.
TrigIntegrals antiderivatives(double g) {
  const double s = std::sin(g), c = std::cos(g), s2 = std::sin(2.0 * g);
  TrigIntegrals P{};
  P[0][0] = g;
  P[1][0] = -c;
  P[0][1] = s;
  P[2][0] = 0.5 * g - 0.25 * s2;
  P[1][1] = 0.5 * s * s;
  P[0][2] = 0.5 * g + 0.25 * s2;
  P[3][0] = -c + c * c * c / 3.0;
  P[2][1] = s * s * s / 3.0;
  P[1][2] = -c * c * c / 3.0;
  P[0][3] = s - s * s * s / 3.0;
  return P;
}

TrigIntegrals trig_integrals(double g1, double g2) {
  const TrigIntegrals a = antiderivatives(g1), b = antiderivatives(g2);
  TrigIntegrals S{};
  for (int i = 0; i < 4; ++i)
    for (int j = 0; i + j < 4; ++j)
      S[static_cast<std::size_t>(i)][static_cast<std::size_t>(j)] =
          b[static_cast<std::size_t>(i)][static_cast<std::size_t>(j)] -
          a[static_cast<std::size_t>(i)][static_cast<std::size_t>(j)];
  return S;
}

// Sommerfeld's substitution: gamma(psi) with tan(gamma / 2) = sqrt((1 + eps) / (1 - eps))
// tan(psi / 2), continued monotonically over the real line (gamma - psi is 2 pi periodic).
double sommerfeld_angle(double psi, double eps) {
  const double k = std::round(psi / units::kTwoPi);
  const double p = psi - k * units::kTwoPi;  // in [-pi, pi]
  return 2.0 * std::atan2(std::sqrt(1.0 + eps) * std::sin(0.5 * p),
                          std::sqrt(1.0 - eps) * std::cos(0.5 * p)) +
         k * units::kTwoPi;
}

// The film integrals over the arc [psi1, psi2] in the eccentricity frame (r, t):
//   A(a, b)    = integral m_a m_b / (1 - eps cos psi)^3 dpsi,
//   T[i]       = integral m_{a} m_{b} m_{c} / (1 - eps cos psi)^4 dpsi with i of the three
//                indices on t (sin) and 3 - i on r (cos),
// m = (cos psi, sin psi), by Sommerfeld's substitution (header comment).
struct FilmIntegrals {
  Eigen::Matrix2d A;
  std::array<double, 4> T{};
};

FilmIntegrals film_integrals(double psi1, double psi2, double eps) {
  const TrigIntegrals S = trig_integrals(sommerfeld_angle(psi1, eps), sommerfeld_angle(psi2, eps));
  const double q = 1.0 - eps * eps, e2 = eps * eps;
  // (1 - eps^2)^(i/2 - m + 1/2) for m = 3 and m = 4.
  FilmIntegrals r;
  r.A(0, 0) = std::pow(q, -2.5) * (S[0][2] + 2.0 * eps * S[0][1] + e2 * S[0][0]);
  r.A(0, 1) = r.A(1, 0) = std::pow(q, -2.0) * (S[1][1] + eps * S[1][0]);
  r.A(1, 1) = std::pow(q, -1.5) * S[2][0];
  r.T[0] =
      std::pow(q, -3.5) * (S[0][3] + 3.0 * eps * S[0][2] + 3.0 * e2 * S[0][1] + e2 * eps * S[0][0]);
  r.T[1] = std::pow(q, -3.0) * (S[1][2] + 2.0 * eps * S[1][1] + e2 * S[1][0]);
  r.T[2] = std::pow(q, -2.5) * (S[2][1] + eps * S[2][0]);
  r.T[3] = std::pow(q, -2.0) * S[3][0];
  return r;
}

void check_positive(double value, const std::string& key, const char* what) {
  if (!std::isfinite(value) || value <= 0.0)
    throw InputError({}, key, fmt::format("a finite {} > 0", what), fmt::format("{}", value));
}

}  // namespace

SqueezeFilmDamper::SqueezeFilmDamper(std::string name, SqueezeFilmParameters parameters)
    : name_(std::move(name)), parameters_(parameters) {
  check_positive(parameters_.radius, name_ + ".radius", "journal radius [m]");
  check_positive(parameters_.length, name_ + ".length", "land length [m]");
  check_positive(parameters_.clearance, name_ + ".clearance", "radial clearance [m]");
  check_positive(parameters_.viscosity, name_ + ".viscosity", "viscosity [Pa s]");
}

std::string SqueezeFilmDamper::describe() const {
  return fmt::format("squeeze-film damper '{}' ({} film)", name_,
                     parameters_.film == SqueezeFilm::pi ? "pi" : "2 pi");
}

double SqueezeFilmDamper::centred_damping() const {
  const auto& p = parameters_;
  const double full =
      units::kPi * p.viscosity * p.radius * std::pow(p.length, 3) / std::pow(p.clearance, 3);
  return p.film == SqueezeFilm::two_pi ? full : 0.5 * full;
}

void SqueezeFilmDamper::pointwise(const Eigen::VectorXd& u, const Eigen::VectorXd& v,
                                  double /*theta*/, double /*omega*/, ElementStep& out) const {
  const auto& p = parameters_;
  if (!u.allFinite() || !v.allFinite())
    throw NumericalError(describe(), fmt::format("a non-finite motion: u = ({}, {}), v = ({}, {})",
                                                 u[0], u[1], v[0], v[1]));
  const double e = std::hypot(u[0], u[1]), eps = e / p.clearance;
  if (eps >= 1.0)
    throw NumericalError(describe(),
                         fmt::format("the journal touches the housing: eccentricity ratio "
                                     "e / c = {:.6g} >= 1 (the film force is infinite); the "
                                     "motion is too large for the clearance",
                                     eps));
  // The eccentricity frame: r along u (x when centred), t ahead of it.
  const double phi = e > 0.0 ? std::atan2(u[1], u[0]) : 0.0;
  Eigen::Matrix2d rot;
  rot << std::cos(phi), -std::sin(phi), std::sin(phi), std::cos(phi);
  const Eigen::Vector2d vt = rot.transpose() * Eigen::Vector2d(v[0], v[1]);
  const bool at_rest = vt.squaredNorm() == 0.0;
  const bool half = p.film == SqueezeFilm::pi && !at_rest;
  // The squeezed half circle, centred on the direction of v.
  const double centre = half ? std::atan2(vt[1], vt[0]) : 0.0;
  const double span = half ? 0.5 * units::kPi : units::kPi;
  const FilmIntegrals I = film_integrals(centre - span, centre + span, eps);
  const double scale = p.viscosity * p.radius * std::pow(p.length, 3);
  const double c3 = std::pow(p.clearance, 3), c4 = c3 * p.clearance;
  // df/dv = scale A / c^3; at rest, the pi film takes the mean of the one-sided tangents.
  const double rest_share = (p.film == SqueezeFilm::pi && at_rest) ? 0.5 : 1.0;
  const Eigen::Matrix2d damping = rest_share * scale / c3 * I.A;
  const Eigen::Vector2d force = scale / c3 * I.A * vt;
  // df/du (a, c) = 3 scale / c^4 sum_b T_abc v_b, T indexed by its number of t indices.
  Eigen::Matrix2d stiffness;
  for (int a = 0; a < 2; ++a)
    for (int c = 0; c < 2; ++c) {
      double sum = 0.0;
      for (int b = 0; b < 2; ++b) sum += I.T[static_cast<std::size_t>(a + b + c)] * vt[b];
      stiffness(a, c) = 3.0 * scale / c4 * sum;
    }
  out.force = rot * force;
  out.damping = rot * damping * rot.transpose();
  out.stiffness = rot * stiffness * rot.transpose();
}

}  // namespace geardyn::hbm
