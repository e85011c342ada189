#include "geardyn/cyclic/cyclic_symmetry.hpp"

#include <fmt/format.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <limits>
#include <unordered_map>
#include <unordered_set>

#include "geardyn/core/error.hpp"
#include "geardyn/core/units.hpp"

namespace geardyn::cyclic {

using Complex = std::complex<double>;
using ComplexSparse = Eigen::SparseMatrix<Complex>;

Eigen::Matrix3d rotation(const Eigen::Vector3d& axis, double angle) {
  return Eigen::AngleAxisd(angle, axis.normalized()).toRotationMatrix();
}

namespace {

[[noreturn]] void input_error(const std::string& key, const std::string& expected,
                              const std::string& found, const std::string& hint = {}) {
  throw InputError({}, key, expected, found, hint);
}

std::string list_ids(const std::vector<long>& ids, std::size_t shown = 10) {
  std::string out;
  for (std::size_t i = 0; i < std::min(shown, ids.size()); ++i)
    out += (i ? ", " : "") + std::to_string(ids[i]);
  if (ids.size() > shown) out += fmt::format(" (and {} more)", ids.size() - shown);
  return out;
}

// Uniform grid of cell size h over points; a query returns the nearest stored point within
// `radius` <= h by scanning the 27 cells around the query (every point within h of the query
// lies in one of them).
class SpatialHash {
 public:
  SpatialHash(double cell, const std::vector<Eigen::Vector3d>& points, std::vector<int> members)
      : cell_(cell), points_(points) {
    for (int i : members)
      cells_[key(cell_index(points_[static_cast<std::size_t>(i)]))].push_back(i);
  }
  // Index of the nearest member within radius, -1 if none; distance in `best`.
  int nearest(const Eigen::Vector3d& x, double radius, double& best) const {
    const Eigen::Array3i c = cell_index(x);
    int found = -1;
    best = std::numeric_limits<double>::infinity();
    for (int dx = -1; dx <= 1; ++dx)
      for (int dy = -1; dy <= 1; ++dy)
        for (int dz = -1; dz <= 1; ++dz) {
          const auto it = cells_.find(key(c + Eigen::Array3i(dx, dy, dz)));
          if (it == cells_.end()) continue;
          for (int i : it->second) {
            const double d = (points_[static_cast<std::size_t>(i)] - x).norm();
            if (d <= radius && d < best) {
              best = d;
              found = i;
            }
          }
        }
    return found;
  }

