#include "geardyn/gear/geometry.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "geardyn/core/units.hpp"

namespace geardyn::gear {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

[[noreturn]] void fail(const GearPairSpec& spec, const std::string& field, std::string expected,
                       std::string found, std::string hint = {}) {
  throw InputError(spec.where, field.empty() ? spec.key_path : spec.key_path + "." + field,
                   std::move(expected), std::move(found), std::move(hint));
}

std::string num(double v) { return fmt::format("{:.10g}", v); }

void require_positive(const GearPairSpec& spec, const std::string& field, double v) {
  if (!std::isfinite(v) || v <= 0.0) fail(spec, field, "a finite value > 0", num(v));
}

void validate_angles(const GearPairSpec& spec) {
  const double alpha = spec.pressure_angle_rad;
  if (!std::isfinite(alpha) || alpha <= 0.0 || alpha >= 45.0 * units::kRadPerDegree)
    fail(spec, "pressure_angle", "a normal pressure angle in (0, 45) deg",
         num(alpha / units::kRadPerDegree) + " deg");
  const double beta = spec.helix_angle_rad;
  if (!std::isfinite(beta)) fail(spec, "helix_angle", "a finite angle", num(beta));
  switch (spec.type) {
    case GearType::Spur:
    case GearType::StraightBevel:
      if (beta != 0.0)
        fail(spec, "helix_angle", fmt::format("0 for a {} gear", to_string(spec.type)),
             num(beta / units::kRadPerDegree) + " deg",
             spec.type == GearType::Spur ? "use type \"helical\" for a helix angle"
                                         : "use type \"spiral_bevel\" for a spiral angle");
      break;
    case GearType::Helical:
      if (beta <= 0.0 || beta >= 45.0 * units::kRadPerDegree)
        fail(spec, "helix_angle", "a helix angle in (0, 45) deg (the hand is given separately)",
             num(beta / units::kRadPerDegree) + " deg",
             beta == 0.0 ? "use type \"spur\" for beta = 0" : "");
      break;
    case GearType::SpiralBevel:
      if (beta <= 0.0 || beta >= 60.0 * units::kRadPerDegree)
        fail(spec, "helix_angle", "a mean spiral angle in (0, 60) deg",
             num(beta / units::kRadPerDegree) + " deg",
             beta == 0.0 ? "use type \"straight_bevel\" for beta = 0" : "");
      break;
    case GearType::Hypoid:
      if (beta < 0.0 || beta >= 60.0 * units::kRadPerDegree)
        fail(spec, "helix_angle", "the wheel's mean spiral angle in [0, 60) deg",
             num(beta / units::kRadPerDegree) + " deg");
      break;
  }
  const double beta1 = spec.pinion_spiral_angle_rad;
  if (spec.type == GearType::Hypoid) {
    if (!std::isfinite(beta1) || beta1 <= 0.0 || beta1 >= 70.0 * units::kRadPerDegree)
      fail(spec, "pinion_spiral_angle", "the hypoid pinion's mean spiral angle in (0, 70) deg",
           num(beta1 / units::kRadPerDegree) + " deg");
  } else if (!std::isnan(beta1)) {
    fail(spec, "pinion_spiral_angle", "no pinion spiral angle (it applies to hypoid gears only)",
         num(beta1 / units::kRadPerDegree) + " deg",
         "for spiral bevel gears give the mean spiral angle only");
  }
}

// Fills the transverse quantities and checks that the involutes can mesh. `z2s` is the signed
// tooth count of the wheel (negative for an internal gear); radii are signed in the same way.
struct Transverse {
  double r1, r2, rb1, rb2, ra1, ra2, rf1, rf2;  // magnitudes
  double alpha_wt, a;
};

void check_contact(const GearPairSpec& spec, const Transverse& t, bool internal,
                   double& path_of_contact) {
  if (t.ra1 <= t.rb1)
    fail(spec, "profile_shift_pinion", "a pinion tip circle above its base circle",
         fmt::format("tip radius {} m <= base radius {} m", num(t.ra1), num(t.rb1)));
  if (t.ra2 <= t.rb2)
    fail(spec, "profile_shift_wheel", "a wheel tip circle above its base circle",
         fmt::format("tip radius {} m <= base radius {} m", num(t.ra2), num(t.rb2)));
  const double g1 = std::sqrt(t.ra1 * t.ra1 - t.rb1 * t.rb1);
  const double g2 = std::sqrt(t.ra2 * t.ra2 - t.rb2 * t.rb2);
  const double t1t2 = t.a * std::sin(t.alpha_wt);
  const double tol = 1e-12 * t.a;
  if (!internal) {
    // The wheel's tip must not pass the pinion's interference point T1, and vice versa.
    if (g2 > t1t2 + tol)
      fail(spec, "teeth_pinion", "no involute interference at the pinion root",
           fmt::format("the wheel tip reaches {} m past the pinion's interference point",
                       num(g2 - t1t2)),
           "increase the pinion's profile shift or tooth count, or reduce the wheel addendum");
    if (g1 > t1t2 + tol)
      fail(spec, "teeth_wheel", "no involute interference at the wheel root",
           fmt::format("the pinion tip reaches {} m past the wheel's interference point",
                       num(g1 - t1t2)),
           "reduce the pinion addendum or profile shift");
    path_of_contact = g1 + g2 - t1t2;
  } else {
    // Internal mesh: along the line of action T2, T1, A (internal gear tip), C, E (pinion tip).
    if (g2 < t1t2 - tol)
      fail(spec, "teeth_wheel", "no involute interference at the pinion root",
           fmt::format("the internal gear's tip reaches {} m inside the pinion's interference "
                       "point",
                       num(t1t2 - g2)),
           "use more teeth on the internal gear or a positive pinion profile shift");
    path_of_contact = g1 - g2 + t1t2;
  }
}

}  // namespace

