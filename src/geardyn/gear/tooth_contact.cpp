#include "geardyn/gear/tooth_contact.hpp"

#include <fmt/format.h>

#include <Eigen/LU>
#include <algorithm>
#include <cmath>
#include <complex>
#include <numeric>
#include <utility>

#include "geardyn/core/error.hpp"
#include "geardyn/core/units.hpp"

namespace geardyn::gear {

namespace {

[[noreturn]] void fail(const GearPairGeometry& g, const std::string& field, std::string expected,
                       std::string found, std::string hint = {}) {
  throw InputError(g.spec.where, g.spec.key_path + "." + field, std::move(expected),
                   std::move(found), std::move(hint));
}

std::string num(double v) { return fmt::format("{:.6g}", v); }

double shape_power(ReliefShape s) { return s == ReliefShape::Parabolic ? 2.0 : 1.0; }

// Index of the last grid value <= x (clamped to [0, n-2]) and the fraction beyond it in [0, 1].
std::pair<std::size_t, double> bracket(const std::vector<double>& grid, double x) {
  if (x <= grid.front()) return {0, 0.0};
  if (x >= grid.back()) return {grid.size() - 2, 1.0};
  const auto it = std::upper_bound(grid.begin(), grid.end(), x);
  const std::size_t i = static_cast<std::size_t>(it - grid.begin()) - 1;
  return {i, (x - grid[i]) / (grid[i + 1] - grid[i])};
}

// One candidate contact point at a mesh position.
struct Candidate {
  int pair = 0;
  int slice = 0;
  double s = 0.0, y = 0.0, g = 0.0;
};

// The contact problem at one mesh position (header): unknowns w (candidates) and delta.
class PositionSolver {
 public:
  PositionSolver(const std::vector<Candidate>& c, const Eigen::MatrixXd& a,
                 const ContactCompliance& compliance, double force, double dy,
                 const ToothContactOptions& options)
      : c_(c), a_(a), compliance_(compliance), force_(force), dy_(dy), options_(options) {
    const Eigen::Index n = a.rows();
    w_floor_ = 1e-9 * force / (dy * static_cast<double>(n));
    // Residuals are lengths: scaled by the larger of the elastic approach and the gaps.
    scale_ = a.diagonal().maxCoeff() * force / (dy * static_cast<double>(n));
    for (const auto& ci : c) scale_ = std::max(scale_, std::abs(ci.g));
    // Loads follow from approach differences divided by the compliance: with very stiff teeth
    // (gaps >> elastic approach) double precision bounds how well the force balance can hold.
    const double wbar = force / (dy * static_cast<double>(n));
    force_tolerance_ = std::max(options.tolerance, 64.0 * std::numeric_limits<double>::epsilon() *
                                                       scale_ / (a.diagonal().minCoeff() * wbar));
  }

  // Returns false (and sets message) when the iterations do not converge.
  bool solve(std::string& message) {
    const Eigen::Index n = a_.rows();
    active_.assign(static_cast<std::size_t>(n), true);
    w_ = Eigen::VectorXd::Constant(n, force_ / (dy_ * static_cast<double>(n)));
    for (int outer = 0; outer < options_.max_iterations; ++outer) {
      if (!newton(message)) return false;
      // Drop loads that came out negative (all of them at first, the worst one later on).
      const bool single = outer > 20;
      Eigen::Index worst = -1;
      int changed = 0;
      for (Eigen::Index i = 0; i < n; ++i) {
        if (!active_[static_cast<std::size_t>(i)] || w_(i) >= 0.0) continue;
        if (worst < 0 || w_(i) < w_(worst)) worst = i;
        if (!single) active_[static_cast<std::size_t>(i)] = false, w_(i) = 0.0, ++changed;
      }
      if (single && worst >= 0) active_[static_cast<std::size_t>(worst)] = false, w_(worst) = 0.0;
      if (worst >= 0) continue;
      // Add open points that penetrate.
      const Eigen::VectorXd body = a_ * w_;
      worst = -1;
      double worst_gap = -options_.tolerance * scale_;
      for (Eigen::Index i = 0; i < n; ++i) {
        if (active_[static_cast<std::size_t>(i)]) continue;
        const double d = body(i) + c_[static_cast<std::size_t>(i)].g - delta_;
        if (d < -options_.tolerance * scale_ && !single) {
          active_[static_cast<std::size_t>(i)] = true;
          ++changed;
        }
        if (d < worst_gap) worst_gap = d, worst = i;
      }
      if (single && worst >= 0) active_[static_cast<std::size_t>(worst)] = true, ++changed;
      if (changed == 0) return tangent(message);
    }
    message =
        fmt::format("the contact set did not settle in {} iterations", options_.max_iterations);
    return false;
  }

