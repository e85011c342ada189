#pragma once
// Two-node shaft element for a hollow circular section: bending in two planes (Timoshenko or
// Euler-Bernoulli), axial and torsional, in the node frame (local z = spin axis e3).
//
// Source: Friswell, Penny, Garvey, Lees, "Dynamics of Rotating Machines", CUP 2010, chapter 5
// (Timoshenko element with shear parameter Phi = 12 E I / (kappa G A L^2), translational mass,
// rotary mass and gyroscopic matrix). The matrices are obtained here by integrating the
// interdependent interpolation shape functions of that element (Friedman & Kosmatka, Comput.
// Struct. 47 (1993) 473-481) with 4-point Gauss quadrature, which is exact for them; the result
// equals Friswell's closed forms.
//
// Sign conventions (node frame): in the e1-e3 plane the slope is ry = d ux / dz, in the e2-e3 plane
// rx = -d uy / dz (right-handed rotations). The gyroscopic matrix G is per unit spin speed about
// +e3 and enters as M q'' + Omega G q' + K q = f (docs/theory.md §1); for a thin slice of polar
// inertia dIp it gives the disk terms G(rx, ry) = +dIp, G(ry, rx) = -dIp, so that forward whirl
// frequencies rise with speed (Friswell ch. 5, with their rotations theta = rx, psi = ry).
#include "geardyn/fe/element_types.hpp"
#include "geardyn/model/model.hpp"

namespace geardyn::fe {

struct BeamProperties {
  double length = model::kNaN;             ///< L [m]
  double outer_diameter = model::kNaN;     ///< [m]
  double inner_diameter = 0.0;             ///< [m], 0 for solid
  double youngs_modulus = model::kNaN;     ///< E [Pa]
  double shear_modulus = model::kNaN;      ///< G [Pa]
  double density = model::kNaN;            ///< rho [kg/m^3]
  double shear_coefficient = model::kNaN;  ///< kappa; NaN: cowper_shear_coefficient()
  model::BeamTheory theory = model::BeamTheory::Timoshenko;
  bool rotary_inertia = true;  ///< include rho I (rotary mass) in bending
  bool gyroscopic = true;      ///< compute G (else zero)
};

struct BeamMatrices {
  Matrix12d stiffness = Matrix12d::Zero();   ///< K
  Matrix12d mass = Matrix12d::Zero();        ///< translational + rotary + axial + torsional
  Matrix12d gyroscopic = Matrix12d::Zero();  ///< G per unit spin speed (skew-symmetric)
  double shear_parameter = 0.0;              ///< Phi (0 for Euler-Bernoulli)
  double shear_coefficient = 0.0;            ///< kappa used (NaN for Euler-Bernoulli)
};

/// Cowper's shear coefficient of a hollow circular section (G. R. Cowper, "The shear coefficient
/// in Timoshenko's beam theory", J. Appl. Mech. 33 (1966) 335-340, Table 1; the value Friswell et
/// al. 2010 use in chapter 5):
///   kappa = 6 (1 + nu) (1 + m^2)^2 / ((7 + 6 nu) (1 + m^2)^2 + (20 + 12 nu) m^2),  m = d_i / d_o.
/// Solid section (m = 0): 6 (1 + nu) / (7 + 6 nu), 0.886 for nu = 0.3.
/// Precondition: -1 < nu <= 0.5, 0 <= m < 1.
double cowper_shear_coefficient(double poisson_ratio, double diameter_ratio);

/// Element matrices in the node frame, element vector (node 1: ux uy uz rx ry rz, node 2: ...).
/// Bending: 4x4 Timoshenko blocks in both planes (Phi = 0 for Euler-Bernoulli); axial EA/L with
/// consistent mass rho A L / 6 [2 1; 1 2]; torsion G J / L with consistent polar mass
/// rho J L / 6 [2 1; 1 2]; J = 2 I = pi (d_o^4 - d_i^4) / 32.
/// Throws std::invalid_argument for non-physical properties (the assembly checks input first).
BeamMatrices timoshenko_beam(const BeamProperties& properties);

}  // namespace geardyn::fe