std::string_view to_string(GearType type) {
  switch (type) {
    case GearType::Spur:
      return "spur";
    case GearType::Helical:
      return "helical";
    case GearType::StraightBevel:
      return "straight_bevel";
    case GearType::SpiralBevel:
      return "spiral_bevel";
    case GearType::Hypoid:
      return "hypoid";
  }
  return "spur";
}

std::string_view to_string(MeshType type) {
  return type == MeshType::Internal ? "internal" : "external";
}

GearType parse_gear_type(std::string_view text, const std::string& key_path,
                         const SourceLocation& where) {
  for (GearType t : {GearType::Spur, GearType::Helical, GearType::StraightBevel,
                     GearType::SpiralBevel, GearType::Hypoid})
    if (text == to_string(t)) return t;
  throw InputError(where, key_path, "one of spur, helical, straight_bevel, spiral_bevel, hypoid",
                   std::string(text));
}

MeshType parse_mesh_type(std::string_view text, const std::string& key_path,
                         const SourceLocation& where) {
  if (text == "external") return MeshType::External;
  if (text == "internal") return MeshType::Internal;
  throw InputError(where, key_path, "one of external, internal", std::string(text));
}

bool is_bevel(GearType type) {
  return type == GearType::StraightBevel || type == GearType::SpiralBevel ||
         type == GearType::Hypoid;
}

double involute(double alpha_rad) { return std::tan(alpha_rad) - alpha_rad; }

double inverse_involute(double inv_value) {
  if (!(inv_value >= 0.0) || inv_value > 1.5)
    throw std::invalid_argument(
        fmt::format("inverse_involute: argument {} outside [0, 1.5]", inv_value));
  if (inv_value == 0.0) return 0.0;
  // inv(a) ~ a^3/3 for small a gives the start; Newton on tan(a) - a - v with derivative tan^2(a)
  // converges monotonically from above because inv is convex on [0, pi/2).
  double a = std::min(std::cbrt(3.0 * inv_value), 1.4);
  for (int it = 0; it < 60; ++it) {
    const double t = std::tan(a);
    const double step = (t - a - inv_value) / (t * t);
    a -= step;
    if (std::abs(step) < 1e-15 * std::max(1.0, a)) break;
  }
  return a;
}