 private:
  Eigen::Array3i cell_index(const Eigen::Vector3d& x) const {
    return (x.array() / cell_).floor().cast<int>();
  }
  static std::uint64_t key(const Eigen::Array3i& c) {
    const auto u = [](int v) { return static_cast<std::uint64_t>(static_cast<std::uint32_t>(v)); };
    return (u(c[0]) * 0x9E3779B97F4A7C15ULL) ^ (u(c[1]) * 0xC2B2AE3D27D4EB4FULL) ^
           (u(c[2]) * 0x165667B19E3779F9ULL);
  }
  double cell_;
  const std::vector<Eigen::Vector3d>& points_;
  std::unordered_map<std::uint64_t, std::vector<int>> cells_;
};

}  // namespace

namespace {

// The checks of the options and of the node lists.
void check_interface_input(const std::vector<long>& node_ids,
                           const std::vector<Eigen::Vector3d>& coords,
                           const InterfaceOptions& options, const std::string& key) {
  if (options.n_sectors < 2)
    input_error(key + ".n_sectors", "N >= 2 sectors", std::to_string(options.n_sectors));
  if (!(options.axis.norm() > 0.0) || !options.axis.allFinite())
    input_error(key + ".axis", "a non-zero finite axis vector",
                fmt::format("({}, {}, {})", options.axis.x(), options.axis.y(), options.axis.z()));
  if (node_ids.size() != coords.size())
    input_error(key, "one coordinate per node id",
                fmt::format("{} ids, {} coordinates", node_ids.size(), coords.size()));
  if (node_ids.empty()) input_error(key, "a sector with nodes", "no nodes");
  if (!std::isnan(options.tolerance) &&
      !(options.tolerance > 0.0 && std::isfinite(options.tolerance)))
    input_error(key + ".tolerance", "a positive tolerance [m] or NaN (automatic)",
                fmt::format("{}", options.tolerance));
  if (options.left_nodes.empty() != options.right_nodes.empty())
    input_error(key, "left and right node sets both given or both empty",
                fmt::format("{} left, {} right nodes", options.left_nodes.size(),
                            options.right_nodes.size()));
}

// The left and right nodes (indices) given by id in the options.
void given_sides(const std::vector<long>& node_ids, const InterfaceOptions& options,
                 const std::string& key, std::vector<int>& left, std::vector<int>& right) {
  const std::size_t n = node_ids.size();
  std::unordered_map<long, int> index;
  for (std::size_t i = 0; i < n; ++i) index.emplace(node_ids[i], static_cast<int>(i));
  auto lookup = [&](const std::vector<long>& ids, const char* side, std::vector<int>& into) {
    std::vector<long> missing;
    for (long id : ids) {
      const auto it = index.find(id);
      if (it == index.end())
        missing.push_back(id);
      else
        into.push_back(it->second);
    }
    if (!missing.empty())
      input_error(key + "." + side + "_nodes", "ids of sector nodes",
                  fmt::format("unknown node id(s) {}", list_ids(missing)));
  };
  lookup(options.left_nodes, "left", left);
  lookup(options.right_nodes, "right", right);
  std::unordered_set<int> left_set(left.begin(), left.end());
  std::vector<long> both;
  for (int i : right)
    if (left_set.count(i)) both.push_back(node_ids[static_cast<std::size_t>(i)]);
  if (!both.empty())
    input_error(key, "disjoint left and right node sets",
                fmt::format("node(s) {} in both", list_ids(both)));
}

// The left and right nodes (indices) found from the angles about the axis: the sector is the
// complement of the largest empty angular gap.
void detected_sides(const std::vector<long>& node_ids, const std::vector<Eigen::Vector3d>& coords,
                    const std::vector<double>& radius, const InterfaceOptions& options,
                    const SectorInterfaces& out, double tol, const std::string& key,
                    std::vector<int>& left, std::vector<int>& right) {
  const Eigen::Vector3d& a = out.axis;
  const std::size_t n = coords.size();
  // Angles about the axis; the sector is the complement of the largest empty angular gap.
  Eigen::Vector3d e1 = a.unitOrthogonal(), e2 = a.cross(e1);
  std::vector<double> angle(n);
  for (std::size_t i = 0; i < n; ++i) angle[i] = std::atan2(coords[i].dot(e2), coords[i].dot(e1));
  std::vector<double> sorted = angle;
  std::sort(sorted.begin(), sorted.end());
  double gap = sorted.front() + units::kTwoPi - sorted.back(), start = sorted.front();
  for (std::size_t i = 1; i < n; ++i)
    if (sorted[i] - sorted[i - 1] > gap) {
      gap = sorted[i] - sorted[i - 1];
      start = sorted[i];
    }
  std::vector<long> beyond;
  double widest = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    double psi = std::fmod(angle[i] - start + 2.0 * units::kTwoPi, units::kTwoPi);
    if (psi > units::kTwoPi - 1e-12) psi = 0.0;
    widest = std::max(widest, psi);
    const double to_left = radius[i] * std::sin(std::min(psi, 0.5 * units::kPi));
    const double off_right = out.sector_angle - psi;
    const double to_right = radius[i] * std::sin(std::min(std::abs(off_right), 0.5 * units::kPi));
    if (to_left <= tol) left.push_back(static_cast<int>(i));
    if (to_right <= tol) right.push_back(static_cast<int>(i));
    if (off_right < 0.0 && to_right > tol) beyond.push_back(node_ids[i]);
  }
  if (!beyond.empty())
    input_error(key + ".n_sectors",
                fmt::format("a sector of 360/{} = {:.6g} deg", options.n_sectors,
                            360.0 / options.n_sectors),
                fmt::format("nodes spanning {:.6g} deg; node(s) {} lie beyond the sector angle",
                            widest * 180.0 / units::kPi, list_ids(beyond)),
                "check the number of sectors and that the mesh is one sector only");
}

// Pairs every left node with the right node at its position rotated by the sector angle R.
void pair_sides(const std::vector<long>& node_ids, const std::vector<Eigen::Vector3d>& coords,
                const std::vector<int>& left, const std::vector<int>& right,
                const Eigen::Matrix3d& R, double tol, const std::string& key,
                SectorInterfaces& out) {
  const std::size_t n = coords.size();
  SpatialHash hash(tol, coords, right);
  std::vector<char> right_used(n, 0);
  std::vector<long> unpaired_left, shared_right;
  double worst_unpaired = 0.0;
  for (int p : left) {
    const Eigen::Vector3d target = R * coords[static_cast<std::size_t>(p)];
    double distance = 0.0;
    const int q = hash.nearest(target, tol, distance);
    if (q < 0) {
      unpaired_left.push_back(node_ids[static_cast<std::size_t>(p)]);
      double nearest = std::numeric_limits<double>::infinity();
      for (int r : right)
        nearest = std::min(nearest, (coords[static_cast<std::size_t>(r)] - target).norm());
      if (std::isfinite(nearest)) worst_unpaired = std::max(worst_unpaired, nearest);
      continue;
    }
    if (right_used[static_cast<std::size_t>(q)]) {
      shared_right.push_back(node_ids[static_cast<std::size_t>(q)]);
      continue;
    }
    right_used[static_cast<std::size_t>(q)] = 1;
    out.pairs.push_back(
        {node_ids[static_cast<std::size_t>(p)], node_ids[static_cast<std::size_t>(q)], distance});
  }
  std::vector<long> unpaired_right;
  for (int q : right)
    if (!right_used[static_cast<std::size_t>(q)]) {
      unpaired_right.push_back(node_ids[static_cast<std::size_t>(q)]);
      const Eigen::Vector3d back = R.transpose() * coords[static_cast<std::size_t>(q)];
      double nearest = std::numeric_limits<double>::infinity();
      for (int p : left)
        nearest = std::min(nearest, (coords[static_cast<std::size_t>(p)] - back).norm());
      if (std::isfinite(nearest)) worst_unpaired = std::max(worst_unpaired, nearest);
    }
  if (!shared_right.empty())
    input_error(key, "one left partner per right node",
                fmt::format("right node(s) {} matched by two left nodes (coincident nodes?)",
                            list_ids(shared_right)));
  if (!unpaired_left.empty() || !unpaired_right.empty()) {
    std::string found;
    if (!unpaired_left.empty())
      found += fmt::format("left node(s) {} have no right partner", list_ids(unpaired_left));
    if (!unpaired_right.empty())
      found += fmt::format("{}right node(s) {} have no left partner", found.empty() ? "" : "; ",
                           list_ids(unpaired_right));
    found += fmt::format(" within {:.3g} m; worst mismatch {:.6g} m", tol, worst_unpaired);
    input_error(key, "every interface node paired with its partner rotated by 360/N deg", found,
                "the right face must be the left face rotated by the sector angle about the axis; "
                "check N, the axis, the mesh, or raise the tolerance");
  }
  if (out.pairs.empty())
    input_error(key, "interface nodes on the sector's edges", "no left/right node pairs");
}

}  // namespace

