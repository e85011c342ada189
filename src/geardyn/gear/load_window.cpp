#include "geardyn/gear/load_window.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "geardyn/core/error.hpp"
#include "geardyn/core/units.hpp"
#include "geardyn/signal/fft.hpp"

namespace geardyn::gear {
namespace {

[[noreturn]] void fail(const std::string& key, std::string expected, std::string found,
                       std::string hint = {}) {
  throw InputError(SourceLocation{}, "tooth_load." + key, std::move(expected), std::move(found),
                   std::move(hint));
}

void validate_window(int teeth, double contact_ratio) {
  if (teeth < 2) fail("teeth", "a gear with at least 2 teeth", std::to_string(teeth));
  if (!std::isfinite(contact_ratio) || contact_ratio < 1.0 || contact_ratio > 3.0)
    fail("contact_ratio", "a contact ratio in [1, 3]", fmt::format("{}", contact_ratio),
         "the window model covers one to three pairs in contact");
  if (contact_ratio >= teeth)
    fail("contact_ratio", fmt::format("a contact ratio below the tooth count {}", teeth),
         fmt::format("{}", contact_ratio));
}

void validate_force(const Eigen::Ref<const Eigen::VectorXd>& f, const char* key) {
  if (f.size() < 1) fail(key, "at least one sample per revolution", "none");
  if (!f.allFinite()) fail(key, "finite samples", "NaN or infinite values");
}

double sinc(double x) { return std::abs(x) < 1e-8 ? 1.0 - x * x / 6.0 : std::sin(x) / x; }

// Window in pitch units: x = phi / p reduced to [0, N), ramp = CR - 1. Working in pitch units
// keeps sample points that fall on a pitch boundary (i N / n integer) exact, so a rectangular
// window covers exactly n / N samples.
double window_in_pitches(double x, double ramp) {
  if (ramp <= 0.0) return x < 1.0 ? 1.0 : 0.0;
  const double lo = std::max(x - 1.0, 0.0);
  const double hi = std::min(x, ramp);
  return hi > lo ? (hi - lo) / ramp : 0.0;
}

double reduce_pitches(double x, int teeth) {
  double r = std::fmod(x, static_cast<double>(teeth));
  if (r < 0.0) r += teeth;
  if (r >= teeth) r -= teeth;  // fmod of a tiny negative number can round up to N
  return r;
}

std::string order_rule(int order, int teeth, int h) {
  // order = m N + h or m N - h; name it the way the thesis does ("N-h", "2N+h", ...).
  if (h == 0) return order == teeth ? "N" : fmt::format("{}N", order / teeth);
  const int m_plus = (order - h) / teeth;
  if ((order - h) % teeth == 0)
    return m_plus == 0 ? "h" : (m_plus == 1 ? "N+h" : fmt::format("{}N+h", m_plus));
  const int m_minus = (order + h) / teeth;
  return m_minus == 1 ? "N-h" : fmt::format("{}N-h", m_minus);
}

}  // namespace

double tooth_load_window(double phi_rad, int teeth, double contact_ratio) {
  validate_window(teeth, contact_ratio);
  return window_in_pitches(reduce_pitches(phi_rad * teeth / units::kTwoPi, teeth),
                           contact_ratio - 1.0);
}

Eigen::VectorXd tooth_load_window_samples(int samples, int teeth, double contact_ratio,
                                          double shift_rad) {
  validate_window(teeth, contact_ratio);
  if (samples < 1) fail("samples", "at least one sample per revolution", std::to_string(samples));
  if (!std::isfinite(shift_rad)) fail("shift", "a finite window shift [rad]", "non-finite");
  const double shift_pitches = shift_rad * teeth / units::kTwoPi;
  Eigen::VectorXd w(samples);
  for (int i = 0; i < samples; ++i) {
    // i N / n is exact whenever it is an integer (both factors are exact in double).
    const double x = static_cast<double>(i) * teeth / samples - shift_pitches;
    w[i] = window_in_pitches(reduce_pitches(x, teeth), contact_ratio - 1.0);
  }
  return w;
}

std::complex<double> tooth_load_window_coefficient(int order, int teeth, double contact_ratio) {
  validate_window(teeth, contact_ratio);
  const double pitch = units::kTwoPi / teeth;
  const double ramp = (contact_ratio - 1.0) * pitch;
  const double k = order;
  return std::polar(sinc(0.5 * k * pitch) * sinc(0.5 * k * ramp) / teeth,
                    -0.5 * k * contact_ratio * pitch);
}

Eigen::VectorXd filtered_tooth_force(const Eigen::Ref<const Eigen::VectorXd>& mesh_force_n,
                                     int teeth, double contact_ratio, double shift_rad) {
  validate_force(mesh_force_n, "mesh_force");
  const Eigen::VectorXd w = tooth_load_window_samples(static_cast<int>(mesh_force_n.size()), teeth,
                                                      contact_ratio, shift_rad);
  return mesh_force_n.cwiseProduct(w);
}

std::vector<EngineOrderHarmonic> engine_order_harmonics(
    const Eigen::Ref<const Eigen::VectorXd>& tooth_force, const std::vector<int>& orders) {
  validate_force(tooth_force, "tooth_force");
  const int n = static_cast<int>(tooth_force.size());
  for (int k : orders)
    if (k < 0 || k > n / 2)
      fail("orders",
           fmt::format("orders in [0, n/2] = [0, {}] for {} samples per revolution", n / 2, n),
           std::to_string(k), "sample the revolution more finely (at least 2 k + 1 samples)");
  const Eigen::VectorXcd X = signal::real_fft(tooth_force);
  std::vector<EngineOrderHarmonic> out;
  out.reserve(orders.size());
  for (int k : orders) {
    EngineOrderHarmonic h;
    h.order = k;
    h.coefficient = X[k] / static_cast<double>(n);
    const bool single = k == 0 || (n % 2 == 0 && k == n / 2);
    h.amplitude = (single ? 1.0 : 2.0) * std::abs(h.coefficient);
    h.phase_rad = std::arg(X[k]);
    out.push_back(h);
  }
  return out;
}

std::vector<int> nodal_diameter_orders(int teeth, int nodal_diameter, int count) {
  if (teeth < 2) fail("teeth", "a gear with at least 2 teeth", std::to_string(teeth));
  if (nodal_diameter < 0 || 2 * nodal_diameter > teeth)
    fail("nodal_diameter", fmt::format("a nodal diameter in [0, N/2] = [0, {}]", teeth / 2),
         std::to_string(nodal_diameter));
  if (count < 1) fail("orders_per_diameter", "at least one order", std::to_string(count));
  std::vector<int> orders;
  for (int m = 0; static_cast<int>(orders.size()) < count; ++m) {
    for (int k : {m * teeth - nodal_diameter, m * teeth + nodal_diameter}) {
      if (k < 1 || static_cast<int>(orders.size()) >= count) continue;
      if (!orders.empty() && orders.back() == k) continue;
      orders.push_back(k);
    }
  }
  return orders;
}

ForceDirections force_directions(double normal_pressure_angle_rad, double spiral_angle_rad,
                                 double pitch_cone_angle_rad, Flank loaded) {
  const double s = loaded == Flank::Concave ? 1.0 : -1.0;
  const double ta = std::tan(normal_pressure_angle_rad);
  const double sb = std::sin(spiral_angle_rad), cb = std::cos(spiral_angle_rad);
  const double sd = std::sin(pitch_cone_angle_rad), cd = std::cos(pitch_cone_angle_rad);
  ForceDirections d;
  d.radial_per_tangential = (ta * cd - s * sb * sd) / cb;
  d.axial_per_tangential = (ta * sd + s * sb * cd) / cb;
  return d;
}

std::vector<HarmonicComponents> harmonic_components(
    const Eigen::Ref<const Eigen::VectorXd>& tooth_force, int teeth,
    const std::vector<int>& nodal_diameters, const ForceDirections& directions,
    int orders_per_diameter) {
  std::vector<HarmonicComponents> out;
  for (int h : nodal_diameters) {
    const std::vector<int> orders = nodal_diameter_orders(teeth, h, orders_per_diameter);
    for (const EngineOrderHarmonic& e : engine_order_harmonics(tooth_force, orders)) {
      HarmonicComponents c;
      c.nodal_diameter = h;
      c.order = e.order;
      c.tangential = std::polar(e.amplitude, e.phase_rad);
      c.radial = directions.radial_per_tangential * c.tangential;
      c.axial = directions.axial_per_tangential * c.tangential;
      out.push_back(c);
    }
  }
  return out;
}

Table tooth_load_table(const Eigen::Ref<const Eigen::VectorXd>& mesh_force_n, int teeth,
                       double contact_ratio, double shift_rad) {
  validate_force(mesh_force_n, "mesh_force");
  const int n = static_cast<int>(mesh_force_n.size());
  const Eigen::VectorXd w = tooth_load_window_samples(n, teeth, contact_ratio, shift_rad);
  Table t;
  t.name = "tooth_load";
  t.title = fmt::format("Load on one tooth over one revolution (N = {}, CR = {}, shift = {} deg)",
                        teeth, contact_ratio, shift_rad * (180.0 / units::kPi));
  std::vector<double> angle(n), angle_deg(n), force(n), window(n), tooth(n);
  for (int i = 0; i < n; ++i) {
    angle[i] = units::kTwoPi * i / n;
    angle_deg[i] = angle[i] * (180.0 / units::kPi);
    force[i] = mesh_force_n[i];
    window[i] = w[i];
    tooth[i] = mesh_force_n[i] * w[i];
  }
  t.add("angle_rad", "rad", std::move(angle));
  t.add("angle_deg", "deg", std::move(angle_deg));
  t.add("mesh_force_n", "N", std::move(force));
  t.add("window", "", std::move(window));
  t.add("tooth_force_n", "N", std::move(tooth));
  return t;
}

Table order_spectrum_table(const Eigen::Ref<const Eigen::VectorXd>& tooth_force, int max_order,
                           double static_force_n) {
  if (!std::isfinite(static_force_n) || static_force_n <= 0.0)
    fail("static_force", "a static force > 0 N", fmt::format("{}", static_force_n));
  if (max_order < 0) fail("max_order", "a maximum order >= 0", std::to_string(max_order));
  std::vector<int> orders(static_cast<std::size_t>(max_order) + 1);
  for (int k = 0; k <= max_order; ++k) orders[static_cast<std::size_t>(k)] = k;
  const auto harmonics = engine_order_harmonics(tooth_force, orders);
  Table t;
  t.name = "order_spectrum";
  t.title = "Engine-order spectrum of the tooth force (order 0: mean)";
  std::vector<double> order, amp, phase, rel;
  for (const auto& h : harmonics) {
    order.push_back(h.order);
    amp.push_back(h.amplitude);
    phase.push_back(h.phase_rad * (180.0 / units::kPi));
    rel.push_back(h.amplitude / static_force_n);
  }
  t.add("order", "", std::move(order));
  t.add("amplitude_n", "N", std::move(amp));
  t.add("phase_deg", "deg", std::move(phase));
  t.add("amplitude_per_static_force", "", std::move(rel));
  return t;
}

Table harmonic_table(const Eigen::Ref<const Eigen::VectorXd>& tooth_force, int teeth,
                     const std::vector<int>& nodal_diameters, const ForceDirections& directions,
                     double static_force_n, int orders_per_diameter) {
  if (!std::isfinite(static_force_n) || static_force_n <= 0.0)
    fail("static_force", "a static force > 0 N", fmt::format("{}", static_force_n));
  const auto comps =
      harmonic_components(tooth_force, teeth, nodal_diameters, directions, orders_per_diameter);
  Table t;
  t.name = "engine_order_harmonics";
  t.title = fmt::format("Tooth-force harmonics per nodal diameter (N = {})", teeth);
  std::vector<double> nd, order, amp, phase, rel, fr, fa, pr, pa;
  std::vector<std::string> rule;
  for (const auto& c : comps) {
    nd.push_back(c.nodal_diameter);
    order.push_back(c.order);
    rule.push_back(order_rule(c.order, teeth, c.nodal_diameter));
    amp.push_back(std::abs(c.tangential));
    phase.push_back(std::arg(c.tangential) * (180.0 / units::kPi));
    rel.push_back(std::abs(c.tangential) / static_force_n);
    fr.push_back(std::abs(c.radial));
    fa.push_back(std::abs(c.axial));
    pr.push_back(std::arg(c.radial) * (180.0 / units::kPi));
    pa.push_back(std::arg(c.axial) * (180.0 / units::kPi));
  }
  t.add("nodal_diameter", "", std::move(nd));
  t.add("order", "", std::move(order));
  t.add_text("order_rule", std::move(rule));
  t.add("amplitude_n", "N", std::move(amp));
  t.add("phase_deg", "deg", std::move(phase));
  t.add("amplitude_per_static_force", "", std::move(rel));
  t.add("radial_n", "N", std::move(fr));
  t.add("axial_n", "N", std::move(fa));
  t.add("radial_phase_deg", "deg", std::move(pr));
  t.add("axial_phase_deg", "deg", std::move(pa));
  return t;
}

}  // namespace geardyn::gear
