#include "geardyn/gear/mesh_stiffness.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "geardyn/core/units.hpp"

namespace geardyn::gear {
namespace {

// ISO 6336-1:2019 9.3, constants of the flexibility series q' [mm·µm/N].
constexpr double kC1 = 0.04723, kC2 = 0.15551, kC3 = 0.25791, kC4 = -0.00635, kC5 = -0.11654,
                 kC6 = -0.00193, kC7 = -0.24188, kC8 = 0.00529, kC9 = 0.00182;
constexpr double kSteelModulusPa = 206e9;         // E_st
constexpr double kIsoUnitToSi = 1e9;              // 1 N/(mm·µm) = 1e9 N/m^2
constexpr double kReferenceLineLoadNPerMm = 100;  // below this ISO corrects c'

[[noreturn]] void fail(const GearPairGeometry& g, const std::string& field, std::string expected,
                       std::string found, std::string hint = {}) {
  throw InputError(g.spec.where, g.spec.key_path + "." + field, std::move(expected),
                   std::move(found), std::move(hint));
}

// Single-pair stiffness law along the path, normalised by c' (see header): value and primitive.
class PairLaw {
 public:
  PairLaw(double path_length, double ramp_length) : g_(path_length), L_(ramp_length) {}

  double value(double s) const {
    if (s < 0.0 || s >= g_) return 0.0;
    if (L_ <= 0.0) return 1.0;
    if (s < L_) return 0.75 + 0.25 * s / L_;
    if (s <= g_ - L_) return 1.0;
    return 0.75 + 0.25 * (g_ - s) / L_;
  }

  // int_0^s value(t) dt, continuous and piecewise quadratic.
  double primitive(double s) const {
    if (s <= 0.0) return 0.0;
    if (s >= g_) return g_ - 0.25 * L_;
    if (L_ <= 0.0) return s;
    if (s < L_) return 0.75 * s + 0.125 * s * s / L_;
    if (s <= g_ - L_) return 0.875 * L_ + (s - L_);
    const double r = s - (g_ - L_);
    return 0.875 * L_ + (g_ - 2.0 * L_) + r - 0.125 * r * r / L_;
  }

  double path_length() const { return g_; }

