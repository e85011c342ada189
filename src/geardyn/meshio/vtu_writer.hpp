#pragma once
// VTK XML UnstructuredGrid (.vtu) output of a solid mesh with nodal fields, and .pvd
// collections for a set of modes or steps, for ParaView.
//
// Binary: every array is stored in one raw appended-data block, zlib-compressed in blocks of
// 32 KiB (VTK's vtkZLibDataCompressor layout: a UInt64 header [blocks, block size, last block
// size, compressed size of each block], then the compressed blocks; VTK file-formats
// documentation, "XML File Formats", appended data). A 247 MB ASCII wheel of modes becomes a
// few tens of MB, read by ParaView 5.x without conversion.
//
// Cell types and node order (VTK file-formats documentation, "Linear / Non-linear cell types",
// and the class documentation of vtkQuadraticTetra / vtkQuadraticHexahedron /
// vtkQuadraticWedge):
//   tet4 -> VTK_TETRA (10), tet10 -> VTK_QUADRATIC_TETRA (24): Gmsh order with the last two
//     mid-edge nodes swapped (VTK: edges (0,1) (1,2) (2,0) (0,3) (1,3) (2,3)).
//   hex8 -> VTK_HEXAHEDRON (12), same order; hex20 -> VTK_QUADRATIC_HEXAHEDRON (25), mid-edge
//     nodes on (0,1) (1,2) (2,3) (3,0) (4,5) (5,6) (6,7) (7,4) (0,4) (1,5) (2,6) (3,7).
//   wedge6 -> VTK_WEDGE (13), same corner order; wedge15 -> VTK_QUADRATIC_WEDGE (26), mid-edge
//     nodes on (0,1) (1,2) (2,0) (3,4) (4,5) (5,3) (0,3) (1,4) (2,5). The corners are kept in
//     Gmsh order, which is what VTK's wedge parametric coordinates (and Gmsh's own VTK export)
//     use; the VTK class comment claiming the opposite orientation of (0,1,2) is known to
//     disagree with the implementation.
// Files are written to a temporary sibling and renamed into place, so a reader never sees a
// partial file.
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include "geardyn/solid/mesh.hpp"

namespace geardyn::meshio {

/// A nodal field: num_components values per node, node-major (node i's values at
/// [i * num_components, (i + 1) * num_components)). E.g. the real part of a mode shape:
/// name "mode_3_re", 3 components (ux, uy, uz).
struct Field {
  std::string name;
  int num_components = 3;
  std::vector<double> values;
};

/// Throws InputError if a field's size does not match the mesh (key "fields[i]"), a name is
/// empty or repeats, or an element references a node outside the mesh.
void check_fields(const solid::Mesh& mesh, const std::vector<Field>& fields);

/// Writes `mesh` with point data `fields` (plus "node_id") and cell data "material" and
/// "element_id". Throws std::runtime_error if the file cannot be written.
void write_vtu(const std::filesystem::path& path, const solid::Mesh& mesh,
               const std::vector<Field>& fields);

/// A set of states on one mesh (modes, frequencies, time steps): writes one .vtu per state,
/// named <pvd stem>_<k>.vtu next to `pvd_path`, and the .pvd collection referencing them with
/// timestep = times[k] (e.g. the natural frequency in Hz). Returns the .vtu paths.
std::vector<std::filesystem::path> write_vtu_series(const std::filesystem::path& pvd_path,
                                                    const solid::Mesh& mesh,
                                                    const std::vector<std::vector<Field>>& states,
                                                    const std::vector<double>& times);

/// Cells of a surface (or any 2D patch) on a subset of a mesh's nodes, e.g. the radiating
/// surface of a housing (acoustics/surface.hpp).
struct SurfaceCells {
  std::vector<int> points;  ///< mesh node index of each output point
  /// Indices into `points` in VTK node order: 3 (VTK_TRIANGLE), 6 (VTK_QUADRATIC_TRIANGLE),
  /// 4 (VTK_QUAD) or 8 (VTK_QUADRATIC_QUAD) nodes: corners, then mid-edge nodes of (0,1) (1,2) ...
  std::vector<std::vector<int>> cells;
  std::vector<long> cell_ids;  ///< written as cell data "element_id" (one per cell, or empty)
};

/// Writes the surface `cells` of `mesh` with cell data `cell_fields` (values cell-major, one set
/// per cell) and point data `point_fields` (one set per entry of cells.points), plus "node_id".
/// Throws InputError for a field of the wrong size or a repeated/empty name, a point outside the
/// mesh, a cell of another node count or with an index outside `points`; std::runtime_error if
/// the file cannot be written.
void write_surface_vtu(const std::filesystem::path& path, const solid::Mesh& mesh,
                       const SurfaceCells& cells, const std::vector<Field>& cell_fields,
                       const std::vector<Field>& point_fields);

/// VTK cell type of an element type.
int vtk_cell_type(solid::ElementType type);

/// vtk_order(type)[i] = index in the Gmsh-ordered element of VTK's node i.
const std::vector<int>& vtk_order(solid::ElementType type);

/// Writes `content` to a temporary file next to `path`, then renames it to `path`.
void write_file_atomically(const std::filesystem::path& path, std::string_view content);

}  // namespace geardyn::meshio