SectorInterfaces find_interfaces(const std::vector<long>& node_ids,
                                 const std::vector<Eigen::Vector3d>& coords,
                                 const InterfaceOptions& options) {
  const std::string key = "cyclic.interfaces";
  check_interface_input(node_ids, coords, options, key);

  SectorInterfaces out;
  out.n_sectors = options.n_sectors;
  out.axis = options.axis.normalized();
  out.sector_angle = units::kTwoPi / options.n_sectors;
  const Eigen::Vector3d& a = out.axis;
  const Eigen::Matrix3d R = rotation(a, out.sector_angle);
  const std::size_t n = coords.size();

  double size = 0.0;
  for (const auto& x : coords) size = std::max(size, x.norm());
  if (!(size > 0.0)) input_error(key, "nodes away from the origin", "all nodes at the origin");
  const double tol = std::isnan(options.tolerance) ? 1e-6 * size : options.tolerance;
  out.tolerance_used = tol;

  std::vector<double> radius(n);
  std::vector<long> on_axis;
  for (std::size_t i = 0; i < n; ++i) {
    radius[i] = (coords[i] - coords[i].dot(a) * a).norm();
    if (radius[i] <= tol) on_axis.push_back(node_ids[i]);
  }
  if (!on_axis.empty())
    input_error(key, "no node on the axis of symmetry",
                fmt::format("node(s) {} within {:.3g} m of the axis", list_ids(on_axis), tol),
                "a node on the axis belongs to every sector, which cyclic symmetry does not "
                "support here; mesh a small hole around the axis");

  std::vector<int> left, right;
  if (!options.left_nodes.empty()) {
    given_sides(node_ids, options, key, left, right);
  } else {
    detected_sides(node_ids, coords, radius, options, out, tol, key, left, right);
  }

  pair_sides(node_ids, coords, left, right, R, tol, key, out);
  std::sort(out.pairs.begin(), out.pairs.end(),
            [](const NodePair& x, const NodePair& y) { return x.left_node_id < y.left_node_id; });
  for (const auto& pr : out.pairs)
    if (pr.mismatch >= out.worst_mismatch) {
      out.worst_mismatch = pr.mismatch;
      out.worst_left_node = pr.left_node_id;
    }
  return out;
}

