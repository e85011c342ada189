#include "geardyn/assembly/solid_coupling.hpp"

#include <fmt/format.h>

#include <Eigen/QR>
#include <algorithm>
#include <cmath>
#include <map>
#include <stdexcept>

#include "geardyn/core/error.hpp"
#include "geardyn/fe/dof_map.hpp"
#include "geardyn/fe/element_types.hpp"
#include "geardyn/fe/rigid_disk.hpp"
#include "geardyn/reduce/craig_bampton.hpp"
#include "geardyn/solid/assembly.hpp"

namespace geardyn::assembly {
namespace {

using Triplets = std::vector<Eigen::Triplet<double>>;
using RowSparse = Eigen::SparseMatrix<double, Eigen::RowMajor>;

std::size_t index_of(const model::Model& model, const model::Solid& solid) {
  for (std::size_t i = 0; i < model.solids.size(); ++i)
    if (&model.solids[i] == &solid) return i;
  for (std::size_t i = 0; i < model.solids.size(); ++i)
    if (model.solids[i].name == solid.name) return i;
  return 0;
}

const std::vector<int>& set_nodes(const solid::Mesh& mesh, const std::string& solid_name,
                                  const std::string& set, const SourceLocation& where,
                                  const std::string& key) {
  const auto it = mesh.node_sets.find(set);
  if (it != mesh.node_sets.end() && !it->second.empty()) return it->second;
  std::string available;
  for (const auto& [set_name, nodes] : mesh.node_sets)
    available += (available.empty() ? "" : ", ") + fmt::format("\"{}\"", set_name);
  throw InputError(where, key,
                   fmt::format("a node set of solid '{}' ({})", solid_name,
                               available.empty() ? "it has none" : available),
                   it == mesh.node_sets.end() ? fmt::format("\"{}\"", set)
                                              : fmt::format("\"{}\", an empty set", set));
}

Eigen::Matrix3d skew(const Eigen::Vector3d& v) {
  Eigen::Matrix3d s;
  s << 0, -v.z(), v.y(), v.z(), 0, -v.x(), -v.y(), v.x(), 0;
  return s;
}

// Rigid-body motion (U, theta) about point p of every coordinate: translation c at x reads
// (U + theta x (x - p))_c, rotation c reads theta_c.
Eigen::MatrixXd rigid_modes(const std::vector<solid::DofInfo>& dofs, const Eigen::Vector3d& p) {
  Eigen::MatrixXd R = Eigen::MatrixXd::Zero(static_cast<Eigen::Index>(dofs.size()), 6);
  for (std::size_t k = 0; k < dofs.size(); ++k) {
    const auto row = static_cast<Eigen::Index>(k);
    const int c = dofs[k].component;
    if (c < 0) continue;
    if (c < 3) {
      R(row, c) = 1.0;
      R.block(row, 3, 1, 3) = -skew(dofs[k].x - p).row(c);
    } else {
      R(row, c) = 1.0;
    }
  }
  return R;
}

struct SensorSet {
  std::string set;
  const model::Sensor* first = nullptr;  ///< for messages
  std::size_t sensor_index = 0;
};

/// The solid's mesh with one reference node per spider (at its rotor node) and its rigid
/// element.
struct SpiderPoints {
  solid::Mesh mesh;
  std::vector<int> reference;   ///< mesh node of each spider's reference point
  std::vector<int> rotor_node;  ///< rotor node of each spider
  long next_id = 1;             ///< first node id after the mesh's and the references'
};

SpiderPoints spider_points(const model::Solid& solid, const SolidComponent& built,
                           const fe::DofMap& rotor, const std::string& base) {
  SpiderPoints sp;
  sp.mesh = built.mesh;
  solid::Mesh& mesh = sp.mesh;
  for (long id : mesh.node_ids) sp.next_id = std::max(sp.next_id, id + 1);
  sp.reference.assign(solid.spiders.size(), -1);
  sp.rotor_node.assign(solid.spiders.size(), -1);
  for (std::size_t k = 0; k < solid.spiders.size(); ++k) {
    const model::Spider& spider = solid.spiders[k];
    const std::string key = fmt::format("{}.spiders[{}]", base, k);
    const std::vector<int>& nodes =
        set_nodes(mesh, solid.name, spider.node_set, spider.where, key + ".node_set");
    sp.rotor_node[k] = rotor.find_node(spider.node);
    if (sp.rotor_node[k] < 0)
      throw InputError(spider.where, key + ".node",
                       "a rotor node: \"<shaft>.<k>\" of an existing shaft, or a [[nodes]] name",
                       fmt::format("\"{}\"", spider.node));
    sp.reference[k] = mesh.num_nodes();
    mesh.coords.push_back(rotor.node(sp.rotor_node[k]).position);
    mesh.node_ids.push_back(sp.next_id++);
    solid::RigidElement element;
    element.kind = spider.kind == model::SpiderKind::Rigid ? solid::RigidElement::Kind::Rigid
                                                           : solid::RigidElement::Kind::Averaging;
    element.id = static_cast<long>(k + 1);
    element.reference = sp.reference[k];
    element.nodes = nodes;
    element.where = spider.where;
    mesh.rigid_elements.push_back(std::move(element));
  }
  return sp;
}

/// The sensor sets of this solid (one point per set, whatever DOFs its sensors read).
std::vector<SensorSet> sensor_sets_of(const model::Model& model, const model::Solid& solid,
                                      const solid::Mesh& mesh) {
  std::vector<SensorSet> sensor_sets;
  for (std::size_t j = 0; j < model.sensors.size(); ++j) {
    const model::Sensor& s = model.sensors[j];
    if (s.solid != solid.name) continue;
    const bool seen = std::any_of(sensor_sets.begin(), sensor_sets.end(),
                                  [&](const SensorSet& e) { return e.set == s.node_set; });
    if (seen) continue;
    (void)set_nodes(mesh, solid.name, s.node_set, s.where, fmt::format("sensors[{}].node_set", j));
    sensor_sets.push_back({s.node_set, &s, j});
  }
  return sensor_sets;
}

/// Constraint rows u = A x (averaging spiders: 6 rows, sensors: 3 rows) and rigid masters.
struct Constraints {
  Triplets a;
  int n_rows = 0;
  std::vector<int> row_owner;             ///< spider k, or -(1 + sensor set index)
  std::vector<solid::DofInfo> row_info;   ///< DofInfo of each u
  std::vector<std::vector<int>> rigid_x;  ///< rigid masters (x indices) of each spider
  std::vector<int> first_row;             ///< of each averaging spider (-1: rigid)
  std::vector<int> sensor_first_row;
  std::vector<Eigen::Vector3d> sensor_position;

