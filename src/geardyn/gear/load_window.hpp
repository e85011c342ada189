#pragma once
// Tooth-load window and engine-order harmonics (docs/theory.md §12; the damper-ring thesis:
// A. Durastante, "Simulation of the Dynamic Response of Aeronautical Gears Equipped with Damper
// Rings", MSc thesis, Politecnico di Torino, 2018, sec. 1.3.3 and 3.3-3.4).
//
// A gear of N teeth turns by the pitch p = 2 pi / N per mesh cycle. One tooth carries load while
// it passes the mesh, for about CR pitches. Its share of the mesh force is the window
//     w(phi) = (box_p * box_L / L)(phi),  L = (CR - 1) p,  1 <= CR <= 3,
// i.e. w(phi) = |(phi - p, phi] ∩ [0, L)| / L (CR = 1: the rectangle 1 on [0, p)).
// phi is the gear rotation since the tooth entered contact (the STE file's first sample), shifted
// by a user offset: the window of the tooth is w(phi - shift), 2 pi periodic. Properties:
//   - support [0, CR p); the windows of all teeth, w(phi - j p), sum to 1 at every phi;
//   - 1 <= CR <= 2: a trapezoid of height 1, from a rectangle (CR = 1) to a triangle (CR = 2);
//   - 2 < CR <= 3: a trapezoid with plateau height p / L = 1 / (CR - 1);
//   - Fourier coefficient, W_k = (1/2pi) int w(phi) e^{-i k phi} dphi
//       = (1/N) e^{-i k CR p / 2} sinc(k p / 2) sinc(k L / 2),   sinc(x) = sin(x) / x,
//     so a constant mesh force gives no harmonic at k = N, 2N, ... (for every CR).
// The filtered tooth force over one revolution is f(phi) = F_d(phi) w(phi - shift); its DFT X_k
// over n samples gives the engine-order harmonics: one-sided amplitude A_k = 2 |X_k| / n
// (0 < k < n/2), phase arg X_k, so f(phi) ~ A_0 + sum_k A_k cos(k phi + phase_k); X_0 / n is the
// mean (the static share of the tooth load), not a harmonic.
// A mode with h nodal diameters is excited by the orders k = +-h (mod N): k = h and k = N - h
// first, then N + h, 2N - h, ... (`nodal_diameter_orders`).
// 3D components: the tangential harmonic is split with the ratios of tooth_forces.hpp,
//   radial / tangential = (tan(alpha_n) cos(delta) -+ sin(beta) sin(delta)) / cos(beta),
//   axial / tangential  = (tan(alpha_n) sin(delta) +- sin(beta) cos(delta)) / cos(beta),
// (upper signs: concave flank loaded; delta = 0 gives the spur / helical ratios).
#include <Eigen/Dense>
#include <complex>
#include <string>
#include <vector>

#include "geardyn/core/table.hpp"
#include "geardyn/gear/tooth_forces.hpp"

namespace geardyn::gear {

/// w(phi) as above (phi in rad, any real value, reduced modulo 2 pi). Throws InputError for
/// teeth < 2, CR outside [1, 3], or CR >= teeth (the window would overlap itself).
double tooth_load_window(double phi_rad, int teeth, double contact_ratio);

/// w(2 pi i / n - shift), i = 0 .. n-1. Throws InputError for n < 1 and as above.
Eigen::VectorXd tooth_load_window_samples(int samples, int teeth, double contact_ratio,
                                          double shift_rad = 0.0);

/// Closed-form W_k (see above) of the unshifted window; the shifted one is W_k e^{-i k shift}.
std::complex<double> tooth_load_window_coefficient(int order, int teeth, double contact_ratio);

/// Tooth force over one revolution: f_i = F_i w(2 pi i / n - shift), F the dynamic mesh force
/// sampled uniformly over one revolution of this gear (sample 0: the tooth enters contact).
/// Throws InputError for an empty or non-finite force and for the window arguments as above.
Eigen::VectorXd filtered_tooth_force(const Eigen::Ref<const Eigen::VectorXd>& mesh_force_n,
                                     int teeth, double contact_ratio, double shift_rad = 0.0);

struct EngineOrderHarmonic {
  int order = 0;
  double amplitude = 0.0;            ///< 2|X_k|/n (k = 0 and k = n/2: |X_k|/n); unit of the signal
  double phase_rad = 0.0;            ///< arg X_k (cosine phase at phi = 0)
  std::complex<double> coefficient;  ///< X_k / n
};

/// Harmonics of `tooth_force` (uniform samples over one revolution) at the given orders.
/// Throws InputError for a negative order or one above n/2 (needs more samples per revolution).
std::vector<EngineOrderHarmonic> engine_order_harmonics(
    const Eigen::Ref<const Eigen::VectorXd>& tooth_force, const std::vector<int>& orders);

/// The first `count` orders k >= 1 with k = +-h (mod N), ascending, without repeats:
/// h, N - h, N + h, 2N - h, ... (h = 0: N, 2N, ...; h = N/2: N/2, 3N/2, ...). Throws InputError
/// for h outside [0, N/2] or count < 1.
std::vector<int> nodal_diameter_orders(int teeth, int nodal_diameter, int count = 2);

/// radial / tangential and axial / tangential ratios (formulas above). delta = 0 for cylindrical
/// gears; for helical gears the axial ratio carries the flank's sign.
struct ForceDirections {
  double radial_per_tangential = 0.0;
  double axial_per_tangential = 0.0;
};
ForceDirections force_directions(double normal_pressure_angle_rad, double spiral_angle_rad,
                                 double pitch_cone_angle_rad, Flank loaded);

/// One harmonic split into 3D components (complex amplitudes, same phase convention).
struct HarmonicComponents {
  int nodal_diameter = 0;
  int order = 0;
  std::complex<double> tangential, radial, axial;  ///< one-sided complex amplitudes A_k e^{i phase}
};
std::vector<HarmonicComponents> harmonic_components(
    const Eigen::Ref<const Eigen::VectorXd>& tooth_force, int teeth,
    const std::vector<int>& nodal_diameters, const ForceDirections& directions,
    int orders_per_diameter = 2);

/// Table "tooth_load": angle_rad, angle_deg, mesh_force_n, window, tooth_force_n.
Table tooth_load_table(const Eigen::Ref<const Eigen::VectorXd>& mesh_force_n, int teeth,
                       double contact_ratio, double shift_rad = 0.0);

/// Table "order_spectrum": order 0 .. max_order, amplitude_n, phase_deg and
/// amplitude_per_static_force (amplitude / static_force_n; static_force_n > 0).
Table order_spectrum_table(const Eigen::Ref<const Eigen::VectorXd>& tooth_force, int max_order,
                           double static_force_n);

/// Table "engine_order_harmonics": per nodal diameter and order: nodal_diameter, order,
/// order_rule ("h", "N-h", "N+h", ...), amplitude_n and phase_deg (tangential),
/// amplitude_per_static_force, radial_n, axial_n (component amplitudes), radial_phase_deg,
/// axial_phase_deg.
Table harmonic_table(const Eigen::Ref<const Eigen::VectorXd>& tooth_force, int teeth,
                     const std::vector<int>& nodal_diameters, const ForceDirections& directions,
                     double static_force_n, int orders_per_diameter = 2);

}  // namespace geardyn::gear