SectorInterfaces find_interfaces(const std::vector<solid::DofInfo>& dofs,
                                 const InterfaceOptions& options) {
  std::vector<long> ids;
  std::vector<Eigen::Vector3d> coords;
  std::unordered_set<long> seen;
  for (const auto& d : dofs)
    if (d.component >= 0 && seen.insert(d.node_id).second) {
      ids.push_back(d.node_id);
      coords.push_back(d.x);
    }
  return find_interfaces(ids, coords, options);
}

// ---------------------------------------------------------------------------------------------
// CyclicSector

CyclicSector::CyclicSector(std::vector<solid::DofInfo> dofs, SectorInterfaces interfaces)
    : dofs_(std::move(dofs)), interfaces_(std::move(interfaces)) {
  const std::string key = "cyclic.sector";
  if (interfaces_.n_sectors < 2)
    input_error(key, "interfaces from find_interfaces (N >= 2)",
                fmt::format("N = {}", interfaces_.n_sectors));
  R_alpha_ = rotation(interfaces_.axis, interfaces_.sector_angle);
  const Eigen::Index n = num_dofs();

  // node id -> DOF index per component (-1: absent)
  std::unordered_map<long, std::array<Eigen::Index, 6>> node_dofs;
  for (Eigen::Index j = 0; j < n; ++j) {
    const auto& d = dofs_[static_cast<std::size_t>(j)];
    if (d.component < -1 || d.component > 5)
      input_error(key + ".dofs", "components -1..5",
                  fmt::format("component {} at node {}", d.component, d.node_id));
    if (d.component < 0) continue;
    auto [it, inserted] = node_dofs.try_emplace(d.node_id);
    if (inserted) it->second.fill(-1);
    if (it->second[static_cast<std::size_t>(d.component)] >= 0)
      input_error(key + ".dofs", "each (node, component) once",
                  fmt::format("node {} component {} twice", d.node_id, d.component));
    it->second[static_cast<std::size_t>(d.component)] = j;
  }

  // Cartesian triples of every node, and the check that rotating about the axis keeps a
  // partial triple within its present components (otherwise the sector is not cyclic).
  for (const auto& [id, comps] : node_dofs) {
    for (int t = 0; t < 2; ++t) {
      std::array<Eigen::Index, 3> triple{comps[3 * t], comps[3 * t + 1], comps[3 * t + 2]};
      const int present = (triple[0] >= 0) + (triple[1] >= 0) + (triple[2] >= 0);
      if (present == 0) continue;
      for (int c = 0; c < 3; ++c)
        for (int d = 0; d < 3; ++d)
          if (triple[static_cast<std::size_t>(c)] < 0 && triple[static_cast<std::size_t>(d)] >= 0 &&
              std::abs(R_alpha_(c, d)) > 1e-12)
            input_error(key + ".dofs",
                        "nodes whose DOF components are unchanged by the sector rotation",
                        fmt::format("node {} has {} of its {} components; rotating about the axis "
                                    "mixes in the missing ones",
                                    id, present, t == 0 ? "translation" : "rotation"),
                        "a partial set of components (e.g. a constraint on ux only) is not "
                        "cyclically symmetric");
      triples_.push_back(triple);
    }
  }

  std::vector<char> dependent(static_cast<std::size_t>(n), 0);
  auto node = [&](long id, const char* side) -> const std::array<Eigen::Index, 6>& {
    const auto it = node_dofs.find(id);
    if (it == node_dofs.end())
      input_error(key + ".interfaces", "interface nodes that have DOFs",
                  fmt::format("{} node {} has no DOF in the list", side, id));
    return it->second;
  };
  for (const auto& pair : interfaces_.pairs) {
    const auto& left = node(pair.left_node_id, "left");
    const auto& right = node(pair.right_node_id, "right");
    for (int t = 0; t < 2; ++t) {
      int nl = 0, nr = 0;
      for (int c = 0; c < 3; ++c) {
        nl += left[static_cast<std::size_t>(3 * t + c)] >= 0;
        nr += right[static_cast<std::size_t>(3 * t + c)] >= 0;
      }
      if (nl == 0 || nr == 0) continue;  // present on one side only: independent
      if (nl != 3 || nr != 3)
        input_error(key + ".interfaces", "complete Cartesian triples on interface partners",
                    fmt::format("left node {} has {} and right node {} has {} of the {} "
                                "components",
                                pair.left_node_id, nl, pair.right_node_id, nr,
                                t == 0 ? "translation" : "rotation"),
                    "constrain or release interface nodes alike on both faces");
      for (int c = 0; c < 3; ++c) {
        Dependency dep;
        dep.dof = right[static_cast<std::size_t>(3 * t + c)];
        for (int d = 0; d < 3; ++d)
          if (std::abs(R_alpha_(c, d)) > 1e-14)
            dep.terms.emplace_back(left[static_cast<std::size_t>(3 * t + d)], R_alpha_(c, d));
        dependent[static_cast<std::size_t>(dep.dof)] = 1;
        dependencies_.push_back(std::move(dep));
      }
    }
  }
  dof_to_reduced_.assign(static_cast<std::size_t>(n), -1);
  for (Eigen::Index j = 0; j < n; ++j)
    if (!dependent[static_cast<std::size_t>(j)]) {
      dof_to_reduced_[static_cast<std::size_t>(j)] = num_reduced_++;
      reduced_to_dof_.push_back(j);
    }
}