namespace {

// The checks of the specification that do not depend on the gear type.
void check_spec(const GearPairSpec& spec) {
  if (spec.teeth_pinion <= 0)
    fail(spec, "teeth_pinion", "a positive tooth count", std::to_string(spec.teeth_pinion));
  if (spec.teeth_wheel <= 0)
    fail(spec, "teeth_wheel", "a positive tooth count", std::to_string(spec.teeth_wheel));
  const int z1 = spec.teeth_pinion;
  const int z2 = spec.teeth_wheel;
  const double u = static_cast<double>(z2) / z1;
  if (!std::isnan(spec.ratio)) {
    if (!std::isfinite(spec.ratio_tolerance) || spec.ratio_tolerance < 0.0)
      fail(spec, "ratio_tolerance", "a relative tolerance >= 0", num(spec.ratio_tolerance));
    if (!std::isfinite(spec.ratio) || std::abs(spec.ratio - u) > spec.ratio_tolerance * u)
      fail(spec, "ratio", fmt::format("z2/z1 = {}/{} = {}", z2, z1, num(u)), num(spec.ratio),
           "the ratio is computed from the tooth counts; give it only as a check");
  }
  require_positive(spec, "module", spec.module_m);
  require_positive(spec, "face_width", spec.face_width_m);
  if (!std::isfinite(spec.addendum_coefficient) || spec.addendum_coefficient <= 0.0)
    fail(spec, "addendum_coefficient", "h_a* > 0", num(spec.addendum_coefficient));
  if (!std::isfinite(spec.dedendum_coefficient) ||
      spec.dedendum_coefficient <= spec.addendum_coefficient)
    fail(spec, "dedendum_coefficient", "h_f* > h_a* (root clearance)",
         num(spec.dedendum_coefficient));
  if (!std::isfinite(spec.profile_shift_pinion))
    fail(spec, "profile_shift_pinion", "a finite value", num(spec.profile_shift_pinion));
  if (!std::isfinite(spec.profile_shift_wheel))
    fail(spec, "profile_shift_wheel", "a finite value", num(spec.profile_shift_wheel));
  validate_angles(spec);
}

// Transverse geometry of a spur or helical pair; sets the moduli, the pitch radii and the helix
// angles in g, beta and m_n.
Transverse cylindrical_pair(const GearPairSpec& spec, bool internal, GearPairGeometry& g,
                            double& beta, double& m_n) {
  const int z1 = spec.teeth_pinion;
  const int z2 = spec.teeth_wheel;
  const double ha = spec.addendum_coefficient;
  const double hf = spec.dedendum_coefficient;
  const double x1 = spec.profile_shift_pinion;
  const double x2 = spec.profile_shift_wheel;
  const double alpha_n = spec.pressure_angle_rad;
  Transverse t{};
  if (!std::isnan(spec.outer_cone_distance_m))
    fail(spec, "outer_cone_distance", "no outer cone distance (bevel gears only)",
         num(spec.outer_cone_distance_m));
  beta = spec.helix_angle_rad;
  m_n = spec.module_m;
  const double m_t = m_n / std::cos(beta);
  const double alpha_t = std::atan(std::tan(alpha_n) / std::cos(beta));
  const double z2s = internal ? -static_cast<double>(z2) : static_cast<double>(z2);
  const double r1 = 0.5 * z1 * m_t;
  const double r2s = 0.5 * z2s * m_t;
  // Zero-backlash working pressure angle for the given profile shifts (ISO 21771 5.2).
  const double inv_w0 = involute(alpha_t) + 2.0 * std::tan(alpha_n) * (x1 + x2) / (z1 + z2s);
  if (inv_w0 <= 0.0 || inv_w0 > 1.0)
    fail(spec, "profile_shift_pinion",
         "profile shifts giving a working pressure angle between 0 and ~70 deg",
         fmt::format("inv(alpha_wt) = {} for x1 + x2 = {}", num(inv_w0), num(x1 + x2)));
  const double alpha_w0 = inverse_involute(inv_w0);
  const double a0 = std::abs(r1 + r2s);  // reference centre distance
  const double a_zero_backlash = a0 * std::cos(alpha_t) / std::cos(alpha_w0);
  double alpha_wt = alpha_w0;
  double a = a_zero_backlash;
  if (!std::isnan(spec.centre_distance_m)) {
    require_positive(spec, "centre_distance", spec.centre_distance_m);
    a = spec.centre_distance_m;
    const double c = a0 * std::cos(alpha_t) / a;
    if (c >= 1.0)
      fail(spec, "centre_distance",
           fmt::format("a centre distance above a0 cos(alpha_t) = {} m",
                       num(a0 * std::cos(alpha_t))),
           num(a) + " m");
    alpha_wt = std::acos(c);
    // Profile-shift sum the given centre distance can take without backlash; more would make
    // the teeth overlap. Signed tooth count makes the same inequality hold for internal gears.
    const double x_sum_max =
        (involute(alpha_wt) - involute(alpha_t)) * (z1 + z2s) / (2.0 * std::tan(alpha_n));
    if (x1 + x2 > x_sum_max + 1e-9)
      fail(spec, "centre_distance",
           fmt::format("a centre distance leaving non-negative backlash for x1 + x2 = {} "
                       "(zero-backlash centre distance {} m)",
                       num(x1 + x2), num(a_zero_backlash)),
           num(a) + " m",
           internal ? "reduce the centre distance or the profile shifts"
                    : "increase the centre distance or reduce the profile shifts");
  }
  t.r1 = r1;
  t.r2 = std::abs(r2s);
  t.rb1 = r1 * std::cos(alpha_t);
  t.rb2 = t.r2 * std::cos(alpha_t);
  t.ra1 = r1 + m_n * (ha + x1);
  t.rf1 = r1 - m_n * (hf - x1);
  t.ra2 = std::abs(r2s + m_n * (ha + x2));  // signed: d_a = d + 2 m_n (h_a* + x)
  t.rf2 = std::abs(r2s - m_n * (hf - x2));
  t.alpha_wt = alpha_wt;
  t.a = a;
  g.normal_module_m = m_n;
  g.transverse_module_m = m_t;
  g.transverse_pressure_angle_rad = alpha_t;
  g.pinion.mean_pitch_radius_m = t.r1;
  g.wheel.mean_pitch_radius_m = t.r2;
  g.pinion.spiral_angle_rad = beta;
  g.wheel.spiral_angle_rad = beta;
  return t;
}

// Transverse geometry of the virtual cylindrical pair of a bevel or hypoid pair at mid face;
// sets the moduli, the cone data and the spiral angles in g, beta, m_n and the virtual tooth
// counts.
Transverse bevel_pair(const GearPairSpec& spec, double u, GearPairGeometry& g, double& beta,
                      double& m_n, double& zv1, double& zv2) {
  const int z1 = spec.teeth_pinion;
  const int z2 = spec.teeth_wheel;
  const double ha = spec.addendum_coefficient;
  const double hf = spec.dedendum_coefficient;
  const double x1 = spec.profile_shift_pinion;
  const double x2 = spec.profile_shift_wheel;
  const double alpha_n = spec.pressure_angle_rad;
  Transverse t{};
  if (!std::isnan(spec.centre_distance_m))
    fail(spec, "centre_distance", "no centre distance (cylindrical gears only)",
         num(spec.centre_distance_m), "bevel gears are set by the shaft angle");
  const double sigma = spec.shaft_angle_rad;
  if (!std::isfinite(sigma) || sigma <= 0.0 || sigma >= units::kPi)
    fail(spec, "shaft_angle", "a shaft angle in (0, 180) deg",
         num(sigma / units::kRadPerDegree) + " deg");
  if (std::abs(x1 + x2) > 1e-12)
    fail(spec, "profile_shift_wheel",
         fmt::format("x2 = -x1 = {} (bevel gears use balanced profile shift)", num(-x1)), num(x2));
  const double delta1 = std::atan2(std::sin(sigma), u + std::cos(sigma));
  const double delta2 = sigma - delta1;
  if (delta2 >= 0.5 * units::kPi - 1e-9)
    fail(spec, "shaft_angle",
         "a wheel pitch cone angle below 90 deg (crown and internal bevel gears are not "
         "supported)",
         fmt::format("delta2 = {} deg", num(delta2 / units::kRadPerDegree)));
  const double m_e = spec.module_m;
  const double R_e = 0.5 * m_e * z1 / std::sin(delta1);
  if (!std::isnan(spec.outer_cone_distance_m)) {
    require_positive(spec, "outer_cone_distance", spec.outer_cone_distance_m);
    if (std::abs(spec.outer_cone_distance_m - R_e) > 1e-6 * R_e)
      fail(spec, "outer_cone_distance", fmt::format("m_e z1 / (2 sin delta1) = {} m", num(R_e)),
           num(spec.outer_cone_distance_m) + " m",
           "check the outer module, tooth counts and shaft angle");
  }
  const double b = spec.face_width_m;
  if (b >= R_e)
    fail(spec, "face_width",
         fmt::format("a face width below the outer cone distance {} m", num(R_e)), num(b) + " m",
         "bevel face widths are usually below R_e / 3");
  const double R_m = R_e - 0.5 * b;
  const double m_m = m_e * R_m / R_e;  // mid-face module (thesis 3.2)
  const double beta2 = spec.helix_angle_rad;
  const double beta1 = spec.type == GearType::Hypoid ? spec.pinion_spiral_angle_rad : beta2;
  m_n = m_m * std::cos(beta2);  // mean normal module, common to both members
  const double r_m2 = 0.5 * m_m * z2;
  const double r_m1 = 0.5 * m_n / std::cos(beta1) * z1;
  beta = 0.5 * (beta1 + beta2);
  const double m_t = m_n / std::cos(beta);  // = m_m for bevel gears
  const double alpha_t = std::atan(std::tan(alpha_n) / std::cos(beta));
  zv1 = z1 / std::cos(delta1);
  zv2 = z2 / std::cos(delta2);
  t.r1 = 0.5 * zv1 * m_t;
  t.r2 = 0.5 * zv2 * m_t;
  t.rb1 = t.r1 * std::cos(alpha_t);
  t.rb2 = t.r2 * std::cos(alpha_t);
  t.ra1 = t.r1 + m_n * (ha + x1);
  t.ra2 = t.r2 + m_n * (ha + x2);
  t.rf1 = t.r1 - m_n * (hf - x1);
  t.rf2 = t.r2 - m_n * (hf - x2);
  t.alpha_wt = alpha_t;
  t.a = t.r1 + t.r2;
  g.normal_module_m = m_n;
  g.transverse_module_m = m_t;
  g.transverse_pressure_angle_rad = alpha_t;
  g.outer_module_m = m_e;
  g.mean_module_m = m_m;
  g.outer_cone_distance_m = R_e;
  g.mean_cone_distance_m = R_m;
  g.pinion.mean_pitch_radius_m = r_m1;
  g.wheel.mean_pitch_radius_m = r_m2;
  g.pinion.pitch_cone_angle_rad = delta1;
  g.wheel.pitch_cone_angle_rad = delta2;
  g.pinion.spiral_angle_rad = beta1;
  g.wheel.spiral_angle_rad = beta2;
  return t;
}

}  // namespace

