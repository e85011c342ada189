#pragma once
// Gmsh post-processing output: a .msh file (format 4.1, ASCII) holding the mesh and one
// $NodeData view per field, readable by the Gmsh program and by gmsh::open / gmsh::merge
// (each field becomes a post-processing view named after it).
//
// Node tags are 1 + node index and element tags 1 + element index (Gmsh needs positive, unique
// tags; the external ids may be neither). Elements are grouped into one volume entity per
// (material, element type); the entities of a material form a physical group named after it. Node
// order inside an element is Gmsh's, as in solid::Mesh. Written to a temporary file, then renamed
// into place.
#include <filesystem>
#include <vector>

#include "geardyn/meshio/vtu_writer.hpp"
#include "geardyn/solid/mesh.hpp"

namespace geardyn::meshio {

/// Writes `mesh` and `fields` (1, 3 or 9 components each: Gmsh's scalar, vector and tensor
/// views) to `path`. All fields are views at time `time`, time step 0. Throws InputError for
/// fields that do not match the mesh, std::runtime_error if the file cannot be written.
void write_gmsh_views(const std::filesystem::path& path, const solid::Mesh& mesh,
                      const std::vector<Field>& fields, double time = 0.0);

/// Gmsh element type number of an element type (4, 11, 5, 17, 6, 18).
int gmsh_element_type(solid::ElementType type);

}  // namespace geardyn::meshio