  const Eigen::VectorXd& loads() const { return w_; }
  double approach() const { return delta_; }
  double tangent_stiffness() const { return tangent_; }

 private:
  double hertz(std::size_t i, double w, double& slope) const {
    const double s = c_[i].s;
    if (w >= w_floor_) {
      slope = compliance_.hertz_compliance(s, w);
      return compliance_.hertz_approach(s, w);
    }
    slope = compliance_.hertz_compliance(s, w_floor_);
    return compliance_.hertz_approach(s, w_floor_) + slope * (w - w_floor_);
  }

  std::vector<Eigen::Index> active_indices() const {
    std::vector<Eigen::Index> idx;
    for (std::size_t i = 0; i < active_.size(); ++i)
      if (active_[i]) idx.push_back(static_cast<Eigen::Index>(i));
    return idx;
  }

  // Residual and Jacobian on the active set; returns the residual's max norm (scaled).
  double assemble(const std::vector<Eigen::Index>& idx, Eigen::VectorXd& r, Eigen::MatrixXd* j) {
    const Eigen::Index m = static_cast<Eigen::Index>(idx.size());
    r.resize(m + 1);
    if (j) j->setZero(m + 1, m + 1);
    double sum = 0.0;
    for (Eigen::Index p = 0; p < m; ++p) {
      const Eigen::Index i = idx[static_cast<std::size_t>(p)];
      double body = 0.0;
      for (Eigen::Index q = 0; q < m; ++q) {
        const Eigen::Index k = idx[static_cast<std::size_t>(q)];
        body += a_(i, k) * w_(k);
        if (j) (*j)(p, q) = a_(i, k);
      }
      double slope = 0.0;
      const double h = hertz(static_cast<std::size_t>(i), w_(i), slope);
      r(p) = body + h + c_[static_cast<std::size_t>(i)].g - delta_;
      if (j) {
        (*j)(p, p) += slope;
        (*j)(p, m) = -1.0;
        (*j)(m, p) = dy_;
      }
      sum += w_(i);
    }
    r(m) = dy_ * sum - force_;
    // Scaled so that 1 means "at the tolerance".
    return std::max(r.head(m).lpNorm<Eigen::Infinity>() / scale_,
                    std::abs(r(m)) / force_ * options_.tolerance / force_tolerance_);
  }

  // Solves j x = rhs with the rows made dimensionless (lengths by scale_, the force balance by
  // F) and the unknowns too (loads by the mean line load, delta by scale_): the compliances
  // can be tiny next to the -1 of delta (stiff teeth), which unscaled loses every digit.
  Eigen::VectorXd scaled_solve(const Eigen::MatrixXd& j, const Eigen::VectorXd& rhs,
                               Eigen::Index m) const {
    const double wbar = force_ / (dy_ * static_cast<double>(a_.rows()));
    Eigen::VectorXd row = Eigen::VectorXd::Constant(m + 1, 1.0 / scale_);
    row(m) = 1.0 / force_;
    Eigen::VectorXd col = Eigen::VectorXd::Constant(m + 1, wbar);
    col(m) = scale_;
    const Eigen::MatrixXd js = row.asDiagonal() * j * col.asDiagonal();
    const Eigen::VectorXd x = Eigen::PartialPivLU<Eigen::MatrixXd>(js).solve(row.cwiseProduct(rhs));
    return col.cwiseProduct(x);
  }

