// Analytic slice compliance of a meshing tooth pair (docs/theory.md §15.1-15.2).
//
// Tooth body: the potential-energy method (D.C.H. Yang, J.Y. Lin, "Hertzian damping, tooth
// friction and bending elasticity in gear impact dynamics", J. Mech. Trans. Autom. Des. 109,
// 1987; X. Tian, "Dynamic simulation for system response of gearbox including localized gear
// faults", MSc thesis, University of Alberta, 2004; Z. Chen, Y. Shao, "Dynamic simulation of spur
// gear with tooth root crack propagating along tooth width and crack depth", Eng. Fail. Anal. 18,
// 2011). Each tooth is a non-uniform cantilever along its centre line; the line load w acts at the
// contact point along the line of action, at the angle alpha_1 to the normal of the centre line,
// with the lever arm d = |y_c - y| along the centre line and the offset h_c of the contact point
// from it. Per unit face width (I = 2 h^3 / 3, A = 2 h for the half thickness h(y)):
//   c_b = int (cos a1 d - sin a1 h_c)^2 / (E' I) dy      (bending)
//   c_s = int 1.2 cos^2 a1 / (G A) dy                     (shear)
//   c_a = int sin^2 a1 / (E' A) dy                        (axial compression)
// E' = E / (1 - nu^2) in plane strain (option), G = E / (2 (1 + nu)).
// Profile: the involute half angle beta(r) = (pi/2 + 2 x tan alpha_n) / z + inv alpha_t
// - inv alpha_r in the transverse section, a1 = alpha_r - beta; integrated over the profile
// pressure angle alpha_r (smooth at the base circle). Root: when r_f < r_b the tooth continues
// below the base circle as a straight part of the base-circle half thickness down to the root
// circle (the model of Tian 2004 and Chen & Shao 2011); when r_f >= r_b the cantilever starts on
// the involute at the root circle. The trochoidal fillet is not integrated.
//
// Internal gear (approximation): the same integrals on the ring's own tooth, whose involute
// half angle beta(r) = (pi/2 + 2 x2 tan alpha_n) / z2 - inv alpha_t + inv alpha_r grows towards
// its root circle (outside); the load angle is a1 = alpha_r + beta (the centre line points
// outwards, so the tooth's taper has the opposite sense to an external tooth's) and the
// cantilever runs from the contact point out to r_f2.
//
// Fillet foundation: P. Sainsot, P. Velex, O. Duverger, "Contribution of gear body to tooth
// deflections - a new bidimensional analytical formula", J. Mech. Design 126 (2004) 748-752:
//   c_f = cos^2 a1 / E [L* (u_f/S_f)^2 + M* (u_f/S_f) + P* (1 + Q* tan^2 a1)]
//   X* = A / theta_f^2 + B h_fi^2 + C h_fi / theta_f + D / theta_f + E h_fi + F
// with their table of A..F for L*, M*, P*, Q* (below), h_fi = r_f / r_int, theta_f the half
// angle of the tooth at the root circle, S_f = 2 r_f theta_f, u_f the distance from the root
// circle to the point where the line of action crosses the centre line. The correction for two
// neighbouring teeth loaded together is NOT included. theta_f of an external gear is where the
// fillet meets the root circle, the end of the basic rack's tip flat rolled on the reference
// circle: theta_f = pi/z - e_t / r with the flat's half width (normal section, per m_n)
//   e = pi/4 - h_fP* tan(alpha_n) - rho_fP* (1 - sin alpha_n) / cos alpha_n,  e_t = e m_n /
//   cos(beta)
// (independent of the profile shift). For the ring (approximation): theta_f is its involute half
// angle at r_f2, and its body is the external body of the same rim thickness (r_int = 2 r_f - r_o).
//
// Hertzian approach: C. Weber, K. Banaschek, "Formänderung und Profilrücknahme bei gerad- und
// schrägverzahnten Rädern", Schriftenreihe Antriebstechnik 11, Vieweg, 1955, as quoted by
// R.W. Cornell, "Compliance and stress sensitivity of spur gear teeth", J. Mech. Des. 103 (1981)
// 447-459: per body i the approach between the contact surface and the tooth centre line at the
// depth d_i along the load,
//   delta_i = 2 w (1 - nu_i^2) / (pi E_i) [ln(2 d_i / b_H) - nu_i / (2 (1 - nu_i))],
// the plane-strain compression of a body under the Hertz pressure of a line contact, with the
// half width b_H = sqrt(4 w R / (pi E*)) (K.L. Johnson, "Contact Mechanics", 1985, sec. 4.3);
// d_i = h_c / cos(alpha_1) is taken along the load. delta = delta_1 + delta_2;
// its derivative is analytic: d delta / d w = delta / w - sum_i (1 - nu_i^2) / (pi E_i).
// Helical gears: the normal section (radii of curvature rho_n = rho_t / cos beta_b; the load per
// unit length of contact line equals the transverse line load w, since the normal force
// w / cos beta_b is spread on 1 / cos beta_b of contact line per unit face width); the approach
// along the transverse line of action is delta_n / cos beta_b.
#include "geardyn/gear/tooth_compliance.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>

