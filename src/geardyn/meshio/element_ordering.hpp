#pragma once
// Node ordering of solid elements: conversion from Nastran's connectivity to Gmsh's (the order
// solid::Element uses, documented in solid/mesh.hpp) and orientation to a positive volume.
//
// Both conventions list the corners first and then one node per edge; they differ only in the
// order of the edges. Each convention is written down once as its edge table and the
// permutation is derived by matching edges, so a table can be checked against the manual line by
// line:
//   Nastran (MSC/NX Quick Reference Guide, CTETRA / CHEXA / CPENTA, 1-based grid numbers)
//     CTETRA  G5..G10  = edges 1-2 2-3 3-1 1-4 2-4 3-4
//     CHEXA   G9..G20  = edges 1-2 2-3 3-4 4-1 1-5 2-6 3-7 4-8 5-6 6-7 7-8 8-5
//     CPENTA  G7..G15  = edges 1-2 2-3 3-1 1-4 2-5 3-6 4-5 5-6 6-4
//   Gmsh (reference manual, "Node ordering"): see solid/mesh.hpp.
#include <Eigen/Dense>
#include <span>
#include <utility>
#include <vector>

#include "geardyn/solid/mesh.hpp"

namespace geardyn::meshio {

/// Number of corner nodes of an element type (4, 8 or 6).
int num_corner_nodes(solid::ElementType type);

/// Whether `type` has mid-edge nodes.
bool is_quadratic(solid::ElementType type);

/// The edges (pairs of 0-based corner indices) whose mid-edge nodes follow the corners, in the
/// order the convention lists them. Empty for linear types.
std::span<const std::pair<int, int>> gmsh_edges(solid::ElementType type);
std::span<const std::pair<int, int>> nastran_edges(solid::ElementType type);

/// Reorders one element's nodes from Nastran's order to Gmsh's. `nodes.size()` must equal
/// num_element_nodes(type).
std::vector<int> nastran_to_gmsh(solid::ElementType type, const std::vector<int>& nodes);

/// Outcome of orient_positive.
enum class Orientation { Positive, Flipped, Degenerate };

/// Makes the element's volume positive in Gmsh's convention (the Jacobian at the reference
/// centroid, computed from the corners, is > 0), mirroring the connectivity when it is negative.
/// Nastran accepts either orientation of a solid; a mirrored connectivity describes the same
/// element. Returns Degenerate (and leaves `nodes` unchanged) when the corner volume is zero to
/// within 1e-12 of the cube of the longest corner-to-centroid distance.
Orientation orient_positive(solid::ElementType type, std::vector<int>& nodes,
                            const std::vector<Eigen::Vector3d>& coords);

/// Signed volume measure of the corner configuration (six times the volume for a tet, the
/// Jacobian determinant at the centroid times the reference volume for hex and wedge): > 0 for
/// Gmsh's orientation.
double corner_volume_measure(solid::ElementType type, const std::vector<int>& nodes,
                             const std::vector<Eigen::Vector3d>& coords);

}  // namespace geardyn::meshio