void CyclicSector::check_nodal_diameter(int h) const {
  if (h < 0 || h > max_nodal_diameter())
    input_error("cyclic.nodal_diameter",
                fmt::format("0..{} (N = {})", max_nodal_diameter(), n_sectors()),
                std::to_string(h));
}

Complex CyclicSector::phase(int h) const {
  const int N = n_sectors();
  const int k = ((h % N) + N) % N;
  if (k == 0) return 1.0;
  if (2 * k == N) return -1.0;
  return std::polar(1.0, units::kTwoPi * k / N);
}

ComplexSparse CyclicSector::transformation(int h) const {
  check_nodal_diameter(h);
  const Complex ph = phase(h);
  std::vector<Eigen::Triplet<Complex>> t;
  t.reserve(static_cast<std::size_t>(num_reduced_) + 3 * dependencies_.size());
  for (Eigen::Index r = 0; r < num_reduced_; ++r)
    t.emplace_back(reduced_to_dof_[static_cast<std::size_t>(r)], r, 1.0);
  for (const auto& dep : dependencies_)
    for (const auto& [left, weight] : dep.terms)
      t.emplace_back(dep.dof, dof_to_reduced_[static_cast<std::size_t>(left)], ph * weight);
  ComplexSparse T(num_dofs(), num_reduced_);
  T.setFromTriplets(t.begin(), t.end());
  return T;
}

