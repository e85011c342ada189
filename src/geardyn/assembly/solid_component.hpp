#pragma once
// The solid components of a model, built once per run: the mesh read (Gmsh, Nastran) or
// generated (annular plate, gear sector), checked, with its fixed node sets applied and K, M
// assembled; a reduced component loaded from its file; or K, M and their DOF map read from
// Matrix Market files exported by another FE code. Bad meshes, missing node sets and
// inverted elements are InputErrors raised here, before any analysis runs or any result is
// written.
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "geardyn/core/progress.hpp"
#include "geardyn/model/model.hpp"
#include "geardyn/reduce/reduced_component.hpp"
#include "geardyn/solid/assembly.hpp"
#include "geardyn/solid/mesh.hpp"

namespace geardyn::assembly {

struct SolidComponent {
  std::string name;
  int sectors = 1;                    ///< the body is this many copies of the mesh about z
  double interface_tolerance = 1e-6;  ///< [m]
  solid::Mesh mesh;                   ///< empty for reduced and matrices components
  /// Assembled mesh; for type = "matrices" only dofs, K and M (the imported matrices); empty for
  /// a reduced component.
  solid::SolidSystem system;
  std::optional<reduce::ReducedComponent> reduced;  ///< type = "reduced"
  bool external_matrices = false;                   ///< type = "matrices"
  std::string source_sha256;  ///< of the mesh / reduced file, or of the generator parameters
  std::string description;    ///< one line: source, nodes, elements, DOFs
  std::vector<std::string> warnings;  ///< e.g. Nastran cards skipped

  bool is_reduced() const { return reduced.has_value(); }
  /// A mesh stands behind K and M: node sets, element shapes and full-wheel replication exist.
  bool has_mesh() const { return !is_reduced() && !external_matrices; }
  /// "reduced", "matrices" or "mesh", for messages.
  std::string kind() const;
  /// DOF list, stiffness and mass the analyses work on: the assembled mesh, or the reduced
  /// component's coordinates.
  std::vector<solid::DofInfo> dofs() const;
  Eigen::SparseMatrix<double> stiffness() const;
  Eigen::SparseMatrix<double> mass() const;
};

using SolidComponents = std::map<std::string, SolidComponent>;

/// Material of the solid FE from a model material (nu = E / (2 G) - 1).
solid::Material solid_material(const model::Material& m);

/// Builds one solid. Paths are relative to the model file's folder. Throws InputError for bad
/// input (file, key, what was expected and found).
SolidComponent build_solid(const model::Model& model, const model::Solid& solid,
                           Progress& progress = null_progress());

/// Builds every [[solids]] entry the enabled analyses (or all, if `all`) use.
SolidComponents build_solids(const model::Model& model, Progress& progress = null_progress());

/// Checks what the model asks of the built solids that the parser cannot know: the node sets of
/// spiders and solid sensors exist in the meshes. Throws InputError (key solids[i].spiders[k]...).
void check_solid_sets(const model::Model& model, const SolidComponents& solids);

}  // namespace geardyn::assembly
