#pragma once
// A short rotor on two bearings (shaft "s" along z from z = -0.2 m, 4 elements, s.2 at z = 0)
// and an annular plate at z = 0 about the shaft, as TOML text for the tests of solids joined to
// the rotor.
//
//        bearing            plate (b = 20 mm, a = 150 mm, h = 10 mm)          bearing
//   s.0 ====|=====s.1=========s.2=========s.3=====|==== s.4      d = 40 mm, L = 0.4 m
//           k                  |                  k
#include <fmt/format.h>

#include <cmath>
#include <numbers>
#include <string>

namespace geardyn::test {

inline constexpr double kPlateInner = 0.02, kPlateOuter = 0.15, kPlateThickness = 0.01;
inline constexpr double kDensity = 7800.0;

/// The rotor; `extra` is appended (solids, disks, sensors, analyses).
inline std::string spider_rotor(const std::string& extra) {
  return R"(version = 1

[[materials]]
name = "steel"
youngs_modulus = 2.1e11
poisson_ratio = 0.3
density = 7800.0

[[materials]]
name = "stiff"
youngs_modulus = 2.1e15
poisson_ratio = 0.3
density = 7800.0

[[shafts]]
name = "s"
material = "steel"
origin = [0.0, 0.0, -0.2]
  [[shafts.elements]]
  length = 0.4
  outer_diameter = 0.04
  divisions = 4

[[bearings]]
node = "s.0"
kxx = 1e7
kyy = 1e7
kzz = 1e7

[[bearings]]
node = "s.4"
kxx = 1e7
kyy = 1e7

[[constraints]]
node = "s.0"
dofs = ["rz"]
)" + extra;
}

/// The plate as a [[solids]] entry joined to s.2 through its "inner" node set.
inline std::string spider_plate(const std::string& material, int coupling_modes,
                                const std::string& kind = "rigid",
                                const std::string& node_set = "inner") {
  return fmt::format(R"(
[[solids]]
name = "disk"
type = "annular_plate"
material = "{}"
inner_radius = {}
outer_radius = {}
thickness = {}
radial_elements = 4
circumferential_elements = 24
layers = 1
order = 2
coupling_modes = {}
  [[solids.spiders]]
  node_set = "{}"
  node = "s.2"
  kind = "{}"
)",
                     material, kPlateInner, kPlateOuter, kPlateThickness, coupling_modes, node_set,
                     kind);
}

/// Uniform annular disk: m = rho pi (a^2 - b^2) h, Ip = m (a^2 + b^2) / 2,
/// Id = m (3 (a^2 + b^2) + h^2) / 12 (about a diameter through the centre of mass).
struct PlateInertia {
  double mass, polar, diametral;
};
inline PlateInertia plate_inertia() {
  const double a2 = kPlateOuter * kPlateOuter, b2 = kPlateInner * kPlateInner;
  const double h = kPlateThickness;
  const double m = kDensity * std::numbers::pi * (a2 - b2) * h;
  return {m, m * (a2 + b2) / 2.0, m * (3.0 * (a2 + b2) + h * h) / 12.0};
}

}  // namespace geardyn::test
