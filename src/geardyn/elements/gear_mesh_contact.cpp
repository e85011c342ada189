#include "geardyn/elements/gear_mesh_contact.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cassert>
#include <cmath>
#include <utility>

#include "geardyn/elements/parameter_check.hpp"

namespace geardyn::elements {

namespace {

using detail::format_number;

// The contact law clipped its force to zero (Tension::clipped): no force, no tangents.
bool clipped_to_zero(const ContactForce& f) {
  return f.force == 0.0 && f.d_penetration == 0.0 && f.d_rate == 0.0;
}

void check_sizes(const MeshForceMap& m, const detail::ParameterCheck& c) {
  if (!(std::isfinite(m.period_rad) && m.period_rad > 0.0))
    c.fail("gear_pair", "a force map over a pinion-angle period > 0 [rad]", m.period_rad);
  if (m.mesh_cycles < 1)
    c.fail("gear_pair", "a force map over >= 1 mesh cycle", static_cast<double>(m.mesh_cycles));
  if (m.unloaded_te_m.empty()) c.fail("gear_pair", "a force map with >= 1 angle", "none");
  if (m.forces_n.empty()) c.fail("gear_pair", "a force map with >= 1 force", "none");
  if (m.approach_m.size() != m.forces_n.size())
    c.fail("gear_pair", fmt::format("{} approach curves (one per force)", m.forces_n.size()),
           std::to_string(m.approach_m.size()));
  for (const auto& d : m.approach_m)
    if (d.size() != m.unloaded_te_m.size())
      c.fail("gear_pair",
             fmt::format("{} approaches per force (one per angle)", m.unloaded_te_m.size()),
             std::to_string(d.size()));
  if (m.reference < 0 || m.reference >= static_cast<int>(m.forces_n.size()))
    c.fail("gear_pair", "a reference force index of the map", static_cast<double>(m.reference));
}

}  // namespace

// ---- MeshForceMap -------------------------------------------------------------------------

MeshForceMap MeshForceMap::constant_stiffness(double stiffness_n_per_m, double period_rad) {
  MeshForceMap m;
  m.period_rad = period_rad;
  m.unloaded_te_m = {0.0};
  m.forces_n = {1.0};
  m.approach_m = {{1.0 / stiffness_n_per_m}};
  m.source = "constant stiffness " + format_number(stiffness_n_per_m) + " N/m";
  return m;
}

double MeshForceMap::stiffness_at_node(int i) const {
  const auto j = static_cast<std::size_t>(reference);
  const auto k = static_cast<std::size_t>(i);
  return forces_n[j] / (approach_m[j][k] - unloaded_te_m[k]);
}

double MeshForceMap::mean_stiffness() const {
  double sum = 0.0;
  for (int i = 0; i < angles(); ++i) sum += stiffness_at_node(i);
  return sum / angles();
}

void check_mesh_force_map(const MeshForceMap& m, const LawSource& source) {
  const detail::ParameterCheck c(source.location, source.key_path);
  check_sizes(m, c);
  for (std::size_t j = 0; j < m.forces_n.size(); ++j) {
    const double f = m.forces_n[j];
    const double below = j == 0 ? 0.0 : m.forces_n[j - 1];
    if (!(std::isfinite(f) && f > below))
      c.fail("gear_pair", "map forces > 0 and increasing [N]",
             fmt::format("F_{} = {} after {}", j, format_number(f), format_number(below)));
  }
  for (std::size_t i = 0; i < m.unloaded_te_m.size(); ++i) {
    double below = m.unloaded_te_m[i];
    if (!std::isfinite(below))
      c.fail("gear_pair", "a finite unloaded TE [m]", fmt::format("{} at angle {}", below, i));
    for (std::size_t j = 0; j < m.forces_n.size(); ++j) {
      const double d = m.approach_m[j][i];
      if (!(std::isfinite(d) && d > below))
        c.fail("gear_pair",
               "a monotone force-approach law: approaches increasing with the force, above the "
               "unloaded TE",
               fmt::format("d_{} = {} m after {} m at angle {} ({} rad)", j, format_number(d),
                           format_number(below), i, format_number(m.angle(static_cast<int>(i)))));
      below = d;
    }
  }
}

ToothFriction spur_tooth_friction(double coefficient, double velocity, double base_radius1,
                                  double base_radius2, double tip_radius1, double tip_radius2,
                                  double centre_distance) {
  ToothFriction f;
  f.coefficient = coefficient;
  f.velocity = velocity;
  f.base_radius1 = base_radius1;
  const double tan_alpha =
      std::tan(std::acos(std::min(1.0, (base_radius1 + base_radius2) / centre_distance)));
  f.pitch_arm1 = base_radius1 * tan_alpha;
  f.pitch_arm2 = base_radius2 * tan_alpha;
  const double g_a =
      std::sqrt(tip_radius1 * tip_radius1 - base_radius1 * base_radius1) - f.pitch_arm1;
  const double g_f =
      std::sqrt(tip_radius2 * tip_radius2 - base_radius2 * base_radius2) - f.pitch_arm2;
  f.path_start = -g_f;
  f.path_length = g_f + g_a;
  return f;
}

// ---- GearMeshContact ----------------------------------------------------------------------

GearMeshContact::GearMeshContact(std::string name, std::shared_ptr<const MeshForceMap> map,
                                 GearMeshContactOptions options, const LawSource& source)
    : name_(std::move(name)), map_(std::move(map)), options_(std::move(options)) {
  const detail::ParameterCheck c(source.location, source.key_path);
  if (!map_) c.fail("gear_pair", "a force map", "none");
  check_mesh_force_map(*map_, source);
  if (!std::isnan(options_.backlash))
    c.non_negative("backlash", options_.backlash,
                   "the total backlash along the line of action [m]");
  c.non_negative("damping", options_.damping);
  const ToothFriction& fr = options_.friction;
  c.non_negative("friction", fr.coefficient);
  if (fr.coefficient > 0.0) {
    c.positive("friction_velocity", fr.velocity,
               "a small sliding speed of the smoothed sign [m/s]");
    c.positive("gear_pair", fr.base_radius1, "the pinion's base radius for tooth friction [m]");
    c.require(std::isfinite(fr.pitch_arm1) && fr.pitch_arm1 > 0.0 && std::isfinite(fr.pitch_arm2) &&
                  fr.pitch_arm2 > 0.0,
              "gear_pair", "arms r_b tan(alpha_w) > 0 at the pitch point for tooth friction [m]",
              std::min(fr.pitch_arm1, fr.pitch_arm2));
    c.require(
        std::isfinite(fr.path_start) && fr.path_start <= 0.0 && -fr.path_start < fr.pitch_arm1,
        "gear_pair",
        "a path of contact starting between the pinion's base circle tangent "
        "point and the pitch point (s_A <= 0) [m]",
        fr.path_start);
    c.require(std::isfinite(fr.path_length) && fr.path_length > 0.0 &&
                  fr.path_start + fr.path_length < fr.pitch_arm2,
              "gear_pair",
              "a path of contact of length > 0 ending before the wheel's base "
              "circle tangent point [m]",
              fr.path_length);
    c.finite("friction_phase", fr.phase);
  }
  const double mean = map_->mean_stiffness();
  ratio_.resize(static_cast<std::size_t>(map_->angles()));
  for (int i = 0; i < map_->angles(); ++i)
    ratio_[static_cast<std::size_t>(i)] = map_->stiffness_at_node(i) / mean;
}

bool GearMeshContact::has_backlash() const { return !std::isnan(options_.backlash); }

GearMeshContact::Grid GearMeshContact::locate(double theta1) const {
  const int n = map_->angles();
  const double x = theta1 / map_->period_rad;
  const double s = (x - std::floor(x)) * n;  // in [0, n], n only by rounding
  Grid g;
  g.i0 = static_cast<int>(std::floor(s));
  g.w = s - g.i0;
  if (g.i0 >= n) {
    g.i0 = 0;
    g.w = 0.0;
  } else if (g.i0 < 0) {
    g.i0 = 0;
  }
  g.i1 = (g.i0 + 1) % n;
  g.inv_h = n / map_->period_rad;
  return g;
}

double GearMeshContact::unloaded_te(double theta1) const {
  const Grid g = locate(theta1);
  const auto& e = map_->unloaded_te_m;
  return (1.0 - g.w) * e[static_cast<std::size_t>(g.i0)] + g.w * e[static_cast<std::size_t>(g.i1)];
}

double GearMeshContact::stiffness_ratio(double theta1) const {
  const Grid g = locate(theta1);
  return (1.0 - g.w) * ratio_[static_cast<std::size_t>(g.i0)] +
         g.w * ratio_[static_cast<std::size_t>(g.i1)];
}

double GearMeshContact::penetration(const Eigen::VectorXd& u) const {
  return u(0) - unloaded_te(u(1));
}

double GearMeshContact::back_penetration(const Eigen::VectorXd& u) const {
  if (!has_backlash()) return -std::numeric_limits<double>::infinity();
  return -penetration(u) - options_.backlash;
}

MeshContactState GearMeshContact::state(const Eigen::VectorXd& u) const {
  if (penetration(u) > 0.0) return MeshContactState::drive;
  if (back_penetration(u) > 0.0) return MeshContactState::back;
  return MeshContactState::separated;
}

double GearMeshContact::static_force(const Eigen::VectorXd& u) const {
  ElementForce out;
  evaluate(u, Eigen::VectorXd::Zero(size()), 0.0, out);
  return out.force(0);
}

void GearMeshContact::node_law(int i, double p, double& force, double& slope) const {
  const auto k = static_cast<std::size_t>(i);
  const double eg = map_->unloaded_te_m[k];
  double a_prev = 0.0, f_prev = 0.0;
  const std::size_t m = map_->forces_n.size();
  for (std::size_t j = 0; j < m; ++j) {
    const double a = map_->approach_m[j][k] - eg;
    const double f = map_->forces_n[j];
    if (p <= a || j + 1 == m) {  // this segment, or the last one extrapolated
      slope = (f - f_prev) / (a - a_prev);
      force = f_prev + slope * (p - a_prev);
      return;
    }
    a_prev = a;
    f_prev = f;
  }
}

GearMeshContact::FlankForce GearMeshContact::flank(const Grid& g, double p, double p_dot) const {
  FlankForce r;
  if (!options_.law) {
    double f0 = 0.0, s0 = 0.0, f1 = 0.0, s1 = 0.0;
    node_law(g.i0, p, f0, s0);
    node_law(g.i1, p, f1, s1);
    r.force = (1.0 - g.w) * f0 + g.w * f1 + options_.damping * p_dot;
    if (options_.tension == Tension::clipped && r.force < 0.0) return FlankForce{};
    r.d_p = (1.0 - g.w) * s0 + g.w * s1;
    r.d_rate = options_.damping;
    r.d_theta = (f1 - f0) * g.inv_h;
    return r;
  }
  const ContactForce f = options_.law->evaluate(p, p_dot);
  if (!options_.vary_stiffness) return {f.force, f.d_penetration, f.d_rate, 0.0};
  if (clipped_to_zero(f)) return r;
  const ContactForce elastic = options_.law->evaluate(p, 0.0);
  const double r0 = ratio_[static_cast<std::size_t>(g.i0)];
  const double r1 = ratio_[static_cast<std::size_t>(g.i1)];
  const double s = (1.0 - g.w) * r0 + g.w * r1;
  r.force = f.force + (s - 1.0) * elastic.force;
  r.d_p = f.d_penetration + (s - 1.0) * elastic.d_penetration;
  r.d_rate = f.d_rate;
  r.d_theta = (r1 - r0) * g.inv_h * elastic.force;
  return r;
}

void GearMeshContact::evaluate(const Eigen::VectorXd& u, const Eigen::VectorXd& v, double,
                               ElementForce& out) const {
  assert(u.size() == size() && v.size() == size());
  out.reset(size());
  const Grid g = locate(u(1));
  const auto& e = map_->unloaded_te_m;
  const double e0 = e[static_cast<std::size_t>(g.i0)], e1 = e[static_cast<std::size_t>(g.i1)];
  const double eg = (1.0 - g.w) * e0 + g.w * e1;
  const double deg = (e1 - e0) * g.inv_h;  // e_g' [m/rad]; e_g'' = 0 inside a grid interval
  const double p = u(0) - eg;
  const double p_dot = v(0) - deg * v(1);
  if (p > 0.0) {
    const FlankForce f = flank(g, p, p_dot);
    out.force(0) = f.force;
    out.stiffness(0, 0) = f.d_p;
    out.stiffness(0, 1) = f.d_theta - f.d_p * deg;
    out.damping(0, 0) = f.d_rate;
    out.damping(0, 1) = -f.d_rate * deg;
    if (has_friction()) add_friction(u, v, out);
  } else if (has_backlash() && -p - options_.backlash > 0.0) {
    // p_b = -p - b, p_b_dot = -p_dot; force -F on delta.
    const FlankForce f = flank(g, -p - options_.backlash, -p_dot);
    out.force(0) = -f.force;
    out.stiffness(0, 0) = f.d_p;
    out.stiffness(0, 1) = -f.d_theta - f.d_p * deg;
    out.damping(0, 0) = f.d_rate;
    out.damping(0, 1) = -f.d_rate * deg;
  }
}

std::vector<ToothPairContact> GearMeshContact::pairs(double theta1) const {
  std::vector<ToothPairContact> out;
  if (!has_friction()) return out;
  const ToothFriction& fr = options_.friction;
  const double pitch_angle = map_->period_rad / map_->mesh_cycles;  // one base pitch of theta1
  const double base_pitch = fr.base_radius1 * pitch_angle;
  const double x = (theta1 - fr.phase) / pitch_angle;
  const double end = fr.path_start + fr.path_length;
  // The newest pair entered at s_A; each older one is a base pitch further along the path.
  for (double s = fr.path_start + (x - std::floor(x)) * base_pitch; s < end; s += base_pitch)
    out.push_back({s, 0.0});
  for (ToothPairContact& pair : out) pair.share = 1.0 / static_cast<double>(out.size());
  return out;
}

void GearMeshContact::add_friction(const Eigen::VectorXd& u, const Eigen::VectorXd& v,
                                   ElementForce& out) const {
  const double normal = out.force(0);
  if (!(normal > 0.0)) return;  // a tension (damping-only) force carries no friction
  const ToothFriction& fr = options_.friction;
  const double rb1 = fr.base_radius1;
  const Eigen::RowVectorXd dn_du = out.stiffness.row(0), dn_dv = out.damping.row(0);
  for (const ToothPairContact& pair : pairs(u(1))) {
    // Generalised direction a = d v_s / d v = (0, rho1, -rho2, -1); d a / d theta1 =
    // (0, r_b1, r_b1, 0) since ds / d theta1 = r_b1.
    Eigen::Vector4d a(0.0, fr.pitch_arm1 + pair.s, -(fr.pitch_arm2 - pair.s), -1.0);
    const Eigen::Vector4d da(0.0, rb1, rb1, 0.0);
    const double vs = a.dot(v);
    const double sigma = std::tanh(vs / fr.velocity);
    const double dsigma = (1.0 - sigma * sigma) / fr.velocity;
    const double dvs_dtheta = da.dot(v);  // r_b1 (theta1_dot + theta2_dot)
    const double g = fr.coefficient * pair.share;
    for (int i = 1; i < 4; ++i) {
      out.force(i) += g * normal * sigma * a(i);
      out.stiffness.row(i) += g * sigma * a(i) * dn_du;
      out.stiffness(i, 1) += g * normal * (dsigma * dvs_dtheta * a(i) + sigma * da(i));
      out.damping.row(i) += g * sigma * a(i) * dn_dv;
      for (int j = 0; j < 4; ++j) out.damping(i, j) += g * normal * dsigma * a(j) * a(i);
    }
  }
}

std::string GearMeshContact::describe() const {
  const MeshForceMap& m = *map_;
  std::string law =
      options_.law
          ? options_.law->describe() +
                (options_.vary_stiffness ? ", stiffness scaled by k(theta) / mean k" : "")
          : fmt::format("map force-approach law, c = {} N s/m{}", format_number(options_.damping),
                        options_.tension == Tension::clipped ? ", clipped at 0" : "");
  return fmt::format("gear mesh '{}' ({}; {} angles x {} forces over {} rad; {}; {})", name_,
                     m.source, m.angles(), m.forces_n.size(), format_number(m.period_rad),
                     has_backlash() ? "backlash " + format_number(options_.backlash) + " m"
                                    : "no back flank",
                     law) +
         (has_friction() ? fmt::format(", tooth friction mu = {} (v_eps = {} m/s)",
                                       format_number(options_.friction.coefficient),
                                       format_number(options_.friction.velocity))
                         : std::string());
}

void GearMeshContact::switches(const Eigen::VectorXd& u, double, double* g) const {
  g[0] = penetration(u);
  if (has_backlash()) g[1] = back_penetration(u);
}

std::string GearMeshContact::describe_switch(int k) const {
  return k == 0 ? "drive flank" : "back flank";
}

}  // namespace geardyn::elements
