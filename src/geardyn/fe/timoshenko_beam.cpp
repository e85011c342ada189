#include "geardyn/fe/timoshenko_beam.hpp"

#include <array>
#include <cmath>
#include <stdexcept>

#include "geardyn/core/units.hpp"

namespace geardyn::fe {
namespace {

// Element-vector positions of the two bending planes, with the sign that turns the node DOF into
// the plane's (w, theta) variables where theta = dw/dz:
//   e1-e3 plane: (ux1, ry1, ux2, ry2);  e2-e3 plane: (uy1, -rx1, uy2, -rx2).
constexpr std::array<int, 4> kPlaneXZ = {0, 4, 6, 10};
constexpr std::array<int, 4> kPlaneYZ = {1, 3, 7, 9};
constexpr std::array<double, 4> kSignXZ = {1.0, 1.0, 1.0, 1.0};
constexpr std::array<double, 4> kSignYZ = {1.0, -1.0, 1.0, -1.0};

struct PlaneShape {
  Eigen::Vector4d w;      // displacement shape functions
  Eigen::Vector4d theta;  // rotation shape functions
};

// Interdependent interpolation shape functions (Friedman & Kosmatka 1993), xi = z / L.
// The shear strain w' - theta is constant along the element, which is what makes the element
// free of shear locking and exact for static end loads.
PlaneShape plane_shape(double xi, double L, double phi) {
  const double s = 1.0 / (1.0 + phi);
  const double xi2 = xi * xi, xi3 = xi2 * xi;
  PlaneShape n;
  n.w << s * (2 * xi3 - 3 * xi2 - phi * xi + 1 + phi),
      s * L * (xi3 - (2 + phi / 2) * xi2 + (1 + phi / 2) * xi), -s * (2 * xi3 - 3 * xi2 - phi * xi),
      s * L * (xi3 - (1 - phi / 2) * xi2 - (phi / 2) * xi);
  n.theta << 6 * s / L * (xi2 - xi), s * (3 * xi2 - (4 + phi) * xi + 1 + phi),
      -6 * s / L * (xi2 - xi), s * (3 * xi2 - (2 - phi) * xi);
  return n;
}

// Scatters a plane vector into the 12-vector with the plane's signs.
Vector12d scatter(const Eigen::Vector4d& v, const std::array<int, 4>& at,
                  const std::array<double, 4>& sign) {
  Vector12d out = Vector12d::Zero();
  for (int j = 0; j < 4; ++j)
    out(at[static_cast<std::size_t>(j)]) = sign[static_cast<std::size_t>(j)] * v(j);
  return out;
}

void require(bool ok, const char* what) {
  if (!ok) throw std::invalid_argument(std::string("timoshenko_beam: ") + what);
}

}  // namespace

double cowper_shear_coefficient(double poisson_ratio, double diameter_ratio) {
  const double nu = poisson_ratio;
  const double m2 = diameter_ratio * diameter_ratio;
  const double a = (1 + m2) * (1 + m2);
  return 6 * (1 + nu) * a / ((7 + 6 * nu) * a + (20 + 12 * nu) * m2);
}

BeamMatrices timoshenko_beam(const BeamProperties& p) {
  require(p.length > 0 && std::isfinite(p.length), "length must be positive");
  require(p.outer_diameter > 0 && std::isfinite(p.outer_diameter),
          "outer diameter must be positive");
  require(p.inner_diameter >= 0 && p.inner_diameter < p.outer_diameter,
          "inner diameter must lie in [0, outer diameter)");
  require(p.youngs_modulus > 0 && p.shear_modulus > 0 && p.density >= 0,
          "E, G must be positive and rho non-negative");

  const double L = p.length;
  const double d_o = p.outer_diameter, d_i = p.inner_diameter;
  const double A = units::kPi * (d_o * d_o - d_i * d_i) / 4;
  const double I = units::kPi * (std::pow(d_o, 4) - std::pow(d_i, 4)) / 64;
  const double J = 2 * I;
  const double E = p.youngs_modulus, G = p.shear_modulus, rho = p.density;

  BeamMatrices out;
  double phi = 0.0;
  if (p.theory == model::BeamTheory::Timoshenko) {
    double kappa = p.shear_coefficient;
    if (std::isnan(kappa)) kappa = cowper_shear_coefficient(E / (2 * G) - 1, d_i / d_o);
    require(kappa > 0 && std::isfinite(kappa), "shear coefficient must be positive");
    phi = 12 * E * I / (kappa * G * A * L * L);
    out.shear_coefficient = kappa;
  } else {
    out.shear_coefficient = model::kNaN;
  }
  out.shear_parameter = phi;

  // Bending stiffness, closed form of integral(EI theta'^2 + kappa G A (w' - theta)^2).
  Eigen::Matrix4d kb;
  kb << 12, 6 * L, -12, 6 * L,                              //
      6 * L, (4 + phi) * L * L, -6 * L, (2 - phi) * L * L,  //
      -12, -6 * L, 12, -6 * L,                              //
      6 * L, (2 - phi) * L * L, -6 * L, (4 + phi) * L * L;
  kb *= E * I / (L * L * L * (1 + phi));

  // Mass and gyroscopic matrices by quadrature of the shape functions: the integrands are
  // polynomials of degree <= 6 in xi, integrated exactly by 4-point Gauss-Legendre.
  const double g1 = std::sqrt(3.0 / 7.0 - 2.0 / 7.0 * std::sqrt(6.0 / 5.0));
  const double g2 = std::sqrt(3.0 / 7.0 + 2.0 / 7.0 * std::sqrt(6.0 / 5.0));
  const double w1 = (18.0 + std::sqrt(30.0)) / 36.0, w2 = (18.0 - std::sqrt(30.0)) / 36.0;
  const std::array<double, 4> points = {-g2, -g1, g1, g2};
  const std::array<double, 4> weights = {w2, w1, w1, w2};

  Eigen::Matrix4d m_translational = Eigen::Matrix4d::Zero();
  Eigen::Matrix4d m_rotary = Eigen::Matrix4d::Zero();
  Matrix12d gyro = Matrix12d::Zero();
  for (std::size_t q = 0; q < 4; ++q) {
    const double xi = 0.5 * (points[q] + 1.0);
    const double dz = 0.5 * weights[q] * L;
    const PlaneShape n = plane_shape(xi, L, phi);
    m_translational += rho * A * dz * n.w * n.w.transpose();
    m_rotary += rho * I * dz * n.theta * n.theta.transpose();
    // ry(z) = N_theta . p_xz;  rx(z) = -N_theta . p_yz. Gyroscopic virtual work of spin about e3:
    // G = integral rho J (N_rx^T N_ry - N_ry^T N_rx) dz (disk limit: G(rx, ry) = +Ip).
    const Vector12d n_ry = scatter(n.theta, kPlaneXZ, kSignXZ);
    const Vector12d n_rx = -scatter(n.theta, kPlaneYZ, kSignYZ);
    gyro += rho * J * dz * (n_rx * n_ry.transpose() - n_ry * n_rx.transpose());
  }

  Eigen::Matrix4d m_bending = m_translational;
  if (p.rotary_inertia) m_bending += m_rotary;
  for (int plane = 0; plane < 2; ++plane) {
    const auto& at = plane == 0 ? kPlaneXZ : kPlaneYZ;
    const auto& sign = plane == 0 ? kSignXZ : kSignYZ;
    for (std::size_t i = 0; i < 4; ++i) {
      for (std::size_t j = 0; j < 4; ++j) {
        const double sij = sign[i] * sign[j];
        out.stiffness(at[i], at[j]) += sij * kb(static_cast<int>(i), static_cast<int>(j));
        out.mass(at[i], at[j]) += sij * m_bending(static_cast<int>(i), static_cast<int>(j));
      }
    }
  }

  // Axial (uz) and torsional (rz): linear shape functions, consistent mass.
  const std::array<int, 2> axial = {2, 8}, torsion = {5, 11};
  const Eigen::Matrix2d unit_k = (Eigen::Matrix2d() << 1, -1, -1, 1).finished();
  const Eigen::Matrix2d unit_m = (Eigen::Matrix2d() << 2, 1, 1, 2).finished() / 6.0;
  for (std::size_t i = 0; i < 2; ++i) {
    for (std::size_t j = 0; j < 2; ++j) {
      const int r = static_cast<int>(i), c = static_cast<int>(j);
      out.stiffness(axial[i], axial[j]) += E * A / L * unit_k(r, c);
      out.mass(axial[i], axial[j]) += rho * A * L * unit_m(r, c);
      out.stiffness(torsion[i], torsion[j]) += G * J / L * unit_k(r, c);
      out.mass(torsion[i], torsion[j]) += rho * J * L * unit_m(r, c);
    }
  }

  if (p.gyroscopic) out.gyroscopic = gyro;
  return out;
}

}  // namespace geardyn::fe