ComplexSparse CyclicSector::reduce(const Eigen::SparseMatrix<double>& A, int h) const {
  if (A.rows() != num_dofs() || A.cols() != num_dofs())
    input_error("cyclic.reduce", fmt::format("a {0}x{0} sector matrix", num_dofs()),
                fmt::format("{}x{}", A.rows(), A.cols()));
  const ComplexSparse T = transformation(h);
  const ComplexSparse Th = T.adjoint();
  const ComplexSparse Ac = A.cast<Complex>();
  const ComplexSparse B = Th * (Ac * T);
  const ComplexSparse Bh = B.adjoint();
  ComplexSparse H = Complex(0.5) * (B + Bh);
  H.prune(Complex(0.0));
  return H;
}

Eigen::VectorXcd CyclicSector::expand(const Eigen::VectorXcd& reduced, int h) const {
  if (reduced.size() != num_reduced_)
    input_error("cyclic.expand", fmt::format("{} reduced coordinates", num_reduced_),
                std::to_string(reduced.size()));
  return transformation(h) * reduced;
}

Eigen::VectorXcd CyclicSector::expand_to_sector(const Eigen::VectorXcd& u0, int h,
                                                int sector) const {
  check_nodal_diameter(h);
  const int N = n_sectors();
  if (sector < 0 || sector >= N)
    input_error("cyclic.expand_to_sector", fmt::format("a sector in 0..{}", N - 1),
                std::to_string(sector));
  if (u0.size() != num_dofs())
    input_error("cyclic.expand_to_sector", fmt::format("{} sector DOFs", num_dofs()),
                std::to_string(u0.size()));
  const int k = static_cast<int>((static_cast<long long>(h) * sector) % N);
  const Complex ph =
      k == 0 ? Complex(1.0) : (2 * k == N ? Complex(-1.0) : std::polar(1.0, units::kTwoPi * k / N));
  const Eigen::Matrix3d Rs = rotation(interfaces_.axis, sector * interfaces_.sector_angle);
  Eigen::VectorXcd out = ph * u0;  // generalised coordinates: phase only
  for (const auto& triple : triples_) {
    Eigen::Vector3cd v = Eigen::Vector3cd::Zero();
    for (int c = 0; c < 3; ++c)
      if (triple[static_cast<std::size_t>(c)] >= 0) v[c] = u0[triple[static_cast<std::size_t>(c)]];
    const Eigen::Vector3cd w = ph * (Rs.cast<Complex>() * v);
    for (int c = 0; c < 3; ++c)
      if (triple[static_cast<std::size_t>(c)] >= 0) out[triple[static_cast<std::size_t>(c)]] = w[c];
  }
  return out;
}

// ---------------------------------------------------------------------------------------------
// Modes per nodal diameter

std::vector<std::string> CyclicModesOptions::validate(int n_sectors) const {
  std::vector<std::string> problems = eigen.validate();
  std::vector<int> seen;
  for (int h : nodal_diameters) {
    if (h < 0 || h > n_sectors / 2)
      problems.push_back(
          fmt::format("nodal diameter {} outside 0..{} (N = {})", h, n_sectors / 2, n_sectors));
    if (std::find(seen.begin(), seen.end(), h) != seen.end())
      problems.push_back(fmt::format("nodal diameter {} listed twice", h));
    seen.push_back(h);
  }
  return problems;
}

