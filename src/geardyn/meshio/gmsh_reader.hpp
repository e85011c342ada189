#pragma once
// Reader for Gmsh meshes (.msh, any version Gmsh 4.8 reads, typically MSH 4.1) through the Gmsh
// API, as solid::Mesh.
//
// What is read
//   Volume elements of types 4 (tet4), 11 (tet10), 5 (hex8), 17 (hex20), 6 (prism6) and
//   18 (prism15), already in Gmsh's node order; a volume element of another type (pyramid,
//   complete second order, third order) is an InputError. Points, lines and surface elements
//   only serve physical groups. Elements are mirrored where their corner volume is negative
//   (element_ordering.hpp); a degenerate element is an InputError.
//   Nodes: those of the volume elements and those of physical groups, ordered by Gmsh node tag
//   (Mesh::node_ids = tags); other nodes (e.g. of unmeshed construction curves) are dropped.
//   Physical groups of any dimension become node sets named after the group (all nodes of its
//   entities, boundaries included; unnamed groups are called "physical_<dim>_<tag>"); groups of
//   dimension 3 also become element sets. Groups of the same name are merged.
//   Materials: a .msh file carries none. Elements of a physical volume named in
//   GmshReadOptions::volume_materials get that material, the others default_material.
//
// Gmsh is a process-wide singleton; the reader holds meshgen::gmsh_mutex() for the whole read
// (so it is safe with the mesh generators and with other threads) and finalises Gmsh before it
// returns, also on errors. Nothing is printed.
#include <filesystem>
#include <map>
#include <string>

#include "geardyn/solid/mesh.hpp"

namespace geardyn::meshio {

struct GmshReadOptions {
  /// Material of the elements not in a physical volume of `volume_materials`. Needed (E > 0,
  /// -1 < nu < 0.5, rho >= 0) only if some element uses it; Material::where locates errors.
  solid::Material default_material;
  /// Physical volume name -> material. A name that is not a physical volume of the file is an
  /// InputError listing the available ones; an element in two listed volumes with different
  /// materials too.
  std::map<std::string, solid::Material> volume_materials;
};

/// Reads the mesh at `path`. Throws InputError for a missing or unreadable file, a file Gmsh
/// rejects (its message is passed on), a file without supported volume elements, and the cases
/// listed above.
solid::Mesh read_gmsh(const std::filesystem::path& path, const GmshReadOptions& options = {});

}  // namespace geardyn::meshio
