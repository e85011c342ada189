#pragma once
// The damper-ring gear sector of the tests (meshgen, damper): one sector of N = 10 of a z = 40,
// m = 4.5 mm steel spur gear with a groove in the rim bore and its split ring,
//   bore 0.020 | hub 0.035 x 40 mm | web 8 mm | rim 0.070..root, face 30 mm
//   groove 0.070..0.074 at z = 9 +- 4 mm; ring r 0.069..0.074, z = 9 +- 3 mm.
#include "geardyn/meshgen/gear_sector.hpp"

namespace geardyn::test {

inline meshgen::GearSectorParams damper_gear(int order = 2) {
  meshgen::GearSectorParams p;
  p.num_sectors = 10;
  p.num_teeth = 40;
  p.bore_radius = 0.020;
  p.hub_outer_radius = 0.035;
  p.hub_width = 0.040;
  p.web_thickness = 0.008;
  p.rim_inner_radius = 0.070;
  p.face_width = 0.030;
  p.tooth.module = 0.0045;
  p.groove = meshgen::GrooveParams{0.009, 0.008, 0.004, meshgen::RingParams{0.006, 0.009, 0.005}};
  p.mesh.global = 0.010;
  p.mesh.tooth = 0.003;
  p.mesh.groove = 0.002;
  p.mesh.element_order = order;
  p.gear_material = {"steel", 1, 210e9, 0.3, 7850, {}};
  p.ring_material = {"ring steel", 2, 200e9, 0.29, 7800, {}};
  return p;
}

}  // namespace geardyn::test
