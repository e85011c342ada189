#pragma once
// The benchmark gear sector, shared by bench/solid_bench.cpp and bench/export_matrices.cpp (the
// scipy comparison must run on the very mesh BM_SectorModes30 times): one sector of N = 10 of a
// z = 40, m = 4.5 mm steel spur gear (the blank of tests/meshgen/gear_sector_test.cpp without
// the damper ring), quadratic tets, free-free (six rigid-body modes among the lowest).
#include "geardyn/meshgen/gear_sector.hpp"

namespace geardyn::bench {

/// Mesh sizes [m] (global, tooth) of the coarse (27 021 DOFs) and fine (270 237 DOFs) sector.
inline constexpr double kCoarseSizes[2] = {0.0060, 0.0030};
inline constexpr double kFineSizes[2] = {0.0020, 0.0013};

inline meshgen::GearSectorParams sector_params(double global_size, double tooth_size) {
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
  p.mesh.global = global_size;
  p.mesh.tooth = tooth_size;
  p.mesh.element_order = 2;
  p.gear_material = {"steel", 1, 210e9, 0.3, 7850, {}};
  return p;
}

}  // namespace geardyn::bench