  bool newton(std::string& message) {
    const auto idx = active_indices();
    if (idx.empty()) {
      message =
          "no slice left in contact (the modifications or the misalignment open every "
          "gap beyond what the load closes)";
      return false;
    }
    const Eigen::Index m = static_cast<Eigen::Index>(idx.size());
    // Start delta at the mean approach the current loads need.
    {
      delta_ = 0.0;
      Eigen::VectorXd r;
      assemble(idx, r, nullptr);
      delta_ = r.head(m).mean();
    }
    Eigen::VectorXd r;
    Eigen::MatrixXd j;
    double norm = assemble(idx, r, &j);
    for (int it = 0; it < 60; ++it) {
      if (norm <= options_.tolerance) return true;
      const Eigen::VectorXd step = scaled_solve(j, -r, m);
      if (!step.allFinite()) break;
      const Eigen::VectorXd w0 = w_;
      const double d0 = delta_;
      double t = 1.0, trial = 0.0;
      for (int ls = 0; ls < 30; ++ls, t *= 0.5) {
        for (Eigen::Index p = 0; p < m; ++p)
          w_(idx[static_cast<std::size_t>(p)]) = w0(idx[static_cast<std::size_t>(p)]) + t * step(p);
        delta_ = d0 + t * step(m);
        trial = assemble(idx, r, &j);
        if (trial < norm || trial <= options_.tolerance) break;
      }
      norm = trial;
    }
    if (norm <= options_.tolerance) return true;
    message = fmt::format(
        "Newton's method on the contact equations stalled at a residual of "
        "{:.3g} (relative)",
        norm);
    return false;
  }

  // Tangent stiffness dF / d delta with the contact set frozen.
  bool tangent(std::string& message) {
    const auto idx = active_indices();
    const Eigen::Index m = static_cast<Eigen::Index>(idx.size());
    Eigen::VectorXd r;
    Eigen::MatrixXd j;
    assemble(idx, r, &j);
    Eigen::VectorXd rhs = Eigen::VectorXd::Zero(m + 1);
    rhs(m) = 1.0;
    const Eigen::VectorXd d = scaled_solve(j, rhs, m);
    if (!(d(m) > 0.0) || !std::isfinite(d(m))) {
      message = "the tangent mesh stiffness is not positive (singular contact equations)";
      return false;
    }
    tangent_ = 1.0 / d(m);
    return true;
  }