GearPairGeometry gear_pair_geometry(const GearPairSpec& spec) {
  check_spec(spec);
  const int z1 = spec.teeth_pinion;
  const int z2 = spec.teeth_wheel;
  const double u = static_cast<double>(z2) / z1;
  const bool bevel = is_bevel(spec.type);
  const bool internal = spec.mesh == MeshType::Internal;
  if (internal && bevel)
    fail(spec, "mesh", "external for bevel and hypoid gears", "internal",
         "internal meshes are supported for spur and helical gears");
  if (internal && z2 <= z1)
    fail(spec, "teeth_wheel",
         fmt::format("more teeth than the pinion ({}) on the internal gear", z1),
         std::to_string(z2));

  GearPairGeometry g;
  g.spec = spec;
  g.ratio = u;
  g.face_width_m = spec.face_width_m;
  g.normal_pressure_angle_rad = spec.pressure_angle_rad;
  g.pinion.teeth = z1;
  g.wheel.teeth = z2;
  g.pinion.profile_shift = spec.profile_shift_pinion;
  g.wheel.profile_shift = spec.profile_shift_wheel;
  const double alpha_n = spec.pressure_angle_rad;

  double beta = 0.0;  // helix angle of the (virtual) cylindrical pair
  double m_n = 0.0;   // normal module of the (virtual) pair
  double zv1 = z1, zv2 = z2;
  const Transverse t = bevel ? bevel_pair(spec, u, g, beta, m_n, zv1, zv2)
                             : cylindrical_pair(spec, internal, g, beta, m_n);

  check_contact(spec, t, internal, g.path_of_contact_m);
  g.helix_angle_rad = beta;
  g.base_helix_angle_rad = std::asin(std::sin(beta) * std::cos(alpha_n));
  g.working_pressure_angle_rad = t.alpha_wt;
  g.centre_distance_m = t.a;
  g.transverse_base_pitch_m =
      units::kPi * g.transverse_module_m * std::cos(g.transverse_pressure_angle_rad);
  g.transverse_contact_ratio = g.path_of_contact_m / g.transverse_base_pitch_m;
  g.overlap_ratio = g.face_width_m * std::sin(beta) / (units::kPi * m_n);
  g.total_contact_ratio = g.transverse_contact_ratio + g.overlap_ratio;

  const double cb = std::cos(g.base_helix_angle_rad);
  auto fill = [&](GearGeometry& m, double r, double rb, double ra, double rf, double zv) {
    m.pitch_radius_m = r;
    m.base_radius_m = rb;
    m.tip_radius_m = ra;
    m.root_radius_m = rf;
    m.working_pitch_radius_m = rb / std::cos(t.alpha_wt);
    m.virtual_teeth = zv;
    m.normal_virtual_teeth = zv / (cb * cb * std::cos(beta));
  };
  fill(g.pinion, t.r1, t.rb1, t.ra1, t.rf1, zv1);
  fill(g.wheel, t.r2, t.rb2, t.ra2, t.rf2, zv2);
  if (internal) g.wheel.normal_virtual_teeth = std::numeric_limits<double>::infinity();
  if (t.rf1 <= 0.0)
    fail(spec, "dedendum_coefficient", "a positive pinion root radius", num(t.rf1) + " m");

  if (g.transverse_contact_ratio < 1.0)
    fail(spec, "", "a transverse contact ratio eps_alpha >= 1",
         fmt::format("eps_alpha = {:.6f}: the gears cannot transmit motion continuously",
                     g.transverse_contact_ratio),
         "increase the addendum, the tooth counts, or reduce the pressure angle");
  return g;
}