  void add_row(const Eigen::SparseVector<double>& row, int owner, solid::DofInfo info) {
    for (Eigen::SparseVector<double>::InnerIterator it(row); it; ++it)
      if (it.value() != 0.0) a.emplace_back(n_rows, static_cast<int>(it.index()), it.value());
    row_owner.push_back(owner);
    row_info.push_back(info);
    ++n_rows;
  }
};

/// The rows of the spiders: averaging spiders constrain their reference point's 6 DOFs, rigid
/// spiders make them masters.
void add_spider_rows(Constraints& out, const model::Solid& solid, const SpiderPoints& sp,
                     const solid::SolidSystem& sys, const RowSparse& recovery,
                     const std::string& base) {
  const solid::Mesh& mesh = sp.mesh;
  for (std::size_t k = 0; k < solid.spiders.size(); ++k) {
    const int r = sp.reference[k];
    const std::string key = fmt::format("{}.spiders[{}]", base, k);
    const Eigen::Vector3d xr = mesh.coords[static_cast<std::size_t>(r)];
    if (solid.spiders[k].kind == model::SpiderKind::Rigid) {
      for (int c = 0; c < 6; ++c) {
        const int d = sys.node_dof(r, c);
        if (d < 0)
          throw InputError(solid.spiders[k].where, key + ".node_set",
                           "a node set that gives the reference point all 6 DOFs (at least 3 "
                           "nodes not on one line, not all fixed)",
                           fmt::format("\"{}\", which leaves its {} without stiffness",
                                       solid.spiders[k].node_set,
                                       model::kComponentNames[static_cast<std::size_t>(c)]));
        out.rigid_x[k].push_back(d);
      }
      continue;
    }
    out.first_row[k] = out.n_rows;
    for (int c = 0; c < 6; ++c) {
      const int all = sys.all_dof(r, c);
      out.add_row(Eigen::SparseVector<double>(recovery.row(all).transpose()), static_cast<int>(k),
                  {mesh.node_ids[static_cast<std::size_t>(r)], c, xr});
    }
  }
}

/// The rows of the sensor sets: the mean translation of each set's nodes.
void add_sensor_rows(Constraints& out, const std::vector<SensorSet>& sensor_sets,
                     const SpiderPoints& sp, const solid::SolidSystem& sys,
                     const RowSparse& recovery) {
  const solid::Mesh& mesh = sp.mesh;
  const int n = sys.num_dofs();
  for (std::size_t s = 0; s < sensor_sets.size(); ++s) {
    const std::vector<int>& nodes = mesh.node_sets.at(sensor_sets[s].set);
    Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
    std::array<Eigen::SparseVector<double>, 3> rows;
    for (auto& row : rows) row.resize(n);
    int counted = 0;
    for (int node : nodes) {
      if (sys.all_dof(node, 0) < 0) continue;  // a node of no element: it has no motion
      centroid += mesh.coords[static_cast<std::size_t>(node)];
      for (int c = 0; c < 3; ++c)
        rows[static_cast<std::size_t>(c)] += recovery.row(sys.all_dof(node, c)).transpose();
      ++counted;
    }
    if (counted == 0)
      throw InputError(sensor_sets[s].first->where,
                       fmt::format("sensors[{}].node_set", sensor_sets[s].sensor_index),
                       "a node set with nodes of the solid's elements",
                       fmt::format("\"{}\", whose nodes belong to no element", sensor_sets[s].set));
    centroid /= counted;
    out.sensor_position.push_back(centroid);
    out.sensor_first_row.push_back(out.n_rows);
    // Sensor points get ids after the spider reference nodes.
    const long id = sp.next_id + static_cast<long>(s);
    for (int c = 0; c < 3; ++c)
      out.add_row(rows[static_cast<std::size_t>(c)] / counted, -1 - static_cast<int>(s),
                  {id, c, centroid});
  }
}

/// A over the columns it touches only (sets are a small part of a mesh).
struct UsedColumns {
  std::vector<int> columns;  ///< columns of A with an entry, ascending
  std::vector<int> index;    ///< x index -> column of `A` (-1: unused)
  Eigen::MatrixXd A;
  Eigen::MatrixXd::ConstColXpr column(int j) const {
    return A.col(index[static_cast<std::size_t>(j)]);
  }
};

UsedColumns used_columns_of(const Constraints& con, int n) {
  UsedColumns u;
  u.index.assign(static_cast<std::size_t>(n), -1);
  for (const auto& t : con.a) u.index[static_cast<std::size_t>(t.col())] = 0;
  for (int j = 0; j < n; ++j) {
    if (u.index[static_cast<std::size_t>(j)] < 0) continue;
    u.index[static_cast<std::size_t>(j)] = static_cast<int>(u.columns.size());
    u.columns.push_back(j);
  }
  u.A = Eigen::MatrixXd::Zero(con.n_rows, static_cast<Eigen::Index>(u.columns.size()));
  for (const auto& t : con.a) u.A(t.row(), u.index[static_cast<std::size_t>(t.col())]) += t.value();
  return u;
}

/// InputError at the first spider or sensor point whose rows of A_c are not independent of the
/// ones before it.
[[noreturn]] void throw_dependent(const Eigen::MatrixXd& A_c, const Constraints& con,
                                  const model::Solid& solid,
                                  const std::vector<SensorSet>& sensor_sets,
                                  const std::string& base, int (*rank_of)(const Eigen::MatrixXd&)) {
  const int n_rows = con.n_rows;
  int bad = n_rows - 1;
  for (int r = 1; r <= n_rows; ++r) {
    if (rank_of(A_c.topRows(r)) < r) {
      bad = r - 1;
      break;
    }
  }
  const int owner = con.row_owner[static_cast<std::size_t>(bad)];
  if (owner >= 0) {
    const auto k = static_cast<std::size_t>(owner);
    throw InputError(solid.spiders[k].where, fmt::format("{}.spiders[{}].node_set", base, k),
                     "a node set whose rigid fit is not already fixed by the other spiders "
                     "(at least 3 nodes not on one line, not all fixed or rigidly joined)",
                     fmt::format("\"{}\"", solid.spiders[k].node_set), "join each node set once");
  }
  const SensorSet& ss = sensor_sets[static_cast<std::size_t>(-1 - owner)];
  throw InputError(ss.first->where, fmt::format("sensors[{}].node_set", ss.sensor_index),
                   "a node set that moves on its own (not fixed, not rigidly joined to a "
                   "rotor node, not measured by another sensor set of the same motion)",
                   fmt::format("\"{}\"", ss.set),
                   "a rigidly joined set moves with its rotor node: put the sensor there");
}

/// The pivots D among the non-master columns of A (one per row) and A_D^-1.
struct Pivots {
  std::vector<int> columns;
  Eigen::MatrixXd A_D_inv;
};

Pivots pivot_columns(const Constraints& con, const UsedColumns& used, int n,
                     const model::Solid& solid, const std::vector<SensorSet>& sensor_sets,
                     const std::string& base) {
  Pivots out;
  const int n_rows = con.n_rows;
  if (n_rows == 0) return out;
  std::vector<bool> is_rigid_master(static_cast<std::size_t>(n), false);
  for (const auto& list : con.rigid_x)
    for (int d : list) is_rigid_master[static_cast<std::size_t>(d)] = true;
  std::vector<int> candidates;
  for (int j : used.columns)
    if (!is_rigid_master[static_cast<std::size_t>(j)]) candidates.push_back(j);
  Eigen::MatrixXd A_c(n_rows, static_cast<Eigen::Index>(candidates.size()));
  for (std::size_t j = 0; j < candidates.size(); ++j)
    A_c.col(static_cast<Eigen::Index>(j)) = used.column(candidates[j]);
  auto rank_of = [](const Eigen::MatrixXd& a) -> int {
    if (a.rows() == 0 || a.cols() == 0) return 0;
    Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr(a);
    qr.setThreshold(1e-9);
    return static_cast<int>(qr.rank());
  };
  if (rank_of(A_c) < n_rows) throw_dependent(A_c, con, solid, sensor_sets, base, rank_of);
  Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr(A_c);
  for (int k = 0; k < n_rows; ++k)
    out.columns.push_back(candidates[static_cast<std::size_t>(qr.colsPermutation().indices()[k])]);
  Eigen::MatrixXd A_D(n_rows, n_rows);
  for (int k = 0; k < n_rows; ++k)
    A_D.col(k) = used.column(out.columns[static_cast<std::size_t>(k)]);
  out.A_D_inv = A_D.partialPivLu().inverse();
  return out;
}

/// The change of variables x = S z, z = [x_F; u]: x_D = A_D^-1 u - A_D^-1 A_F x_F.
struct Elimination {
  std::vector<int> position;  ///< x index -> z index (x_F); -1 for a pivot
  int n_free = 0;
  Eigen::SparseMatrix<double> transform;
};

Elimination eliminate(const Constraints& con, const UsedColumns& used, const Pivots& pivots,
                      int n) {
  const int n_rows = con.n_rows;
  Elimination e;
  e.position.assign(static_cast<std::size_t>(n), -1);
  {
    std::vector<bool> pivot(static_cast<std::size_t>(n), false);
    for (int d : pivots.columns) pivot[static_cast<std::size_t>(d)] = true;
    int next = 0;
    for (int j = 0; j < n; ++j)
      if (!pivot[static_cast<std::size_t>(j)]) e.position[static_cast<std::size_t>(j)] = next++;
  }
  const std::vector<int>& position = e.position;
  e.n_free = n - n_rows;
  const int n_free = e.n_free;
  Triplets s_triplets;
  for (int j = 0; j < n; ++j)
    if (position[static_cast<std::size_t>(j)] >= 0)
      s_triplets.emplace_back(j, position[static_cast<std::size_t>(j)], 1.0);
  if (n_rows > 0) {
    // x_D = A_D^-1 u - A_D^-1 A_F x_F
    std::vector<int> others;
    for (int j : used.columns)
      if (position[static_cast<std::size_t>(j)] >= 0) others.push_back(j);
    Eigen::MatrixXd A_F(n_rows, static_cast<Eigen::Index>(others.size()));
    for (std::size_t j = 0; j < others.size(); ++j)
      A_F.col(static_cast<Eigen::Index>(j)) = used.column(others[j]);
    const Eigen::MatrixXd B = pivots.A_D_inv * A_F;
    for (int i = 0; i < n_rows; ++i) {
      const int d = pivots.columns[static_cast<std::size_t>(i)];
      for (int k = 0; k < n_rows; ++k)
        if (pivots.A_D_inv(i, k) != 0.0)
          s_triplets.emplace_back(d, n_free + k, pivots.A_D_inv(i, k));
      for (std::size_t j = 0; j < others.size(); ++j) {
        const double v = B(i, static_cast<Eigen::Index>(j));
        if (v != 0.0) s_triplets.emplace_back(d, position[static_cast<std::size_t>(others[j])], -v);
      }
    }
  }
  e.transform.resize(n, n);
  e.transform.setFromTriplets(s_triplets.begin(), s_triplets.end());
  e.transform.makeCompressed();
  return e;
}

/// K and M in z (S^T K S, S^T M S, made exactly symmetric) and the DofInfo of each z.
void project(SpiderSystem& out, const solid::SolidSystem& sys, const Constraints& con,
             const Elimination& e) {
  const int n = sys.num_dofs();
  const Eigen::SparseMatrix<double> St = out.transform.transpose();
  const Eigen::SparseMatrix<double> KS = sys.K * out.transform;
  const Eigen::SparseMatrix<double> MS = sys.M * out.transform;
  Eigen::SparseMatrix<double> Kz = St * KS, Mz = St * MS;
  // The two triangles of S^T K S are summed in different orders: make them equal.
  out.K = 0.5 * (Kz + Eigen::SparseMatrix<double>(Kz.transpose()));
  out.M = 0.5 * (Mz + Eigen::SparseMatrix<double>(Mz.transpose()));
  out.K.makeCompressed();
  out.M.makeCompressed();

  out.dofs.resize(static_cast<std::size_t>(n));
  for (int j = 0; j < n; ++j)
    if (e.position[static_cast<std::size_t>(j)] >= 0)
      out.dofs[static_cast<std::size_t>(e.position[static_cast<std::size_t>(j)])] =
          sys.dofs[static_cast<std::size_t>(j)];
  for (int k = 0; k < con.n_rows; ++k)
    out.dofs[static_cast<std::size_t>(e.n_free + k)] = con.row_info[static_cast<std::size_t>(k)];
}

/// Masters and points: spiders in order, then sensor sets. `position`: coordinate of each solid
/// DOF (rigid masters), `u_offset`: coordinate of constraint row 0.
void add_points(std::vector<int>& masters, std::vector<fe::SuperelementPoint>& points,
                const model::Solid& solid, const fe::DofMap& rotor, const SpiderPoints& sp,
                const std::vector<SensorSet>& sensor_sets, const Constraints& con,
                const std::vector<int>& position, int u_offset) {
  for (std::size_t k = 0; k < solid.spiders.size(); ++k) {
    fe::SuperelementPoint point;
    point.node = solid.spiders[k].node;
    points.push_back(point);
    for (int c = 0; c < 6; ++c)
      masters.push_back(
          solid.spiders[k].kind == model::SpiderKind::Rigid
              ? position[static_cast<std::size_t>(con.rigid_x[k][static_cast<std::size_t>(c)])]
              : u_offset + con.first_row[k] + c);
  }
  double common_ratio = rotor.node(sp.rotor_node.front()).speed_ratio;
  for (int node : sp.rotor_node)
    if (std::abs(rotor.node(node).speed_ratio - common_ratio) > 1e-12) common_ratio = 0.0;
  for (std::size_t s = 0; s < sensor_sets.size(); ++s) {
    fe::SuperelementPoint point;
    point.node = solid.name + "/" + sensor_sets[s].set;
    point.new_node = true;
    point.position = con.sensor_position[s];
    point.speed_ratio = common_ratio;
    point.components = {true, true, true, false, false, false};
    points.push_back(point);
    for (int c = 0; c < 3; ++c) masters.push_back(u_offset + con.sensor_first_row[s] + c);
  }
}

}  // namespace

bool has_joined_solids(const model::Model& model) {
  return std::any_of(model.solids.begin(), model.solids.end(),
                     [](const model::Solid& s) { return !s.spiders.empty(); });
}

namespace {

/// Everything both coupling paths start from: the solid assembled with its spider elements,
/// the constraint rows (checked independent) and the rigid masters.
struct Coupling {
  std::string base;
  fe::DofMap rotor;
  SpiderPoints sp;
  std::vector<SensorSet> sensor_sets;
  solid::SolidSystem system;
  Constraints con;
  UsedColumns used;
  Pivots pivots;
};

Coupling coupling_of(const model::Model& model, const model::Solid& solid,
                     const SolidComponent& built, Progress& progress) {
  Coupling c;
  c.base = fmt::format("solids[{}]", index_of(model, solid));
  if (!built.has_mesh())
    throw InputError(solid.where, c.base + ".spiders",
                     "a solid with a mesh (type mesh, annular_plate or gear_sector)",
                     fmt::format("a solid of type \"{}\"", built.kind()),
                     "join the mesh the component was reduced from");
  if (solid.spiders.empty())
    throw std::logic_error("spider_system: solid '" + solid.name + "' has no spiders");
  c.rotor = fe::DofMap::build(model);
  // Spider reference nodes and their rigid elements; the sensor sets of this solid.
  c.sp = spider_points(solid, built, c.rotor, c.base);
  c.sensor_sets = sensor_sets_of(model, solid, c.sp.mesh);

  solid::AssemblyOptions options;
  options.threads = 0;
  options.progress = &progress;
  c.system = solid::assemble(c.sp.mesh, options);
  const solid::SolidSystem& sys = c.system;
  const int n = sys.num_dofs();
  const RowSparse recovery = sys.recovery;

  c.con.rigid_x.resize(solid.spiders.size());
  c.con.first_row.assign(solid.spiders.size(), -1);
  add_spider_rows(c.con, solid, c.sp, sys, recovery, c.base);
  add_sensor_rows(c.con, c.sensor_sets, c.sp, sys, recovery);
  // The rows must be independent on the non-master columns (else: which point is redundant).
  c.used = used_columns_of(c.con, n);
  c.pivots = pivot_columns(c.con, c.used, n, solid, c.sensor_sets, c.base);
  return c;
}

/// Mass matrix of the rigid body about point p from the rigid-body motions of `dofs`.
Eigen::Matrix<double, 6, 6> rigid_mass_of(const Eigen::SparseMatrix<double>& M,
                                          const std::vector<solid::DofInfo>& dofs,
                                          const Eigen::Vector3d& p) {
  const Eigen::MatrixXd R = rigid_modes(dofs, p);
  return R.transpose() * (M * R);
}

/// The joined solid reduced by Craig-Bampton with the constraint rows kept as constraints
/// (reduce::craig_bampton with InterfaceConstraints): coordinates [x; u], no elimination.
struct ConstrainedReduction {
  reduce::ReducedComponent reduced;
  std::vector<fe::SuperelementPoint> points;
  Eigen::SparseMatrix<double> transform;  ///< x = [I 0] [x; u]
  Eigen::Matrix<double, 6, 6> rigid_mass;
  solid::SolidSystem solid_dofs;  ///< the assembled solid without K and M (recovery of x)
};

/// The constraint rows as InterfaceConstraints, the masters as indices into [x; u] and the points.
reduce::InterfaceConstraints constraints_of(const Coupling& c, const model::Solid& solid,
                                            std::vector<int>& masters,
                                            std::vector<fe::SuperelementPoint>& points) {
  const int n = c.system.num_dofs();
  reduce::InterfaceConstraints constraints;
  constraints.A.resize(c.con.n_rows, n);
  constraints.A.setFromTriplets(c.con.a.begin(), c.con.a.end());
  constraints.dofs = c.con.row_info;
  std::vector<int> identity(static_cast<std::size_t>(n));
  for (int j = 0; j < n; ++j) identity[static_cast<std::size_t>(j)] = j;
  add_points(masters, points, solid, c.rotor, c.sp, c.sensor_sets, c.con, identity, n);
  return constraints;
}

ConstrainedReduction reduce_constrained(const model::Model& model, const model::Solid& solid,
                                        const SolidComponent& built, Progress& progress) {
  Coupling c = coupling_of(model, solid, built, progress);
  const solid::SolidSystem& sys = c.system;
  const int n = sys.num_dofs();
  ConstrainedReduction out;
  std::vector<int> masters;
  const reduce::InterfaceConstraints constraints = constraints_of(c, solid, masters, out.points);

  const int n_interior = n - static_cast<int>(masters.size());
  if (solid.coupling_modes > n_interior)
    throw InputError(solid.where, c.base + ".coupling_modes",
                     fmt::format("at most {} (the DOFs of the solid that are not spider or "
                                 "sensor points)",
                                 n_interior),
                     std::to_string(solid.coupling_modes));
  reduce::CraigBamptonOptions options;
  options.n_modes = solid.coupling_modes;
  try {
    out.reduced = reduce::craig_bampton(sys.K, sys.M, sys.dofs, constraints, masters, options,
                                        built.source_sha256, {}, progress);
  } catch (const InputError& e) {
    // The masters are the spider points: a free interior is a solid the spiders do not hold.
    throw InputError(solid.where, c.base + ".spiders",
                     "spiders that hold every rigid-body motion of the solid and of each of its "
                     "parts",
                     e.found(),
                     "join every part of the solid through node sets that fix its motion (a set "
                     "of at least 3 nodes not on one line), or fix it with fixed_sets");
  }
  std::vector<Eigen::Triplet<double>> t;
  for (int j = 0; j < n; ++j) t.emplace_back(j, j, 1.0);
  out.transform.resize(n, n + c.con.n_rows);
  out.transform.setFromTriplets(t.begin(), t.end());
  const Eigen::Vector3d p = c.sp.mesh.coords[static_cast<std::size_t>(c.sp.reference.front())];
  out.rigid_mass = rigid_mass_of(sys.M, sys.dofs, p);
  out.solid_dofs = std::move(c.system);
  out.solid_dofs.K = {};
  out.solid_dofs.M = {};
  return out;
}

}  // namespace

SpiderSystem spider_system(const model::Model& model, const model::Solid& solid,
                           const SolidComponent& built, Progress& progress) {
  Coupling c = coupling_of(model, solid, built, progress);
  SpiderSystem out;
  std::vector<fe::SuperelementPoint> points;
  out.constraints = constraints_of(c, solid, out.constrained_masters, points);
  out.system = std::move(c.system);
  const solid::SolidSystem& sys = out.system;
  const int n = sys.num_dofs();
  // Change of variables x = S z, z = [x_F; u]: pivots D among the non-master columns of A.
  Elimination e = eliminate(c.con, c.used, c.pivots, n);
  out.transform = std::move(e.transform);
  project(out, sys, c.con, e);
  add_points(out.masters, out.points, solid, c.rotor, c.sp, c.sensor_sets, c.con, e.position,
             e.n_free);
  const Eigen::Vector3d p = c.sp.mesh.coords[static_cast<std::size_t>(c.sp.reference.front())];
  out.rigid_mass = rigid_mass_of(out.M, out.dofs, p);
  return out;
}

CoupledSolid couple_solid(const model::Model& model, const model::Solid& solid,
                          const SolidComponent& built, Progress& progress) {
  ConstrainedReduction cr = reduce_constrained(model, solid, built, progress);
  CoupledSolid out;
  out.name = solid.name;
  out.reduced = std::move(cr.reduced);
  out.transform = std::move(cr.transform);
  out.rigid_mass = cr.rigid_mass;
  out.solid_dofs = std::move(cr.solid_dofs);

  fe::Superelement& body = out.body;
  body.name = solid.name;
  body.points = cr.points;
  body.n_generalized = out.reduced.n_modal;
  body.K = 0.5 * (out.reduced.K + out.reduced.K.transpose());
  body.M = 0.5 * (out.reduced.M + out.reduced.M.transpose());
  // The component's own modal damping (docs/theory.md §9, eq. 9.4): in the fixed-interface modal
  // block, where M_eta = I and K_eta = Lambda, C_eta = diag(2 zeta sqrt(lambda_k)); the
  // constraint-mode block is undamped.
  if (solid.modal_damping_ratio > 0.0 && body.n_generalized > 0) {
    body.C = Eigen::MatrixXd::Zero(body.size(), body.size());
    for (int k = body.size() - body.n_generalized; k < body.size(); ++k)
      body.C(k, k) = 2.0 * solid.modal_damping_ratio * std::sqrt(std::max(body.K(k, k), 0.0));
  }

  // Gyroscopic matrix of the rigid body when every spider node spins at one speed about one
  // axis: the rigid-disk matrix (node frame) at the first spider point, rotated to global axes.
  const fe::DofMap rotor = fe::DofMap::build(model);
  const fe::NodeInfo& first = rotor.node(rotor.node_index(solid.spiders.front().node));
  bool common = first.speed_ratio != 0.0;
  for (const model::Spider& spider : solid.spiders) {
    const fe::NodeInfo& node = rotor.node(rotor.node_index(spider.node));
    common = common && std::abs(node.speed_ratio - first.speed_ratio) <= 1e-12 &&
             (node.frame.col(2) - first.frame.col(2)).norm() <= 1e-12;
  }
  const Eigen::Vector3d e3 = first.frame.col(2);
  const double polar = e3.dot(out.rigid_mass.bottomRightCorner<3, 3>() * e3);
  if (common) {
    out.polar_inertia = polar;
    const fe::Matrix6d rotation = fe::node_rotation(first.frame);
    body.G = Eigen::MatrixXd::Zero(body.size(), body.size());
    body.G.topLeftCorner<6, 6>() = first.speed_ratio * rotation *
                                   fe::rigid_disk_gyroscopic(out.polar_inertia) *
                                   rotation.transpose();
  }

  const int n_sensors = static_cast<int>(cr.points.size() - solid.spiders.size());
  out.description = fmt::format(
      "joined to the rotor by {} spider{}{}: {} fixed-interface mode{}{}, mass {:.6g} kg, "
      "polar inertia {:.6g} kg m^2{}",
      solid.spiders.size(), solid.spiders.size() == 1 ? "" : "s",
      n_sensors > 0 ? fmt::format(" and {} sensor point{}", n_sensors, n_sensors == 1 ? "" : "s")
                    : std::string(),
      out.reduced.n_modal, out.reduced.n_modal == 1 ? "" : "s",
      out.reduced.n_modal > 0
          ? fmt::format(" (up to {:.6g} Hz)", out.reduced.fixed_interface_hz.maxCoeff())
          : std::string(),
      out.rigid_mass(0, 0), polar,
      common ? "" : " (no gyroscopic term: the spider nodes do not spin together)");
  return out;
}

std::vector<CoupledSolid> couple_solids(const model::Model& model, const SolidComponents* built,
                                        Progress& progress) {
  std::vector<CoupledSolid> out;
  for (const model::Solid& solid : model.solids) {
    if (solid.spiders.empty()) continue;
    if (built != nullptr) {
      const auto it = built->find(solid.name);
      if (it != built->end()) {
        out.push_back(couple_solid(model, solid, it->second, progress));
        continue;
      }
    }
    const SolidComponent component = build_solid(model, solid, progress);
    out.push_back(couple_solid(model, solid, component, progress));
  }
  return out;
}

Eigen::MatrixXd node_translations(const CoupledSolid& solid, const std::vector<int>& nodes) {
  const reduce::ReducedComponent& rc = solid.reduced;
  const solid::SolidSystem& sys = solid.solid_dofs;
  std::vector<int> master_of(static_cast<std::size_t>(rc.n_full()), -1);
  std::vector<int> interior_of(static_cast<std::size_t>(rc.n_full()), -1);
  for (std::size_t k = 0; k < rc.master_index.size(); ++k)
    master_of[static_cast<std::size_t>(rc.master_index[k])] = static_cast<int>(k);
  for (std::size_t j = 0; j < rc.interior_index.size(); ++j)
    interior_of[static_cast<std::size_t>(rc.interior_index[j])] = static_cast<int>(j);
  const Eigen::SparseMatrix<double, Eigen::RowMajor> recovery = sys.recovery;
  const Eigen::Index nm = rc.n_masters();
  Eigen::MatrixXd R = Eigen::MatrixXd::Zero(3 * static_cast<Eigen::Index>(nodes.size()), rc.size());
  for (std::size_t i = 0; i < nodes.size(); ++i) {
    if (nodes[i] < 0 || static_cast<std::size_t>(nodes[i]) >= sys.node_dofs.size())
      throw std::invalid_argument(
          fmt::format("node index {} is not a node of solid '{}'", nodes[i], solid.name));
    for (int c = 0; c < 3; ++c) {
      const int a = sys.all_dof(nodes[i], c);
      if (a < 0)
        throw std::invalid_argument(
            fmt::format("node index {} of solid '{}' has no translations", nodes[i], solid.name));
      const Eigen::Index row = 3 * static_cast<Eigen::Index>(i) + c;
      for (Eigen::SparseMatrix<double, Eigen::RowMajor>::InnerIterator it(recovery, a); it; ++it) {
        const auto z = static_cast<std::size_t>(it.col());  // x_j = z_j (S = [I 0])
        if (master_of[z] >= 0) {
          R(row, master_of[z]) += it.value();
        } else {
          const auto j = static_cast<Eigen::Index>(interior_of[z]);
          R.row(row).head(nm) += it.value() * rc.Psi.row(j);
          R.row(row).tail(rc.n_modal) += it.value() * rc.Phi.row(j);
        }
      }
    }
  }
  return R;
}

}  // namespace geardyn::assembly