 private:
  double g_, L_;
};

}  // namespace

IsoStiffness iso_mesh_stiffness(const GearPairGeometry& g, const IsoStiffnessOptions& o) {
  IsoStiffness s;
  if (!std::isfinite(o.correction_factor) || o.correction_factor <= 0.0)
    fail(g, "correction_factor", "C_M > 0 (ISO 6336-1: 0.8)",
         fmt::format("{}", o.correction_factor));
  if (!std::isfinite(o.application_factor) || o.application_factor < 1.0)
    fail(g, "application_factor", "K_A >= 1", fmt::format("{}", o.application_factor));
  if (!std::isfinite(o.youngs_modulus_pinion_pa) || o.youngs_modulus_pinion_pa <= 0.0)
    fail(g, "youngs_modulus_pinion", "E1 > 0 Pa", fmt::format("{}", o.youngs_modulus_pinion_pa));
  if (!std::isfinite(o.youngs_modulus_wheel_pa) || o.youngs_modulus_wheel_pa <= 0.0)
    fail(g, "youngs_modulus_wheel", "E2 > 0 Pa", fmt::format("{}", o.youngs_modulus_wheel_pa));

  const double zn1 = g.pinion.normal_virtual_teeth;
  const double zn2 = g.wheel.normal_virtual_teeth;  // inf for an internal gear: terms vanish
  const double x1 = g.pinion.profile_shift;
  const double x2 = g.wheel.profile_shift;
  s.normal_virtual_teeth_pinion = zn1;
  s.normal_virtual_teeth_wheel = zn2;
  s.flexibility_q_prime = kC1 + kC2 / zn1 + kC3 / zn2 + kC4 * x1 + kC5 * x1 / zn1 + kC6 * x2 +
                          kC7 * x2 / zn2 + kC8 * x1 * x1 + kC9 * x2 * x2;
  if (!(s.flexibility_q_prime > 0.0))
    fail(g, "profile_shift_pinion", "profile shifts inside ISO 6336-1's q' series range",
         fmt::format("q' = {} mm·µm/N", s.flexibility_q_prime));
  s.theoretical_single_stiffness = 1.0 / s.flexibility_q_prime;
  s.correction_factor = o.correction_factor;

  // Gear blank factor C_R (solid disc unless both thicknesses are given).
  const bool has_rim = !std::isnan(o.rim_thickness_m);
  const bool has_web = !std::isnan(o.web_thickness_m);
  if (has_rim != has_web)
    fail(g, has_rim ? "web_thickness" : "rim_thickness",
         "both rim and web thickness (gear blank with a web) or neither (solid disc)", "one only");
  s.blank_factor = 1.0;
  if (has_rim) {
    const double bs_b = o.web_thickness_m / g.face_width_m;
    const double sr_m = o.rim_thickness_m / g.normal_module_m;
    if (!std::isfinite(bs_b) || bs_b < 0.2 || bs_b > 1.2)
      fail(g, "web_thickness", "b_s / b in [0.2, 1.2] (ISO 6336-1 range)", fmt::format("{}", bs_b),
           "ISO limits b_s/b to this range; give the limit if intended");
    if (!std::isfinite(sr_m) || sr_m < 1.0)
      fail(g, "rim_thickness", "s_R / m_n >= 1 (ISO 6336-1 range)", fmt::format("{}", sr_m),
           "ISO limits s_R/m_n to >= 1; give the limit if intended");
    s.blank_factor = 1.0 + std::log(bs_b) / (5.0 * std::exp(sr_m / 5.0));
  }

  // Basic rack factor; both members are cut by the same rack here, so C_B = C_B1 = C_B2.
  const double alpha_pn_deg = g.normal_pressure_angle_rad * 180.0 / units::kPi;
  s.basic_rack_factor =
      (1.0 + 0.5 * (1.2 - g.spec.dedendum_coefficient)) * (1.0 - 0.02 * (20.0 - alpha_pn_deg));
  s.helix_factor = std::cos(g.helix_angle_rad);
  const double e1 = o.youngs_modulus_pinion_pa, e2 = o.youngs_modulus_wheel_pa;
  s.material_factor = 2.0 * e1 * e2 / (e1 + e2) / kSteelModulusPa;

  s.load_factor = 1.0;
  if (!std::isnan(o.tangential_force_n)) {
    if (!std::isfinite(o.tangential_force_n) || o.tangential_force_n <= 0.0)
      fail(g, "tangential_force", "F_t > 0 N (or NaN for no load correction)",
           fmt::format("{}", o.tangential_force_n));
    const double line_load = o.tangential_force_n * o.application_factor / (g.face_width_m * 1e3);
    if (line_load < kReferenceLineLoadNPerMm)
      s.load_factor = std::pow(line_load / kReferenceLineLoadNPerMm, 0.25);
  }
  s.single_stiffness = s.theoretical_single_stiffness * s.correction_factor * s.blank_factor *
                       s.basic_rack_factor * s.helix_factor * s.material_factor * s.load_factor;
  s.mesh_stiffness_alpha = s.single_stiffness * (0.75 * g.transverse_contact_ratio + 0.25);
  s.mesh_stiffness_beta = 0.85 * s.mesh_stiffness_alpha;
  s.single_stiffness_n_per_m = s.single_stiffness * kIsoUnitToSi * g.face_width_m;
  s.mesh_stiffness_n_per_m = s.mesh_stiffness_alpha * kIsoUnitToSi * g.face_width_m;
  return s;
}

MeshStiffnessCurve time_varying_mesh_stiffness(const GearPairGeometry& g,
                                               const MeshStiffnessOptions& o) {
  if (o.samples < 16)
    fail(g, "samples", "at least 16 samples per mesh cycle", std::to_string(o.samples));
  MeshStiffnessCurve c;
  c.iso = iso_mesh_stiffness(g, o.iso);
  const double p = g.transverse_base_pitch_m;
  const double path = g.path_of_contact_m;
  const double ramp = std::min((g.transverse_contact_ratio - 1.0) * p, 0.5 * path);
  c.double_zone_length_m = ramp;
  c.mesh_period_rad = units::kTwoPi / g.pinion.teeth;
  const PairLaw law(path, ramp);
  const double b = g.face_width_m;
  // Path-coordinate lag of the trailing face end behind the leading one.
  const double lag = b * std::tan(g.base_helix_angle_rad);
  const bool spur_like = lag <= 1e-12 * path;
  const double c_si = c.iso.single_stiffness * kIsoUnitToSi;  // N/m per metre of face width

  const int n = o.samples;
  c.mesh_fraction.resize(n);
  c.pinion_angle_rad.resize(n);
  c.stiffness_n_per_m.resize(n);
  c.pairs_in_contact.resize(n);
  for (int j = 0; j < n; ++j) {
    const double u = static_cast<double>(j) / n;
    double k = 0.0, pairs = 0.0;
    for (int m = 0;; ++m) {
      const double s0 = (u + m) * p;  // leading face end of the pair that entered m cycles ago
      if (s0 - lag >= path) break;
      if (spur_like) {
        const double f = law.value(s0);
        k += b * f;
        pairs += f > 0.0 ? 1.0 : 0.0;
      } else {
        k += (law.primitive(s0) - law.primitive(s0 - lag)) / std::tan(g.base_helix_angle_rad);
        pairs += (std::clamp(s0, 0.0, path) - std::clamp(s0 - lag, 0.0, path)) / lag;
      }
    }
    c.mesh_fraction[j] = u;
    c.pinion_angle_rad[j] = u * c.mesh_period_rad;
    c.stiffness_n_per_m[j] = c_si * k;
    c.pairs_in_contact[j] = pairs;
  }
  double sum = 0.0;
  c.min_stiffness_n_per_m = c.stiffness_n_per_m.front();
  c.max_stiffness_n_per_m = c.stiffness_n_per_m.front();
  for (double k : c.stiffness_n_per_m) {
    sum += k;
    c.min_stiffness_n_per_m = std::min(c.min_stiffness_n_per_m, k);
    c.max_stiffness_n_per_m = std::max(c.max_stiffness_n_per_m, k);
  }
  c.mean_stiffness_n_per_m = sum / n;
  return c;
}

SyntheticSte synthetic_ste(const MeshStiffnessCurve& curve, const GearPairGeometry& g,
                           double pinion_torque_nm) {
  if (!std::isfinite(pinion_torque_nm) || pinion_torque_nm <= 0.0)
    fail(g, "pinion_torque", "a finite pinion torque > 0 N·m", fmt::format("{}", pinion_torque_nm));
  SyntheticSte e;
  e.base_radius_m = g.pinion.mean_pitch_radius_m * std::cos(g.transverse_pressure_angle_rad);
  e.static_force_n = pinion_torque_nm / e.base_radius_m;
  e.pinion_angle_rad = curve.pinion_angle_rad;
  const std::size_t n = curve.stiffness_n_per_m.size();
  e.ste_m.resize(n);
  e.ste_rad.resize(n);
  double sum = 0.0;
  for (std::size_t j = 0; j < n; ++j) {
    e.ste_m[j] = e.static_force_n / curve.stiffness_n_per_m[j];
    e.ste_rad[j] = e.ste_m[j] / e.base_radius_m;
    sum += e.ste_m[j];
  }
  e.mean_ste_m = n > 0 ? sum / static_cast<double>(n) : 0.0;
  return e;
}

Table mesh_stiffness_table(const MeshStiffnessCurve& curve, const SyntheticSte* ste) {
  Table t;
  t.name = "mesh_stiffness";
  t.title = "Time-varying mesh stiffness over one mesh cycle (sample 0: tooth entering contact)";
  t.add("mesh_fraction", "", curve.mesh_fraction);
  t.add("pinion_angle_rad", "rad", curve.pinion_angle_rad);
  t.add("stiffness_n_per_m", "N/m", curve.stiffness_n_per_m);
  t.add("pairs_in_contact", "", curve.pairs_in_contact);
  if (ste != nullptr) {
    if (ste->ste_m.size() != curve.stiffness_n_per_m.size())
      throw std::invalid_argument("mesh_stiffness_table: STE and stiffness lengths differ");
    t.add("ste_m", "m", ste->ste_m);
    t.add("ste_rad", "rad", ste->ste_rad);
  }
  return t;
}

}  // namespace geardyn::gear