Table CyclicModesResult::table() const {
  Table t;
  t.name = "cyclic_modes";
  t.title = fmt::format("Natural frequencies per nodal diameter ({} sectors)", n_sectors);
  std::vector<double> nd, mode, f, mult, res;
  for (const auto& d : diameters)
    for (Eigen::Index j = 0; j < d.frequency_hz.size(); ++j) {
      nd.push_back(d.nodal_diameter);
      mode.push_back(static_cast<double>(j + 1));
      f.push_back(d.frequency_hz[j]);
      mult.push_back(d.multiplicity);
      res.push_back(d.eigen.residuals[j]);
    }
  t.add("nodal_diameter", "", nd);
  t.add("mode", "", mode);
  t.add("frequency_hz", "Hz", f);
  t.add("multiplicity", "", mult);
  t.add("residual", "", res);
  return t;
}

std::string CyclicModesResult::brief_report() const {
  std::size_t modes = 0;
  double worst = 0.0;
  for (const auto& d : diameters) {
    modes += static_cast<std::size_t>(d.frequency_hz.size());
    worst = std::max(worst, d.eigen.max_residual());
  }
  return fmt::format(
      "cyclic modes: N = {}, {} nodal diameters, {} modes, max residual {:.2e}, "
      "{:.3g} s, status {}{}{}",
      n_sectors, diameters.size(), modes, worst, seconds, to_string(status),
      message.empty() ? "" : ": ", message);
}

CyclicModesResult solve_cyclic_modes(const Eigen::SparseMatrix<double>& K,
                                     const Eigen::SparseMatrix<double>& M,
                                     const CyclicSector& sector, const CyclicModesOptions& options,
                                     Progress& progress) {
  const auto started = std::chrono::steady_clock::now();
  if (auto problems = options.validate(sector.n_sectors()); !problems.empty()) {
    std::string found;
    for (const auto& p : problems) found += (found.empty() ? "" : "; ") + p;
    input_error("cyclic.CyclicModesOptions", "valid cyclic-modes options", found);
  }
  for (const auto* A : {&K, &M})
    if (A->rows() != sector.num_dofs() || A->cols() != sector.num_dofs())
      input_error("cyclic.solve_cyclic_modes",
                  fmt::format("{0}x{0} K and M (one row per sector DOF)", sector.num_dofs()),
                  fmt::format("{}x{}", A->rows(), A->cols()));
  std::vector<int> diameters = options.nodal_diameters;
  if (diameters.empty())
    for (int h = 0; h <= sector.max_nodal_diameter(); ++h) diameters.push_back(h);

  CyclicModesResult out;
  out.n_sectors = sector.n_sectors();
  out.status = Status::Ok;
  progress.start("cyclic modes per nodal diameter", diameters.size());
  for (std::size_t i = 0; i < diameters.size(); ++i) {
    const int h = diameters[i];
    NodalDiameterModes d;
    d.nodal_diameter = h;
    d.multiplicity = (h == 0 || 2 * h == sector.n_sectors()) ? 1 : 2;
    const ComplexSparse Kh = sector.reduce(K, h), Mh = sector.reduce(M, h);
    d.eigen = eig::solve_hermitian(Kh, Mh, options.eigen);
    d.frequency_hz = d.eigen.eigenvalues.unaryExpr(
        [](double lambda) { return std::sqrt(std::max(lambda, 0.0)) / units::kTwoPi; });
    if (d.eigen.eigenvectors.cols() > 0)
      d.sector_shapes = sector.transformation(h) * d.eigen.eigenvectors;
    if (d.eigen.status != Status::Ok) {
      out.status = worse(out.status, d.eigen.status);
      out.message += fmt::format("{}nodal diameter {}: {}", out.message.empty() ? "" : "; ", h,
                                 d.eigen.message);
    }
    out.diameters.push_back(std::move(d));
    progress.update(i + 1);
  }
  progress.finish();
  out.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
  return out;
}

}  // namespace geardyn::cyclic
