#pragma once
// Shared plumbing of the parametric mesh generators: exclusive, deterministic use of the Gmsh
// library, and conversion of a meshed Gmsh model into a solid::Mesh.
//
// Gmsh is a process-wide singleton (one current model, global options). GmshSession holds a
// process-wide mutex for its lifetime, initialises Gmsh without reading user configuration files,
// silences the terminal and fixes every option that affects the mesh (1 thread, fixed random
// seed, fixed algorithms), so the same geometry and sizes always give the same mesh. It finalises
// Gmsh on destruction. Any other code of the process that calls Gmsh must take gmsh_mutex() too.
#include <mutex>
#include <string>
#include <unordered_map>
#include <vector>

#include "geardyn/solid/mesh.hpp"

namespace geardyn::meshgen {

/// The mutex that serialises all use of the Gmsh API inside geardyn.
std::mutex& gmsh_mutex();

/// RAII ownership of Gmsh: lock, initialise, deterministic options, one empty model `model_name`;
/// the destructor finalises Gmsh and unlocks.
class GmshSession {
 public:
  explicit GmshSession(const std::string& model_name);
  ~GmshSession();
  GmshSession(const GmshSession&) = delete;
  GmshSession& operator=(const GmshSession&) = delete;

 private:
  std::unique_lock<std::mutex> lock_;
};

/// One body of the generated mesh: the Gmsh volumes it consists of, the element set it becomes
/// and its material index (into solid::Mesh::materials).
struct GmshBody {
  std::string name;
  int material = 0;
  std::vector<int> volumes;
};

/// Converts the meshed current Gmsh model into a solid::Mesh.
///
/// Node numbering. Nodes used by several bodies are duplicated, one copy per body (bodies are
/// separate parts that touch, e.g. a gear and its damper ring): body b's nodes come after those
/// of bodies 0..b-1. Inside a body the order is: nodes on the left sector plane (theta = 0) in
/// Gmsh tag order, then nodes on the right plane (theta = sector_angle) in the order of their
/// left partners, then all others in tag order. So any set of nodes on given Gmsh entities is
/// sorted, the i-th right node of a body is the i-th left node rotated by sector_angle about z,
/// and the copies of shared nodes in two bodies come in the same order.
///
/// Periodicity is checked, not assumed: every right-plane node must have a left-plane node at
/// R(-sector_angle) x within 1e-6 * length_scale, else NumericalError. The right coordinates are
/// then set to exactly R(sector_angle) x_left (a change below that tolerance; Gmsh's periodic
/// copies differ by round-off only).
class GmshMeshExtraction {
 public:
  /// left_surfaces / right_surfaces: the Gmsh surfaces on the planes theta = 0 and theta =
  /// sector_angle (empty for a full ring). `analysis` names the generator in error messages.
  GmshMeshExtraction(std::string analysis, const std::vector<GmshBody>& bodies,
                     const std::vector<int>& left_surfaces, const std::vector<int>& right_surfaces,
                     double sector_angle, double length_scale);

  solid::Mesh& mesh() { return mesh_; }

  /// Sorted indices of body `body`'s nodes that lie on the Gmsh entities (dim, tags), including
  /// their boundaries. Nodes of the entities not used by the body are skipped.
  std::vector<int> body_nodes_on(int body, int dim, const std::vector<int>& tags) const;

  /// Index of body `body`'s copy of Gmsh node `tag`, or -1 if the body does not use it.
  int body_node(int body, std::size_t tag) const;

 private:
  std::string analysis_;
  solid::Mesh mesh_;
  std::vector<std::vector<std::size_t>> body_tags_;  ///< per body: Gmsh tags in node order
  std::vector<int> body_offset_;
  std::unordered_map<std::size_t, std::size_t> key_;  ///< Gmsh node tag -> ordering key
};

/// Gmsh tags of the surfaces whose every boundary vertex and whose centre of mass lie on the
/// half-plane through the z axis at angle `theta` (tolerance `tol`, m).
std::vector<int> surfaces_on_half_plane(double theta, double tol);

/// Gmsh tags of the surfaces among `candidates` whose every boundary vertex lies at distance
/// `radius` from the z axis (tolerance `tol`), i.e. cylindrical faces about z of that radius.
std::vector<int> surfaces_at_radius(const std::vector<int>& candidates, double radius, double tol);

/// Tags of the boundary surfaces of the given volumes (union, sorted).
std::vector<int> boundary_surfaces(const std::vector<int>& volumes);

}  // namespace geardyn::meshgen