Table geometry_table(const std::vector<GearPairGeometry>& pairs) {
  Table t;
  t.name = "gear_geometry";
  t.title = "Gear pair geometry (bevel and hypoid: virtual cylindrical gears at mid face)";
  std::vector<std::string> pair, member;
  std::vector<double> teeth, zv, r, rm, rb, ra, rf, rw, delta, beta, beta_b, b, x, a, mn, mt,
      alpha_w, ea, eb, eg;
  for (const auto& g : pairs) {
    for (int k = 0; k < 2; ++k) {
      const GearGeometry& m = k == 0 ? g.pinion : g.wheel;
      pair.push_back(g.spec.name);
      member.push_back(k == 0 ? "pinion" : "wheel");
      teeth.push_back(m.teeth);
      zv.push_back(m.virtual_teeth);
      r.push_back(m.pitch_radius_m);
      rm.push_back(m.mean_pitch_radius_m);
      rb.push_back(m.base_radius_m);
      ra.push_back(m.tip_radius_m);
      rf.push_back(m.root_radius_m);
      rw.push_back(m.working_pitch_radius_m);
      delta.push_back(m.pitch_cone_angle_rad / units::kRadPerDegree);
      beta.push_back(m.spiral_angle_rad / units::kRadPerDegree);
      beta_b.push_back(g.base_helix_angle_rad / units::kRadPerDegree);
      b.push_back(g.face_width_m);
      x.push_back(m.profile_shift);
      a.push_back(g.centre_distance_m);
      mn.push_back(g.normal_module_m);
      mt.push_back(g.transverse_module_m);
      alpha_w.push_back(g.working_pressure_angle_rad / units::kRadPerDegree);
      ea.push_back(g.transverse_contact_ratio);
      eb.push_back(g.overlap_ratio);
      eg.push_back(g.total_contact_ratio);
    }
  }
  t.add_text("pair", std::move(pair));
  t.add_text("member", std::move(member));
  t.add("teeth", "", std::move(teeth));
  t.add("virtual_teeth", "", std::move(zv));
  t.add("pitch_radius_m", "m", std::move(r));
  t.add("mean_pitch_radius_m", "m", std::move(rm));
  t.add("base_radius_m", "m", std::move(rb));
  t.add("tip_radius_m", "m", std::move(ra));
  t.add("root_radius_m", "m", std::move(rf));
  t.add("working_pitch_radius_m", "m", std::move(rw));
  t.add("pitch_cone_angle_deg", "deg", std::move(delta));
  t.add("spiral_angle_deg", "deg", std::move(beta));
  t.add("base_helix_angle_deg", "deg", std::move(beta_b));
  t.add("contact_face_width_m", "m", std::move(b));
  t.add("profile_shift", "", std::move(x));
  t.add("centre_distance_m", "m", std::move(a));
  t.add("normal_module_m", "m", std::move(mn));
  t.add("transverse_module_m", "m", std::move(mt));
  t.add("working_pressure_angle_deg", "deg", std::move(alpha_w));
  t.add("transverse_contact_ratio", "", std::move(ea));
  t.add("overlap_ratio", "", std::move(eb));
  t.add("total_contact_ratio", "", std::move(eg));
  return t;
}

}  // namespace geardyn::gear
