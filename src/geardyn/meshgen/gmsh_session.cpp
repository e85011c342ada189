#include "geardyn/meshgen/gmsh_session.hpp"

#include <fmt/format.h>
#include <gmsh.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <numeric>
#include <set>
#include <unordered_map>

namespace geardyn::meshgen {

std::mutex& gmsh_mutex() {
  static std::mutex mutex;
  return mutex;
}

GmshSession::GmshSession(const std::string& model_name) : lock_(gmsh_mutex()) {
  // readConfigFiles = false: a user's gmshrc must not change the mesh.
  gmsh::initialize(0, nullptr, false);
  try {
    gmsh::option::setNumber("General.Terminal", 0);
    gmsh::option::setNumber("General.Verbosity", 2);
    // Every option below that can change the mesh is set explicitly (to its documented value),
    // so the result does not depend on defaults of another Gmsh build or on thread scheduling.
    gmsh::option::setNumber("General.NumThreads", 1);
    gmsh::option::setNumber("Mesh.MaxNumThreads1D", 1);
    gmsh::option::setNumber("Mesh.MaxNumThreads2D", 1);
    gmsh::option::setNumber("Mesh.MaxNumThreads3D", 1);
    gmsh::option::setNumber("Mesh.RandomSeed", 1);
    gmsh::option::setNumber("Mesh.RandomFactor", 1e-9);
    gmsh::option::setNumber("Mesh.Algorithm", 6);  // Frontal-Delaunay (2D)
    // Delaunay (3D), sequential. (HXT, 10, gives better tets but differs from run to run even
    // on one thread, so it cannot be used.)
    gmsh::option::setNumber("Mesh.Algorithm3D", 1);
    gmsh::option::setNumber("Mesh.Optimize", 1);
    gmsh::option::setNumber("Mesh.OptimizeNetgen", 0);
    gmsh::option::setNumber("Mesh.HighOrderOptimize", 0);
    gmsh::option::setNumber("Mesh.SecondOrderLinear", 0);      // mid-nodes on the geometry
    gmsh::option::setNumber("Mesh.SecondOrderIncomplete", 1);  // hex20 / wedge15, not 27 / 18
    gmsh::option::setNumber("Mesh.MeshSizeFromCurvature", 0);
    gmsh::option::setNumber("Mesh.MeshSizeExtendFromBoundary", 1);
    gmsh::option::setNumber("Mesh.MeshSizeFromPoints", 1);
    gmsh::option::setNumber("Geometry.OCCParallel", 0);
    gmsh::model::add(model_name);
  } catch (...) {
    gmsh::finalize();
    throw;
  }
}

GmshSession::~GmshSession() { gmsh::finalize(); }

namespace {

solid::ElementType element_type_of(int gmsh_type, const std::string& analysis) {
  switch (gmsh_type) {
    case 4:
      return solid::ElementType::Tet4;
    case 11:
      return solid::ElementType::Tet10;
    case 5:
      return solid::ElementType::Hex8;
    case 17:
      return solid::ElementType::Hex20;
    case 6:
      return solid::ElementType::Wedge6;
    case 18:
      return solid::ElementType::Wedge15;
    default:
      break;
  }
  throw NumericalError(analysis,
                       fmt::format("Gmsh produced volume elements of type {} (pyramids or "
                                   "complete high-order elements), which geardyn does not support",
                                   gmsh_type));
}

std::vector<std::size_t> node_tags_on(int dim, const std::vector<int>& tags) {
  std::vector<std::size_t> out;
  for (int tag : tags) {
    std::vector<std::size_t> node_tags;
    std::vector<double> coords, params;
    gmsh::model::mesh::getNodes(node_tags, coords, params, dim, tag, true, false);
    out.insert(out.end(), node_tags.begin(), node_tags.end());
  }
  std::sort(out.begin(), out.end());
  out.erase(std::unique(out.begin(), out.end()), out.end());
  return out;
}

Eigen::Vector3d rotate_z(const Eigen::Vector3d& x, double angle) {
  const double c = std::cos(angle), s = std::sin(angle);
  return {c * x.x() - s * x.y(), s * x.x() + c * x.y(), x.z()};
}

}  // namespace

GmshMeshExtraction::GmshMeshExtraction(std::string analysis, const std::vector<GmshBody>& bodies,
                                       const std::vector<int>& left_surfaces,
                                       const std::vector<int>& right_surfaces, double sector_angle,
                                       double length_scale)
    : analysis_(std::move(analysis)) {
  std::unordered_map<std::size_t, Eigen::Vector3d> coord_of;
  {
    std::vector<std::size_t> tags;
    std::vector<double> coords, params;
    gmsh::model::mesh::getNodes(tags, coords, params, -1, -1, false, false);
    coord_of.reserve(tags.size());
    for (std::size_t i = 0; i < tags.size(); ++i)
      coord_of[tags[i]] = Eigen::Vector3d(coords[3 * i], coords[3 * i + 1], coords[3 * i + 2]);
  }

  // Ordering key: left-plane nodes, right-plane nodes (in the order of their partners), rest.
  const std::vector<std::size_t> left = node_tags_on(2, left_surfaces);
  const std::vector<std::size_t> right = node_tags_on(2, right_surfaces);
  if (left.size() != right.size())
    throw NumericalError(analysis_, fmt::format("the sector's left face has {} nodes but the right "
                                                "face has {}: the mesh is not periodic",
                                                left.size(), right.size()));
  std::unordered_map<std::size_t, std::size_t> key;
  key.reserve(coord_of.size());
  for (std::size_t i = 0; i < left.size(); ++i) key[left[i]] = i;
  if (!right.empty()) {
    // Pair each right node with the left node at R(-alpha) x: left nodes sorted by x, then a
    // window search, O(n log n).
    const double tol = 1e-6 * length_scale;
    std::vector<std::pair<double, std::size_t>> by_x;
    by_x.reserve(left.size());
    for (std::size_t t : left) by_x.emplace_back(coord_of.at(t).x(), t);
    std::sort(by_x.begin(), by_x.end());
    std::set<std::size_t> used;
    for (std::size_t t : right) {
      const Eigen::Vector3d back = rotate_z(coord_of.at(t), -sector_angle);
      auto it = std::lower_bound(by_x.begin(), by_x.end(), std::make_pair(back.x() - tol, 0UL));
      std::size_t best = 0;
      bool found = false;
      double best_distance = tol;
      for (; it != by_x.end() && it->first <= back.x() + tol; ++it) {
        const double d = (coord_of.at(it->second) - back).norm();
        if (d <= best_distance) {
          best_distance = d;
          best = it->second;
          found = true;
        }
      }
      if (!found || !used.insert(best).second)
        throw NumericalError(
            analysis_,
            fmt::format("right-face node at ({:.6g}, {:.6g}, {:.6g}) has no left-face "
                        "node at the same place rotated back by {:.6g} rad: the mesh "
                        "is not periodic",
                        coord_of.at(t).x(), coord_of.at(t).y(), coord_of.at(t).z(), sector_angle));
      key[t] = left.size() + key.at(best);
      coord_of[t] = rotate_z(coord_of.at(best), sector_angle);
    }
  }
  {
    std::vector<std::size_t> rest;
    for (const auto& [tag, x] : coord_of)
      if (!key.count(tag)) rest.push_back(tag);
    std::sort(rest.begin(), rest.end());
    const std::size_t first = left.size() + right.size();
    for (std::size_t i = 0; i < rest.size(); ++i) key[rest[i]] = first + i;
  }

  mesh_.source = analysis_;
  int offset = 0;
  for (std::size_t b = 0; b < bodies.size(); ++b) {
    const GmshBody& body = bodies[b];
    struct RawElement {
      int type;
      std::size_t tag;
      std::vector<std::size_t> nodes;
    };
    std::vector<RawElement> raw;
    std::vector<std::size_t> used;
    for (int volume : body.volumes) {
      std::vector<int> types;
      std::vector<std::vector<std::size_t>> element_tags, node_tags;
      gmsh::model::mesh::getElements(types, element_tags, node_tags, 3, volume);
      for (std::size_t k = 0; k < types.size(); ++k) {
        const int n = solid::num_element_nodes(element_type_of(types[k], analysis_));
        for (std::size_t e = 0; e < element_tags[k].size(); ++e) {
          RawElement r{types[k], element_tags[k][e],
                       std::vector<std::size_t>(node_tags[k].begin() + e * n,
                                                node_tags[k].begin() + (e + 1) * n)};
          used.insert(used.end(), r.nodes.begin(), r.nodes.end());
          raw.push_back(std::move(r));
        }
      }
    }
    std::sort(used.begin(), used.end(),
              [&](std::size_t a, std::size_t c) { return key.at(a) < key.at(c); });
    used.erase(std::unique(used.begin(), used.end()), used.end());
    std::unordered_map<std::size_t, int> index;
    index.reserve(used.size());
    for (std::size_t i = 0; i < used.size(); ++i) {
      index[used[i]] = offset + static_cast<int>(i);
      mesh_.coords.push_back(coord_of.at(used[i]));
      mesh_.node_ids.push_back(offset + static_cast<long>(i) + 1);
    }
    std::sort(raw.begin(), raw.end(),
              [](const RawElement& a, const RawElement& c) { return a.tag < c.tag; });
    std::vector<int>& set = mesh_.element_sets[body.name];
    for (const RawElement& r : raw) {
      solid::Element element;
      element.type = element_type_of(r.type, analysis_);
      element.id = static_cast<long>(r.tag);
      element.material = body.material;
      element.nodes.reserve(r.nodes.size());
      for (std::size_t t : r.nodes) element.nodes.push_back(index.at(t));
      set.push_back(mesh_.num_elements());
      mesh_.elements.push_back(std::move(element));
    }
    body_offset_.push_back(offset);
    offset += static_cast<int>(used.size());
    body_tags_.push_back(std::move(used));
  }
  // body_node() answers by binary search on the key in the body's key-sorted tag list.
  key_ = std::move(key);
}

int GmshMeshExtraction::body_node(int body, std::size_t tag) const {
  const auto k = key_.find(tag);
  if (k == key_.end()) return -1;
  const std::vector<std::size_t>& tags = body_tags_.at(static_cast<std::size_t>(body));
  const auto it =
      std::lower_bound(tags.begin(), tags.end(), k->second,
                       [&](std::size_t t, std::size_t value) { return key_.at(t) < value; });
  if (it == tags.end() || *it != tag) return -1;
  return body_offset_.at(static_cast<std::size_t>(body)) + static_cast<int>(it - tags.begin());
}

std::vector<int> GmshMeshExtraction::body_nodes_on(int body, int dim,
                                                   const std::vector<int>& tags) const {
  std::vector<int> out;
  for (std::size_t t : node_tags_on(dim, tags)) {
    const int i = body_node(body, t);
    if (i >= 0) out.push_back(i);
  }
  std::sort(out.begin(), out.end());
  return out;
}

std::vector<int> boundary_surfaces(const std::vector<int>& volumes) {
  std::set<int> out;
  for (int v : volumes) {
    gmsh::vectorpair faces;
    gmsh::model::getBoundary({{3, v}}, faces, false, false, false);
    for (const auto& [dim, tag] : faces) out.insert(tag);
  }
  return {out.begin(), out.end()};
}

namespace {

std::vector<Eigen::Vector3d> surface_vertices(int surface) {
  gmsh::vectorpair points;
  gmsh::model::getBoundary({{2, surface}}, points, false, false, true);
  std::vector<Eigen::Vector3d> out;
  for (const auto& [dim, tag] : points) {
    if (dim != 0) continue;
    double x0, y0, z0, x1, y1, z1;
    gmsh::model::getBoundingBox(0, tag, x0, y0, z0, x1, y1, z1);
    out.emplace_back(0.5 * (x0 + x1), 0.5 * (y0 + y1), 0.5 * (z0 + z1));
  }
  return out;
}

}  // namespace

std::vector<int> surfaces_on_half_plane(double theta, double tol) {
  const Eigen::Vector3d along(std::cos(theta), std::sin(theta), 0.0);
  const Eigen::Vector3d normal(-std::sin(theta), std::cos(theta), 0.0);
  auto on_plane = [&](const Eigen::Vector3d& x) {
    return std::abs(normal.dot(x)) <= tol && along.dot(x) > -tol;
  };
  gmsh::vectorpair surfaces;
  gmsh::model::getEntities(surfaces, 2);
  std::vector<int> out;
  for (const auto& [dim, tag] : surfaces) {
    const std::vector<Eigen::Vector3d> vertices = surface_vertices(tag);
    if (vertices.empty() || !std::all_of(vertices.begin(), vertices.end(), on_plane)) continue;
    // All vertices on the plane, and the surface's parametric centre too (a curved face could
    // have its vertices there, a face of the plane has every point there).
    std::vector<double> lo, hi, point;
    gmsh::model::getParametrizationBounds(2, tag, lo, hi);
    gmsh::model::getValue(2, tag, {0.5 * (lo[0] + hi[0]), 0.5 * (lo[1] + hi[1])}, point);
    if (on_plane(Eigen::Vector3d(point[0], point[1], point[2]))) out.push_back(tag);
  }
  std::sort(out.begin(), out.end());
  return out;
}

std::vector<int> surfaces_at_radius(const std::vector<int>& candidates, double radius, double tol) {
  std::vector<int> out;
  for (int tag : candidates) {
    const std::vector<Eigen::Vector3d> vertices = surface_vertices(tag);
    if (!vertices.empty() &&
        std::all_of(vertices.begin(), vertices.end(), [&](const Eigen::Vector3d& x) {
          return std::abs(std::hypot(x.x(), x.y()) - radius) <= tol;
        }))
      out.push_back(tag);
  }
  return out;
}

}  // namespace geardyn::meshgen