  const std::vector<Candidate>& c_;
  const Eigen::MatrixXd& a_;
  const ContactCompliance& compliance_;
  double force_, dy_;
  const ToothContactOptions& options_;
  double w_floor_ = 0.0, scale_ = 1.0, force_tolerance_ = 0.0;
  std::vector<bool> active_;
  Eigen::VectorXd w_;
  double delta_ = 0.0, tangent_ = 0.0;
};

}  // namespace

double TopographyMap::at(double roll_angle, double y) const {
  if (empty()) return 0.0;
  const auto [i, fi] = bracket(roll_angle_rad, roll_angle);
  const auto [k, fk] = bracket(face_m, y);
  const auto ii = static_cast<Eigen::Index>(i), kk = static_cast<Eigen::Index>(k);
  return (1 - fi) * ((1 - fk) * removed_m(ii, kk) + fk * removed_m(ii, kk + 1)) +
         fi * ((1 - fk) * removed_m(ii + 1, kk) + fk * removed_m(ii + 1, kk + 1));
}

ToothContact::ToothContact(const GearPairGeometry& geometry, FlankModification pinion,
                           FlankModification wheel, const ContactCompliance& compliance,
                           ToothContactOptions options)
    : geometry_(geometry),
      pinion_(std::move(pinion)),
      wheel_(std::move(wheel)),
      compliance_(&compliance),
      options_(options) {
  setup_bevel(geometry);
  const auto& g = geometry_;
  if (options_.positions < 4)
    fail(g, "contact.positions", "at least 4 mesh positions per cycle",
         std::to_string(options_.positions));
  if (options_.slices < 1)
    fail(g, "contact.slices", "at least 1 slice", std::to_string(options_.slices));
  internal_ = g.spec.mesh == MeshType::Internal;
  const double rb1 = g.pinion.base_radius_m, rb2 = g.wheel.base_radius_m;
  const double g1 = std::sqrt(g.pinion.tip_radius_m * g.pinion.tip_radius_m - rb1 * rb1);
  const double g2 = std::sqrt(g.wheel.tip_radius_m * g.wheel.tip_radius_m - rb2 * rb2);
  t1t2_ = g.centre_distance_m * std::sin(g.working_pressure_angle_rad);
  rho1_a_ = internal_ ? g2 - t1t2_ : t1t2_ - g2;
  rho1_low_ = rho1_a_;
  rho1_high_ = rho1_a_ + g.path_of_contact_m;  // = g1: the pinion tip
  (void)g1;
  rho2_low_ = wheel_roll_length(g.path_of_contact_m);
  rho2_high_ = wheel_roll_length(0.0);
  if (internal_) std::swap(rho2_low_, rho2_high_);

  auto check_mod = [&](const FlankModification& m, const char* member, const GearGeometry& gg,
                       double rho_root, double rho_tip) {
    const std::string p = std::string("flank") + member + ".";
    // Errors at the flank's table when it was read from one.
    GearPairGeometry at = g;
    if (m.where.line > 0) at.spec.where = m.where;
    auto rho_of = [&](double r) {
      return std::sqrt(std::max(0.0, r * r - gg.base_radius_m * gg.base_radius_m));
    };
    auto within = [&](double r, const char* key) {
      if (std::isnan(r)) return;
      const double rho = rho_of(r);
      const double lo = std::min(rho_root, rho_tip), hi = std::max(rho_root, rho_tip);
      if (!(r > gg.base_radius_m) || rho < lo || rho > hi)
        fail(at, p + key,
             fmt::format("a start diameter on the active profile, between {} and {} m",
                         num(2.0 * std::sqrt(gg.base_radius_m * gg.base_radius_m + lo * lo)),
                         num(2.0 * std::sqrt(gg.base_radius_m * gg.base_radius_m + hi * hi))),
             num(2.0 * r) + " m",
             "a relief must start on the part of the flank that meshes (a roll angle is "
             "converted to this diameter)");
    };
    within(m.tip_relief_start_radius_m, "tip_relief_start_diameter");
    within(m.root_relief_start_radius_m, "root_relief_start_diameter");
    const double depth = 2.25 * g.normal_module_m;
    for (const auto& [v, key] :
         {std::pair{m.tip_relief_m, "tip_relief"}, std::pair{m.root_relief_m, "root_relief"},
          std::pair{m.profile_crowning_m, "profile_crowning"},
          std::pair{m.lead_crowning_m, "lead_crowning"}, std::pair{m.end_relief_m, "end_relief"}}) {
      if (!(std::abs(v) < 0.25 * depth))
        fail(at, p + key,
             fmt::format("a modification well below the tooth depth ({} m)", num(depth)),
             num(v) + " m", "modification amounts are micrometres (1e-6 m)");
    }
    if (m.end_relief_length_m < 0.0 || m.end_relief_length_m > 0.5 * g.face_width_m)
      fail(at, p + "end_relief_length",
           fmt::format("a length in [0, b/2 = {}] m", num(0.5 * g.face_width_m)),
           num(m.end_relief_length_m) + " m");
    if (m.end_relief_m != 0.0 && m.end_relief_length_m <= 0.0)
      fail(at, p + "end_relief_length", "a positive length with end_relief",
           num(m.end_relief_length_m) + " m");
    const int teeth = gg.teeth;
    if (!m.pitch_deviation_m.empty() && static_cast<int>(m.pitch_deviation_m.size()) != teeth)
      fail(at, p + "pitch_deviations", fmt::format("one value per tooth ({})", teeth),
           fmt::format("{} values", m.pitch_deviation_m.size()));
  };
  check_mod(pinion_, "1", g.pinion, rho1_low_, rho1_high_);
  check_mod(wheel_, "2", g.wheel, internal_ ? rho2_high_ : rho2_low_,
            internal_ ? rho2_low_ : rho2_high_);

  if (!bevel_) nominal_rho1_low_ = rho1_low_, nominal_rho1_high_ = rho1_high_;
  const bool pitch = !pinion_.pitch_deviation_m.empty() || !wheel_.pitch_deviation_m.empty();
  cycles_ = 1;
  if (pitch && options_.hunting_period) cycles_ = std::lcm(g.pinion.teeth, g.wheel.teeth);
}

// Bevel / hypoid pairs: the slice model runs on the virtual cylindrical pair, its centre distance
// changed by the mounting errors; the ease-off stays attached to the pinion's nominal active
// profile (docs/theory.md §15.9).
void ToothContact::setup_bevel(const GearPairGeometry& given) {
  if (!is_bevel(given.spec.type)) {
    if (!options_.ease_off.zero())
      fail(given, "ease_off", "no ease-off (it applies to bevel and hypoid pairs)", "an ease-off",
           "use [gear_pairs.flank1/2] for a cylindrical pair");
    if (!options_.mounting.zero())
      fail(given, "contact.mounting_h",
           "no mounting errors H, V, J or shaft angle error (bevel and hypoid pairs only)",
           "a mounting error", "use misalignment or axis_deviation for a cylindrical pair");
    force_radius_ = given.pinion.base_radius_m;
    return;
  }
  bevel_ = true;
  mounting_ = mounting_effect(given, options_.mounting);
  geometry_ = virtual_cylindrical_pair(given, mounting_.centre_distance_change_m);
  const GearPairGeometry nominal = virtual_cylindrical_pair(given);
  const double rb1 = nominal.pinion.base_radius_m, rb2 = nominal.wheel.base_radius_m;
  nominal_rho1_high_ =
      std::sqrt(nominal.pinion.tip_radius_m * nominal.pinion.tip_radius_m - rb1 * rb1);
  nominal_rho1_low_ =
      nominal.centre_distance_m * std::sin(nominal.working_pressure_angle_rad) -
      std::sqrt(nominal.wheel.tip_radius_m * nominal.wheel.tip_radius_m - rb2 * rb2);
  // F_t = T1 / r_m1 at the real pinion's mean point, F_bt = F_t / cos(alpha_t) (ISO 10300-1).
  force_radius_ =
      given.pinion.mean_pitch_radius_m * std::cos(nominal.transverse_pressure_angle_rad);
}

double ToothContact::bevel_gap(double rho1, double y) const {
  if (!bevel_) return 0.0;
  const double b = geometry_.face_width_m;
  const double xi = ease_off_xi(rho1), eta = 2.0 * y / b - 1.0;
  const double mid = 0.5 * (nominal_rho1_low_ + nominal_rho1_high_);
  return options_.ease_off.at(xi, eta) + mounting_.lead_slope_m * (y / b - 0.5) +
         mounting_.profile_gradient * (rho1 - mid);
}

double ToothContact::wheel_roll_length(double s) const {
  const double rho1 = rho1_a_ + s;
  return internal_ ? rho1 + t1t2_ : t1t2_ - rho1;
}

double ToothContact::flank_removal(const FlankModification& m, double rho, double rho_root,
                                   double rho_tip, double base_radius, double y) const {
  const double b = geometry_.face_width_m;
  const double span = rho_tip - rho_root;  // signed: internal gears have their tip low
  const double t = std::clamp((rho - rho_root) / span, 0.0, 1.0);
  auto t_of_radius = [&](double r) {
    const double rr = std::sqrt(std::max(0.0, r * r - base_radius * base_radius));
    return std::clamp((rr - rho_root) / span, 0.0, 1.0);
  };
  double removed = 0.0;
  if (m.tip_relief_m != 0.0 && !std::isnan(m.tip_relief_start_radius_m)) {
    const double t0 = t_of_radius(m.tip_relief_start_radius_m);
    if (t > t0 && t0 < 1.0)
      removed += m.tip_relief_m * std::pow((t - t0) / (1.0 - t0), shape_power(m.tip_relief_shape));
  }
  if (m.root_relief_m != 0.0 && !std::isnan(m.root_relief_start_radius_m)) {
    const double t0 = t_of_radius(m.root_relief_start_radius_m);
    if (t < t0 && t0 > 0.0)
      removed += m.root_relief_m * std::pow((t0 - t) / t0, shape_power(m.root_relief_shape));
  }
  removed += m.profile_crowning_m * (2.0 * t - 1.0) * (2.0 * t - 1.0);
  const double z = 2.0 * y / b - 1.0;
  removed += m.lead_crowning_m * z * z;
  removed += m.lead_slope_m * (y / b - 0.5);
  if (m.end_relief_m != 0.0 && m.end_relief_length_m > 0.0) {
    const double l = m.end_relief_length_m, p = shape_power(m.end_relief_shape);
    if (y < l) removed += m.end_relief_m * std::pow((l - y) / l, p);
    if (y > b - l) removed += m.end_relief_m * std::pow((y - (b - l)) / l, p);
  }
  removed += m.topography.at(std::abs(rho) / base_radius, y);
  return removed;
}

double ToothContact::gap(double s, double y, int pair, int cycle) const {
  const auto& g = geometry_;
  const double rho1 = pinion_roll_length(s), rho2 = wheel_roll_length(s);
  double gap = flank_removal(pinion_, rho1, rho1_low_, rho1_high_, g.pinion.base_radius_m, y);
  // The wheel's root end meets the pinion's tip (s = g_alpha), its tip end is at s = 0.
  const double w_root = wheel_roll_length(g.path_of_contact_m), w_tip = wheel_roll_length(0.0);
  gap += flank_removal(wheel_, rho2, w_root, w_tip, g.wheel.base_radius_m, y);
  gap += options_.misalignment_in_plane_m * (y / g.face_width_m - 0.5);
  gap += bevel_gap(rho1, y);
  auto tooth = [](int k, int z) { return ((k % z) + z) % z; };
  const int k = cycle - pair;
  if (!pinion_.pitch_deviation_m.empty())
    gap -= pinion_.pitch_deviation_m[static_cast<std::size_t>(tooth(k, g.pinion.teeth))];
  if (!wheel_.pitch_deviation_m.empty())
    gap -= wheel_.pitch_deviation_m[static_cast<std::size_t>(tooth(k, g.wheel.teeth))];
  return gap;
}

ToothContactResult ToothContact::solve(double pinion_torque_nm) const {
  const auto& g = geometry_;
  if (!(pinion_torque_nm > 0.0) || !std::isfinite(pinion_torque_nm))
    fail(g, "torque", "a positive finite torque", num(pinion_torque_nm) + " N m");
  ToothContactResult res;
  res.torque_nm = pinion_torque_nm;
  res.force_n = pinion_torque_nm / force_radius_;
  const int positions = options_.positions, slices = options_.slices;
  const double b = g.face_width_m, dy = b / slices, p_bt = g.transverse_base_pitch_m;
  const double lag = std::tan(g.base_helix_angle_rad);
  const double path = g.path_of_contact_m;
  const int max_pairs = static_cast<int>(std::ceil((path + b * lag) / p_bt)) + 1;
  const int total = positions * cycles_;
  res.pair_load_share = Eigen::MatrixXd::Zero(total, max_pairs);
  res.face_load_n_per_m.assign(static_cast<std::size_t>(slices), 0.0);

  for (int cycle = 0; cycle < cycles_; ++cycle) {
    for (int p = 0; p < positions; ++p) {
      const int index = cycle * positions + p;
      const double u = static_cast<double>(p) / positions;
      std::vector<Candidate> cand;
      for (int j = 0; j < max_pairs; ++j)
        for (int k = 0; k < slices; ++k) {
          const double y = (k + 0.5) * dy;
          const double s = (u + j) * p_bt - y * lag;
          if (s < 0.0 || s > path) continue;
          cand.push_back({j, k, s, y, gap(s, y, j, cycle)});
        }
      const Eigen::Index n = static_cast<Eigen::Index>(cand.size());
      Eigen::MatrixXd a = Eigen::MatrixXd::Zero(n, n);
      for (Eigen::Index first = 0; first < n;) {
        Eigen::Index last = first;
        while (last < n && cand[static_cast<std::size_t>(last)].pair ==
                               cand[static_cast<std::size_t>(first)].pair)
          ++last;
        std::vector<double> s, y;
        for (Eigen::Index i = first; i < last; ++i) {
          s.push_back(cand[static_cast<std::size_t>(i)].s);
          y.push_back(cand[static_cast<std::size_t>(i)].y);
        }
        a.block(first, first, last - first, last - first) = compliance_->body_influence(s, y, dy);
        first = last;
      }
      double min_gap = std::numeric_limits<double>::infinity();
      for (const auto& c : cand) min_gap = std::min(min_gap, c.g);

      PositionSolver solver(cand, a, *compliance_, res.force_n, dy, options_);
      std::string why;
      res.mesh_fraction.push_back(cycle + u);
      if (n == 0 || !solver.solve(why)) {
        if (n == 0) why = "no tooth pair on the path of contact";
        res.status = Status::NotConverged;
        res.message = fmt::format("mesh position u = {:.4f}: {}", cycle + u, why);
        return res;
      }
      const Eigen::VectorXd& w = solver.loads();
      res.te_m.push_back(solver.approach());
      res.unloaded_te_m.push_back(min_gap);
      res.stiffness_secant_n_per_m.push_back(res.force_n / (solver.approach() - min_gap));
      res.stiffness_tangent_n_per_m.push_back(solver.tangent_stiffness());
      double loaded = 0.0, wmax = 0.0, pmax = 0.0;
      for (Eigen::Index i = 0; i < n; ++i) {
        const auto& c = cand[static_cast<std::size_t>(i)];
        const double wi = std::max(0.0, w(i));
        const double pr = wi > 0.0 ? compliance_->max_pressure(c.s, wi) : 0.0;
        if (wi > 0.0) ++loaded;
        wmax = std::max(wmax, wi);
        pmax = std::max(pmax, pr);
        res.pair_load_share(index, c.pair) += wi * dy / res.force_n;
        res.face_load_n_per_m[static_cast<std::size_t>(c.slice)] += wi / total;
        const double rho1 = pinion_roll_length(c.s), rho2 = wheel_roll_length(c.s);
        res.distribution.push_back({index, c.pair, c.s, c.y, rho1 / g.pinion.base_radius_m,
                                    std::hypot(g.pinion.base_radius_m, rho1),
                                    std::hypot(g.wheel.base_radius_m, rho2), c.g, wi, pr});
      }
      res.points_in_contact.push_back(loaded);
      res.max_line_load_n_per_m.push_back(wmax);
      res.max_pressure_pa.push_back(pmax);
    }
  }
  const double mean =
      std::accumulate(res.face_load_n_per_m.begin(), res.face_load_n_per_m.end(), 0.0) / slices;
  res.face_load_factor =
      *std::max_element(res.face_load_n_per_m.begin(), res.face_load_n_per_m.end()) / mean;
  return res;
}

MountingEffect mounting_effect(const GearPairGeometry& g, const MountingErrors& e) {
  MountingEffect m;
  if (!is_bevel(g.spec.type) || e.zero()) return m;
  // Frame at the mean point P of the pitch cones' common element (docs/theory.md (15.20)):
  // e_R along the element away from the apex, e_t along the pinion's pitch-line motion, e_n
  // normal to the pitch plane towards the pinion's axis. Axes a1 = (cos d1, 0, sin d1),
  // a2 = (cos d2, 0, -sin d2); n is the unit normal of the loaded pinion flank (the direction of
  // the force on the wheel): n . e_R = -+ cos(a_n) sin(beta) (concave / convex loaded: the
  // concave flank's thrust pushes the pinion out of mesh, ISO 10300-1 / ANSI/AGMA 2005).
  const double d1 = g.pinion.pitch_cone_angle_rad, d2 = g.wheel.pitch_cone_angle_rad;
  const double an = g.normal_pressure_angle_rad, beta = g.helix_angle_rad;
  const double rm = g.mean_cone_distance_m, b = g.face_width_m;
  const double lengthwise = (e.pinion_concave_loaded ? -1.0 : 1.0) * std::cos(an) * std::sin(beta);
  const double n[3] = {lengthwise, std::cos(an) * std::cos(beta), -std::sin(an)};
  // Pinion displacement relative to the wheel at P. A shaft angle error turns the pinion by
  // -dSigma about e_t through the crossing point: P moves by dSigma R_m e_n. That part is a
  // rotation about the apex, whose gap (proportional to R) the pinion's rotation absorbs
  // exactly: it separates the pair at P but adds no lead slope.
  const double d[3] = {e.h_m * std::cos(d1) - e.j_m * std::cos(d2), e.v_m,
                       e.h_m * std::sin(d1) + e.j_m * std::sin(d2)};
  m.normal_approach_m = d[0] * n[0] + d[1] * n[1] + d[2] * n[2];
  // The rotation absorbs a uniform normal approach only at R_m (lever arm ~ R): the gap left is
  // d . n (R - R_m) / R_m along the normal, / cos(beta_b) along the transverse line of action.
  m.lead_slope_m = m.normal_approach_m / std::cos(g.base_helix_angle_rad) * b / rm;
  m.centre_distance_change_m = d[2] + e.shaft_angle_rad * rm;
  // Tilt about e_t: a flank point at height X_n = -(rho1 - rho1_C) sin(alpha_wt) above the pitch
  // plane moves by -dSigma X_n e_R; its gap changes by dSigma X_n (n . e_R).
  m.profile_gradient = -e.shaft_angle_rad * std::sin(g.working_pressure_angle_rad) * lengthwise /
                       std::cos(g.base_helix_angle_rad);
  return m;
}

GearPairGeometry virtual_cylindrical_pair(const GearPairGeometry& bevel, double change) {
  GearPairGeometry v = bevel;
  if (!is_bevel(bevel.spec.type)) return v;
  v.spec.type = bevel.spec.type == GearType::StraightBevel ? GearType::Spur : GearType::Helical;
  v.spec.helix_angle_rad = bevel.helix_angle_rad;
  v.spec.pinion_spiral_angle_rad = std::numeric_limits<double>::quiet_NaN();
  if (change == 0.0) return v;
  const double rb1 = v.pinion.base_radius_m, rb2 = v.wheel.base_radius_m;
  const double a = bevel.centre_distance_m + change;
  const double g1 = std::sqrt(v.pinion.tip_radius_m * v.pinion.tip_radius_m - rb1 * rb1);
  const double g2 = std::sqrt(v.wheel.tip_radius_m * v.wheel.tip_radius_m - rb2 * rb2);
  const double t1t2 = a > rb1 + rb2 ? std::sqrt(a * a - (rb1 + rb2) * (rb1 + rb2)) : 0.0;
  const double path = g1 + g2 - t1t2;
  if (!(t1t2 - g2 > 0.0) || !(t1t2 - g1 > 0.0) || !(path > v.transverse_base_pitch_m))
    fail(bevel, "contact.mounting_h",
         fmt::format("mounting errors that keep the virtual pair in mesh (contact ratio >= 1, no "
                     "interference): centre distance change {} m here",
                     num(change)),
         fmt::format("path of contact {} m, base pitch {} m", num(path),
                     num(v.transverse_base_pitch_m)),
         "reduce mounting_h, mounting_j or shaft_angle_error_deg");
  v.centre_distance_m = a;
  v.working_pressure_angle_rad = std::acos((rb1 + rb2) / a);
  v.pinion.working_pitch_radius_m = rb1 / std::cos(v.working_pressure_angle_rad);
  v.wheel.working_pitch_radius_m = rb2 / std::cos(v.working_pressure_angle_rad);
  v.path_of_contact_m = path;
  v.transverse_contact_ratio = path / v.transverse_base_pitch_m;
  v.total_contact_ratio = v.transverse_contact_ratio + v.overlap_ratio;
  return v;
}

std::pair<double, double> ease_off_centre(const EaseOff& e, double profile_linear_m,
                                          double length_linear_m) {
  const double a = 2.0 * e.profile_crowning_m, c = 2.0 * e.length_crowning_m, bb = e.bias_m;
  const double det = a * c - bb * bb;
  if (!(det > 0.0))
    return {std::numeric_limits<double>::quiet_NaN(), std::numeric_limits<double>::quiet_NaN()};
  const double fa = e.profile_slope_m + profile_linear_m, fb = e.length_slope_m + length_linear_m;
  return {-(c * fa - bb * fb) / det, -(a * fb - bb * fa) / det};
}

std::pair<double, double> pattern_centre(const ToothContact& contact,
                                         const ToothContactResult& result) {
  double sum = 0.0, xi = 0.0, eta = 0.0;
  const double b = contact.geometry().face_width_m, rb1 = contact.base_radius1();
  for (const auto& p : result.distribution) {
    if (!(p.line_load_n_per_m > 0.0)) continue;
    sum += p.line_load_n_per_m;
    xi += p.line_load_n_per_m * contact.ease_off_xi(p.roll_angle1_rad * rb1);
    eta += p.line_load_n_per_m * (2.0 * p.face_m / b - 1.0);
  }
  if (!(sum > 0.0))
    return {std::numeric_limits<double>::quiet_NaN(), std::numeric_limits<double>::quiet_NaN()};
  return {xi / sum, eta / sum};
}

std::vector<double> mesh_order_amplitudes(const std::vector<double>& series, int cycles,
                                          int orders) {
  const std::size_t n = series.size();
  std::vector<double> amp(static_cast<std::size_t>(orders), 0.0);
  for (int k = 1; k <= orders; ++k) {
    const double bin = static_cast<double>(k) * cycles;
    if (2.0 * bin >= static_cast<double>(n)) break;  // beyond Nyquist: left at 0
    std::complex<double> sum = 0.0;
    for (std::size_t i = 0; i < n; ++i)
      sum += series[i] * std::polar(1.0, -2.0 * units::kPi * bin * static_cast<double>(i) /
                                             static_cast<double>(n));
    amp[static_cast<std::size_t>(k - 1)] = 2.0 * std::abs(sum) / static_cast<double>(n);
  }
  return amp;
}

}  // namespace geardyn::gear