#include "geardyn/core/error.hpp"
#include "geardyn/core/units.hpp"

namespace geardyn::gear {
namespace {

constexpr double kPi = units::kPi;
constexpr int kGaussPoints = 16;
constexpr int kInvolutePanels = 4;

std::string num(double v) { return fmt::format("{:.10g}", v); }

// Gauss-Legendre nodes and weights on [-1, 1] (Newton on the Legendre recurrence).
struct GaussRule {
  std::array<double, kGaussPoints> x{}, w{};
  GaussRule() {
    const int n = kGaussPoints;
    for (int i = 0; i < n; ++i) {
      double t = std::cos(kPi * (i + 0.75) / (n + 0.5));
      double dp = 1.0;
      for (int it = 0; it < 100; ++it) {
        double p0 = 1.0, p1 = t;
        for (int k = 2; k <= n; ++k) {
          const double p2 = ((2.0 * k - 1.0) * t * p1 - (k - 1.0) * p0) / k;
          p0 = p1;
          p1 = p2;
        }
        dp = n * (t * p1 - p0) / (t * t - 1.0);
        const double step = p1 / dp;
        t -= step;
        if (std::abs(step) < 1e-16) break;
      }
      x[static_cast<std::size_t>(i)] = t;
      w[static_cast<std::size_t>(i)] = 2.0 / ((1.0 - t * t) * dp * dp);
    }
  }
};

const GaussRule& gauss() {
  static const GaussRule rule;
  return rule;
}

// Sainsot et al. (2004), Table 1: rows L*, M*, P*, Q*; columns A, B, C, D, E, F.
constexpr double kSainsot[4][6] = {
    {-5.574e-5, -1.9986e-3, -2.3015e-4, 4.7702e-3, 0.0271, 6.8045},
    {60.111e-5, 28.100e-3, -83.431e-4, -9.9256e-3, 0.1624, 0.9086},
    {-50.952e-5, 185.50e-3, 0.0538e-4, 53.300e-3, 0.2895, 0.9236},
    {-6.2042e-5, 9.0889e-3, -4.0964e-4, 7.8297e-3, -0.1472, 0.6904},
};
constexpr double kSainsotMinRatio = 1.4;  // fitted range of h_fi = r_f / r_int
constexpr double kSainsotMaxRatio = 7.0;

double sainsot(int row, double theta_f, double h_fi) {
  const double* c = kSainsot[row];
  return c[0] / (theta_f * theta_f) + c[1] * h_fi * h_fi + c[2] * h_fi / theta_f + c[3] / theta_f +
         c[4] * h_fi + c[5];
}

double inv(double a) { return std::tan(a) - a; }

[[noreturn]] void fail(const GearPairGeometry& g, const std::string& field, std::string expected,
                       std::string found, std::string hint = {}) {
  throw InputError(g.spec.where, g.spec.key_path + "." + field, std::move(expected),
                   std::move(found), std::move(hint));
}

void check_elastic(const GearPairGeometry& g, const ElasticConstants& e, const std::string& who) {
  if (!std::isfinite(e.youngs_modulus_pa) || e.youngs_modulus_pa <= 0.0)
    fail(g, "youngs_modulus_" + who, "a Young's modulus > 0 [Pa]", num(e.youngs_modulus_pa));
  if (!std::isfinite(e.poisson_ratio) || e.poisson_ratio <= -1.0 || e.poisson_ratio >= 0.5)
    fail(g, "poisson_ratio_" + who, "a Poisson ratio in (-1, 0.5)", num(e.poisson_ratio));
}

}  // namespace

ToothCompliance::ToothCompliance(const GearPairGeometry& geometry,
                                 const ToothComplianceOptions& options)
    : geometry_(geometry), options_(options) {
  const GearPairGeometry& g = geometry_;
  if (is_bevel(g.spec.type))
    fail(g, "type", "a cylindrical gear pair (spur or helical) for the slice compliance",
         std::string(to_string(g.spec.type)),
         "bevel and hypoid gears use their virtual cylindrical pair (not yet here)");
  check_elastic(g, options.pinion, "pinion");
  check_elastic(g, options.wheel, "wheel");
  const double rho = options.root_fillet_coefficient;
  const double alpha_n = g.normal_pressure_angle_rad;
  const double m_n = g.normal_module_m;
  const double cos_beta = std::cos(g.helix_angle_rad);
  // Half width of the basic rack's tip flat (normal section, per m_n): it must be >= 0.
  const double flat = kPi / 4.0 - g.spec.dedendum_coefficient * std::tan(alpha_n) -
                      rho * (1.0 - std::sin(alpha_n)) / std::cos(alpha_n);
  if (!std::isfinite(rho) || rho < 0.0 || flat < 0.0)
    fail(g, "root_fillet_coefficient",
         "a rack root fillet rho_fP/m_n >= 0 that leaves a flat on the rack tip", num(rho),
         fmt::format("the largest fillet for h_fP* = {} is {}", num(g.spec.dedendum_coefficient),
                     num((kPi / 4.0 - g.spec.dedendum_coefficient * std::tan(alpha_n)) *
                         std::cos(alpha_n) / (1.0 - std::sin(alpha_n)))));
  cos_beta_b_ = std::cos(g.base_helix_angle_rad);
  const double inv_t = inv(g.transverse_pressure_angle_rad);
  const double e1 = options.pinion.youngs_modulus_pa, e2 = options.wheel.youngs_modulus_pa;
  const double nu1 = options.pinion.poisson_ratio, nu2 = options.wheel.poisson_ratio;
  e_star_ = 1.0 / ((1.0 - nu1 * nu1) / e1 + (1.0 - nu2 * nu2) / e2);

  auto build = [&](const GearGeometry& m, const ElasticConstants& el, bool internal, double bore,
                   const std::string& who) {
    Tooth t;
    t.internal = internal;
    t.rb = m.base_radius_m;
    t.ra = m.tip_radius_m;
    t.rf = m.root_radius_m;
    const double half_ref =
        (kPi / 2.0 + 2.0 * m.profile_shift * std::tan(alpha_n)) / m.virtual_teeth;
    t.c0 = internal ? half_ref - inv_t : half_ref + inv_t;
    auto beta = [&](double a) { return internal ? t.c0 + inv(a) : t.c0 - inv(a); };
    const double alpha_tip = std::acos(t.rb / t.ra);
    if (beta(alpha_tip) <= 0.0)
      fail(g, "profile_shift_" + who, "a tooth with a tip land (not pointed)",
           fmt::format("half tooth angle {} rad at the tip", num(beta(alpha_tip))),
           "reduce the profile shift or the addendum");
    const double nu = el.poisson_ratio, e = el.youngs_modulus_pa;
    t.nu = nu;
    t.e_body = e;
    t.e_beam = options.plane_strain ? e / (1.0 - nu * nu) : e;
    t.g_shear = e / (2.0 * (1.0 + nu));
    t.hertz_k = (1.0 - nu * nu) / (kPi * e);
    double theta_f = 0.0;
    if (!internal) {
      if (t.rf < t.rb) {
        const double beta_b = beta(0.0);
        t.alpha_root = 0.0;
        t.h_base = t.rb * std::sin(beta_b);
        t.y_base = t.rb * std::cos(beta_b);
        t.y_root = std::sqrt(std::max(t.rf * t.rf - t.h_base * t.h_base, 0.0));
      } else {
        t.alpha_root = std::acos(t.rb / t.rf);
        t.y_root = t.rf * std::cos(beta(t.alpha_root));
      }
      // End of the rack-tip flat on the root circle (transverse): its half width is
      // flat m_n / cos(beta), rolled on the reference radius.
      theta_f = kPi / m.virtual_teeth - flat * m_n / cos_beta / m.pitch_radius_m;
    } else {
      t.alpha_root = std::acos(t.rb / t.rf);
      t.y_root = t.rf * std::cos(beta(t.alpha_root));
      theta_f = beta(t.alpha_root);
    }
    t.root_thickness = 2.0 * t.rf * theta_f;
    // Sainsot's body ratio h_fi = r_f / r_int.
    double h_fi = 2.0;
    if (!std::isnan(bore)) {
      const std::string field = "bore_radius_" + who;
      if (!internal) {
        if (!std::isfinite(bore) || bore <= 0.0 || bore >= t.rf)
          fail(g, field, fmt::format("a bore radius in (0, r_f = {}) m", num(t.rf)), num(bore));
        h_fi = t.rf / bore;
      } else {
        if (!std::isfinite(bore) || bore <= t.rf)
          fail(g, field, fmt::format("the ring's outer radius > r_f = {} m", num(t.rf)), num(bore));
        const double r_int = 2.0 * t.rf - bore;  // the external body of the same rim
        h_fi = r_int > 0.0 ? t.rf / r_int : kSainsotMaxRatio;
      }
      if (options.foundation && h_fi < kSainsotMinRatio)
        fail(g, field,
             fmt::format("a gear body with r_f / r_int >= {} (Sainsot et al. 2004 fitted "
                         "1.4 ... 7)",
                         kSainsotMinRatio),
             fmt::format("r_f / r_int = {}", num(h_fi)),
             "a thinner rim is outside the foundation formula: set foundation = false");
      h_fi = std::min(h_fi, kSainsotMaxRatio);
    }
    t.l_star = sainsot(0, theta_f, h_fi);
    t.m_star = sainsot(1, theta_f, h_fi);
    t.p_star = sainsot(2, theta_f, h_fi);
    t.q_star = sainsot(3, theta_f, h_fi);
    return t;
  };
  const bool internal = g.spec.mesh == MeshType::Internal;
  pinion_ = build(g.pinion, options.pinion, false, options.bore_radius_pinion_m, "pinion");
  wheel_ = build(g.wheel, options.wheel, internal, options.bore_radius_wheel_m, "wheel");
}

double ToothCompliance::clamp_s(double s) const {
  if (std::isnan(s)) return 0.0;
  return std::clamp(s, 0.0, geometry_.path_of_contact_m);
}

double ToothCompliance::roll_pinion(double s) const {
  const GearPairGeometry& g = geometry_;
  const double g2 = std::sqrt(g.wheel.tip_radius_m * g.wheel.tip_radius_m -
                              g.wheel.base_radius_m * g.wheel.base_radius_m);
  const double t1t2 = g.centre_distance_m * std::sin(g.working_pressure_angle_rad);
  const double start = g.spec.mesh == MeshType::Internal ? g2 - t1t2 : t1t2 - g2;
  return std::max(start + clamp_s(s), 0.0);
}

double ToothCompliance::roll_wheel(double s) const {
  const GearPairGeometry& g = geometry_;
  const double g2 = std::sqrt(g.wheel.tip_radius_m * g.wheel.tip_radius_m -
                              g.wheel.base_radius_m * g.wheel.base_radius_m);
  return std::max(g.spec.mesh == MeshType::Internal ? g2 + clamp_s(s) : g2 - clamp_s(s), 0.0);
}

double ToothCompliance::pinion_radius(double s) const {
  const double rb = pinion_.rb, rho = roll_pinion(s);
  return std::sqrt(rb * rb + rho * rho);
}

double ToothCompliance::wheel_radius(double s) const {
  const double rb = wheel_.rb, rho = roll_wheel(s);
  return std::sqrt(rb * rb + rho * rho);
}

double ToothCompliance::relative_curvature_radius(double s) const {
  const double r1 = roll_pinion(s), r2 = roll_wheel(s);
  if (geometry_.spec.mesh == MeshType::Internal) return r1 * r2 / (r2 - r1);
  return r1 * r2 / (r1 + r2);
}

ToothCompliance::ContactPoint ToothCompliance::contact_point(const Tooth& t,
                                                             double roll_length) const {
  ContactPoint c;
  c.alpha = std::atan(roll_length / t.rb);
  c.r = std::hypot(t.rb, roll_length);
  const double beta = t.internal ? t.c0 + inv(c.alpha) : t.c0 - inv(c.alpha);
  c.y = c.r * std::cos(beta);
  c.h = c.r * std::sin(beta);
  c.load_angle = t.internal ? c.alpha + beta : c.alpha - beta;
  return c;
}

void ToothCompliance::tooth_terms(const Tooth& t, double roll_length, double& bending,
                                  double& shear, double& compression, double& foundation) const {
  const ContactPoint c = contact_point(t, roll_length);
  const double ca = std::cos(c.load_angle), sa = std::sin(c.load_angle);
  double cb = 0.0, cs = 0.0, cc = 0.0;
  // One section at centre-line coordinate y with half thickness h, weight dy.
  auto add = [&](double y, double h, double dy) {
    const double moment = ca * std::abs(c.y - y) - sa * c.h;
    cb += dy * moment * moment / (t.e_beam * (2.0 / 3.0) * h * h * h);
    cs += dy * 1.2 * ca * ca / (t.g_shear * 2.0 * h);
    cc += dy * sa * sa / (t.e_beam * 2.0 * h);
  };
  const GaussRule& q = gauss();
  // Involute part, over the profile pressure angle between the contact point and the root end.
  const double a_lo = t.internal ? c.alpha : t.alpha_root;
  const double a_hi = t.internal ? t.alpha_root : c.alpha;
  if (a_hi > a_lo) {
    const double panel = (a_hi - a_lo) / kInvolutePanels;
    for (int p = 0; p < kInvolutePanels; ++p) {
      const double mid = a_lo + (p + 0.5) * panel;
      for (int i = 0; i < kGaussPoints; ++i) {
        const double a = mid + 0.5 * panel * q.x[static_cast<std::size_t>(i)];
        const double r = t.rb / std::cos(a);
        const double beta = t.internal ? t.c0 + inv(a) : t.c0 - inv(a);
        const double ta = std::tan(a);
        // dy/dalpha of y = r cos(beta): r tan(a) (cos beta -+ sin beta tan a).
        const double dyda =
            r * ta * std::abs(std::cos(beta) + (t.internal ? -1.0 : 1.0) * std::sin(beta) * ta);
        add(r * std::cos(beta), r * std::sin(beta),
            0.5 * panel * q.w[static_cast<std::size_t>(i)] * dyda);
      }
    }
  }
  // Straight part below the base circle (external, r_f < r_b): polynomial integrands, exact.
  if (t.h_base > 0.0 && t.y_base > t.y_root) {
    const double len = t.y_base - t.y_root;
    for (int i = 0; i < kGaussPoints; ++i)
      add(t.y_root + 0.5 * len * (1.0 + q.x[static_cast<std::size_t>(i)]), t.h_base,
          0.5 * len * q.w[static_cast<std::size_t>(i)]);
  }
  bending = cb;
  shear = cs;
  compression = cc;
  foundation = 0.0;
  if (options_.foundation) {
    const double ta = std::tan(c.load_angle);
    // Where the line of action crosses the centre line, measured from the root circle.
    const double u_f = t.internal ? t.rf - (c.y + c.h * ta) : (c.y - c.h * ta) - t.rf;
    const double ratio = u_f / t.root_thickness;
    foundation =
        ca * ca / t.e_body *
        (t.l_star * ratio * ratio + t.m_star * ratio + t.p_star * (1.0 + t.q_star * ta * ta));
  }
}

PointCompliance ToothCompliance::at(double s) const {
  PointCompliance pc;
  tooth_terms(pinion_, roll_pinion(s), pc.bending_pinion, pc.shear_pinion, pc.compression_pinion,
              pc.foundation_pinion);
  tooth_terms(wheel_, roll_wheel(s), pc.bending_wheel, pc.shear_wheel, pc.compression_wheel,
              pc.foundation_wheel);
  return pc;
}

double ToothCompliance::hertz_half_width(double s, double w) const {
  if (!(w > 0.0)) return 0.0;
  const double r_n = relative_curvature_radius(s) / cos_beta_b_;
  return std::sqrt(4.0 * w * r_n / (kPi * e_star_));
}

double ToothCompliance::hertz_max_pressure(double s, double w) const {
  if (!(w > 0.0)) return 0.0;
  return 2.0 * w / (kPi * hertz_half_width(s, w));
}

double ToothCompliance::hertz_approach(double s, double w) const {
  if (!(w > 0.0)) return 0.0;
  const double b = hertz_half_width(s, w);
  const ContactPoint c1 = contact_point(pinion_, roll_pinion(s));
  const ContactPoint c2 = contact_point(wheel_, roll_wheel(s));
  // Depth of each tooth centre line below the contact point, along the load.
  const double d1 = c1.h / std::cos(c1.load_angle), d2 = c2.h / std::cos(c2.load_angle);
  auto body = [&](const Tooth& t, double d) {
    return 2.0 * w * t.hertz_k * (std::log(2.0 * d / b) - t.nu / (2.0 * (1.0 - t.nu)));
  };
  return (body(pinion_, d1) + body(wheel_, d2)) / cos_beta_b_;
}

double ToothCompliance::hertz_compliance(double s, double w) const {
  if (!(w > 0.0)) return std::numeric_limits<double>::infinity();
  return hertz_approach(s, w) / w - (pinion_.hertz_k + wheel_.hertz_k) / cos_beta_b_;
}

}  // namespace geardyn::gear
