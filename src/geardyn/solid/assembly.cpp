#include "geardyn/solid/assembly.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <exception>
#include <limits>
#include <thread>
#include <utility>

#include "geardyn/solid/element_kernel.hpp"
#include "geardyn/solid/elements.hpp"

namespace geardyn::solid {
namespace {

using Term = std::pair<int, double>;  // (DOF index, coefficient)

Eigen::Matrix3d skew(const Eigen::Vector3d& v) {
  Eigen::Matrix3d S;
  S << 0, -v.z(), v.y(), v.z(), 0, -v.x(), -v.y(), v.x(), 0;
  return S;
}

long external_id(const Mesh& mesh, int node) {
  return mesh.node_ids.empty() ? node : mesh.node_ids[static_cast<std::size_t>(node)];
}

std::string component_list(const std::array<bool, 6>& c) {
  std::string s;
  for (int i = 0; i < 6; ++i) {
    if (c[static_cast<std::size_t>(i)]) s += static_cast<char>('1' + i);
  }
  return s;
}

void check_node(const Mesh& mesh, int node, const SourceLocation& where, const std::string& key) {
  if (node < 0 || node >= mesh.num_nodes()) {
    throw InputError(where, key, fmt::format("a node index in [0, {})", mesh.num_nodes()),
                     fmt::format("{}", node));
  }
}

void check_component(int c, const SourceLocation& where, const std::string& key) {
  if (c < 0 || c > 5) {
    throw InputError(where, key, "a component 0..5 (ux uy uz rx ry rz)", fmt::format("{}", c));
  }
}

// Everything that can be checked before assembly: indices in range, finite values, materials.
// A spring end's direction: zero (along its component) or a finite unit vector.
void check_spring_direction(const Eigen::Vector3d& n, const SourceLocation& where,
                            const std::string& key) {
  if (n.isZero(0.0)) return;
  if (!n.allFinite() || std::abs(n.norm() - 1.0) > 1e-9) {
    throw InputError(where, key, "zero (along the component) or a unit vector",
                     fmt::format("[{}, {}, {}] (length {:.9g})", n.x(), n.y(), n.z(), n.norm()));
  }
}

void validate(const Mesh& mesh) {
  if (!mesh.node_ids.empty() && mesh.node_ids.size() != mesh.coords.size()) {
    throw InputError({}, "node_ids",
                     fmt::format("{} node ids (one per node) or none", mesh.coords.size()),
                     fmt::format("{}", mesh.node_ids.size()));
  }
  for (std::size_t n = 0; n < mesh.coords.size(); ++n) {
    if (!mesh.coords[n].allFinite()) {
      throw InputError({}, fmt::format("nodes[id {}]", external_id(mesh, static_cast<int>(n))),
                       "finite coordinates", "a non-finite coordinate");
    }
  }
  std::vector<char> used_material(mesh.materials.size(), 0);
  for (const Element& e : mesh.elements) {
    const std::string key = fmt::format("elements[id {}]", e.id);
    element_kernel(e.type).check_node_count(static_cast<int>(e.nodes.size()), e.id, e.where);
    for (int node : e.nodes) check_node(mesh, node, e.where, key + ".nodes");
    if (e.material < 0 || e.material >= static_cast<int>(mesh.materials.size())) {
      throw InputError(e.where, key + ".material",
                       fmt::format("a material index in [0, {})", mesh.materials.size()),
                       fmt::format("{}", e.material));
    }
    used_material[static_cast<std::size_t>(e.material)] = 1;
  }
  for (std::size_t m = 0; m < mesh.materials.size(); ++m) {
    if (used_material[m]) check_material(mesh.materials[m]);
  }
  for (const PointMass& p : mesh.point_masses) {
    const std::string key = fmt::format("point_masses[id {}]", p.id);
    check_node(mesh, p.node, p.where, key + ".node");
    if (!std::isfinite(p.mass) || p.mass < 0) {
      throw InputError(p.where, key + ".mass", "a mass >= 0", fmt::format("{}", p.mass));
    }
    if (!p.offset.allFinite()) {
      throw InputError(p.where, key + ".offset", "a finite offset", "a non-finite value");
    }
    const double scale = std::max(p.inertia.cwiseAbs().maxCoeff(), 1e-300);
    if (!p.inertia.allFinite() ||
        (p.inertia - p.inertia.transpose()).cwiseAbs().maxCoeff() > 1e-12 * scale) {
      throw InputError(p.where, key + ".inertia", "a finite symmetric inertia matrix",
                       "a non-symmetric or non-finite matrix");
    }
  }
  for (const Spring& s : mesh.springs) {
    const std::string key = fmt::format("springs[id {}]", s.id);
    check_node(mesh, s.node1, s.where, key + ".node1");
    check_component(s.component1, s.where, key + ".component1");
    if (s.node2 != -1) {
      check_node(mesh, s.node2, s.where, key + ".node2");
      check_component(s.component2, s.where, key + ".component2");
    }
    if (!std::isfinite(s.stiffness)) {
      throw InputError(s.where, key + ".stiffness", "a finite stiffness",
                       fmt::format("{}", s.stiffness));
    }
    check_spring_direction(s.direction1, s.where, key + ".direction1");
    if (s.node2 != -1) check_spring_direction(s.direction2, s.where, key + ".direction2");
  }
  for (const RigidElement& r : mesh.rigid_elements) {
    const std::string key = fmt::format("rigid_elements[id {}]", r.id);
    check_node(mesh, r.reference, r.where, key + ".reference");
    if (r.nodes.empty()) {
      throw InputError(r.where, key + ".nodes", "at least one node", "none");
    }
    for (int node : r.nodes) {
      check_node(mesh, node, r.where, key + ".nodes");
      if (node == r.reference) {
        throw InputError(r.where, key + ".nodes", "nodes other than the reference/independent node",
                         fmt::format("node {} in both", external_id(mesh, node)));
      }
    }
    if (!r.weights.empty()) {
      if (r.weights.size() != r.nodes.size()) {
        throw InputError(r.where, key + ".weights",
                         fmt::format("{} weights (one per node) or none", r.nodes.size()),
                         fmt::format("{}", r.weights.size()));
      }
      double sum = 0;
      for (double w : r.weights) {
        if (!std::isfinite(w) || w < 0) {
          throw InputError(r.where, key + ".weights", "weights >= 0", fmt::format("{}", w));
        }
        sum += w;
      }
      if (!(sum > 0)) throw InputError(r.where, key + ".weights", "a positive sum", "0");
    }
  }
  for (const Constraint& c : mesh.constraints) {
    check_node(mesh, c.node, c.where, "constraints.node");
  }
}

// Builder state shared by the assembly steps.
struct Builder {
  const Mesh& mesh;
  std::vector<int> node_dofs, node_offset;
  int n_all = 0;
  std::vector<char> constrained;
  std::vector<std::vector<Term>> depends;  // per all-DOF: masters (all-DOF indices), if dependent
  std::vector<const RigidElement*> dependent_of;
  std::vector<char> is_dependent;
  // expansion of every all-DOF in kept all-DOFs: flat storage with offsets
  std::vector<int> exp_start;
  std::vector<Term> exp_terms;
  std::vector<int> reduced;  // all-DOF -> reduced index (kept DOFs), -1 otherwise

  explicit Builder(const Mesh& m) : mesh(m) {}

  int dof(int node, int c) const {
    const auto n = static_cast<std::size_t>(node);
    return c < node_dofs[n] ? node_offset[n] + c : -1;
  }
};

void add_dependency(Builder& b, int all_dof, std::vector<Term> masters, const RigidElement& r) {
  const auto d = static_cast<std::size_t>(all_dof);
  if (b.is_dependent[d]) {
    const RigidElement& other = *b.dependent_of[d];
    throw InputError(r.where, fmt::format("rigid_elements[id {}]", r.id),
                     "each DOF dependent in at most one rigid element",
                     fmt::format("a DOF already dependent in rigid element {} (line {})", other.id,
                                 other.where.line),
                     "remove one of the two rigid elements or the shared components");
  }
  b.is_dependent[d] = 1;
  b.dependent_of[d] = &r;
  b.depends[d] = std::move(masters);
}

void add_rigid(Builder& b, const RigidElement& r) {
  const Eigen::Vector3d xr = b.mesh.coords[static_cast<std::size_t>(r.reference)];
  for (int node : r.nodes) {
    const Eigen::Vector3d v = b.mesh.coords[static_cast<std::size_t>(node)] - xr;
    // u_d = u_r + theta_r x v = u_r - S(v) theta_r
    const Eigen::Matrix3d C = -skew(v);
    for (int c = 0; c < 6; ++c) {
      if (!r.components[static_cast<std::size_t>(c)]) continue;
      const int d = b.dof(node, c);
      if (d < 0) continue;  // rotation of a translation-only node: no such DOF
      std::vector<Term> masters;
      if (c < 3) {
        masters.push_back({b.dof(r.reference, c), 1.0});
        for (int j = 0; j < 3; ++j) {
          if (C(c, j) != 0) masters.push_back({b.dof(r.reference, 3 + j), C(c, j)});
        }
      } else {
        masters.push_back({b.dof(r.reference, c), 1.0});
      }
      add_dependency(b, d, std::move(masters), r);
    }
  }
}

void add_averaging(Builder& b, const RigidElement& r) {
  const std::string key = fmt::format("rigid_elements[id {}]", r.id);
  const std::size_t n = r.nodes.size();
  std::vector<double> w(n, 1.0);
  if (!r.weights.empty()) w = r.weights;
  double W = 0;
  Eigen::Vector3d c = Eigen::Vector3d::Zero();
  for (std::size_t i = 0; i < n; ++i) {
    W += w[i];
    c += w[i] * b.mesh.coords[static_cast<std::size_t>(r.nodes[i])];
  }
  c /= W;
  Eigen::Matrix3d J = Eigen::Matrix3d::Zero();
  double size2 = 0;
  for (std::size_t i = 0; i < n; ++i) {
    const Eigen::Vector3d ri = b.mesh.coords[static_cast<std::size_t>(r.nodes[i])] - c;
    J += w[i] * (ri.squaredNorm() * Eigen::Matrix3d::Identity() - ri * ri.transpose());
    size2 = std::max(size2, ri.squaredNorm());
  }
  const Eigen::Vector3d xr = b.mesh.coords[static_cast<std::size_t>(r.reference)];
  const Eigen::Vector3d e = xr - c;
  // Pseudo-inverse of J: eigenvalues below 1e-10 of the largest (or all, for one node) are the
  // undetermined rotations.
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(J);
  const double top = std::max(eig.eigenvalues().cwiseAbs().maxCoeff(), 0.0);
  Eigen::Matrix3d Jinv = Eigen::Matrix3d::Zero();
  bool any_rotation = false;
  for (int k = 3; k < 6; ++k)
    any_rotation = any_rotation || r.components[static_cast<std::size_t>(k)];
  for (int k = 0; k < 3; ++k) {
    const double lam = eig.eigenvalues()[k];
    const Eigen::Vector3d axis = eig.eigenvectors().col(k);
    if (top > 0 && lam > 1e-10 * top) {
      Jinv += axis * axis.transpose() / lam;
      continue;
    }
    // Undetermined rotation about `axis`: acceptable only if no rotation is asked for and the
    // reference point does not move when the fit rotates about it (e parallel to axis).
    const bool moves = (skew(e) * axis).norm() > 1e-9 * std::sqrt(std::max(size2, e.squaredNorm()));
    if (any_rotation || moves) {
      throw InputError(
          r.where, key + ".nodes",
          "independent nodes that fix the rotation of the reference node (not all on one line)",
          fmt::format("{} independent node(s) on one line; rotation about ({:.3g}, {:.3g}, {:.3g}) "
                      "undetermined",
                      n, axis.x(), axis.y(), axis.z()),
          "add non-collinear independent nodes, or list only translations (components 123) "
          "with the reference node on the line of the independent nodes");
    }
  }
  // u_r = sum_i [(w_i/W) I - S(e) J^-1 w_i S(r_i)] u_i;  theta_r = sum_i J^-1 w_i S(r_i) u_i
  std::vector<Eigen::Matrix3d> At(n), Ar(n);
  for (std::size_t i = 0; i < n; ++i) {
    const Eigen::Vector3d ri = b.mesh.coords[static_cast<std::size_t>(r.nodes[i])] - c;
    Ar[i] = Jinv * (w[i] * skew(ri));
    At[i] = (w[i] / W) * Eigen::Matrix3d::Identity() - skew(e) * Ar[i];
  }
  for (int comp = 0; comp < 6; ++comp) {
    if (!r.components[static_cast<std::size_t>(comp)]) continue;
    const int d = b.dof(r.reference, comp);
    if (d < 0) continue;
    std::vector<Term> masters;
    for (std::size_t i = 0; i < n; ++i) {
      const Eigen::Matrix3d& A = comp < 3 ? At[i] : Ar[i];
      const int row = comp % 3;
      for (int j = 0; j < 3; ++j) {
        const double v = A(row, j);
        if (v != 0) masters.push_back({b.dof(r.nodes[i], j), v});
      }
    }
    add_dependency(b, d, std::move(masters), r);
  }
}

// Expands every all-DOF into kept all-DOFs (depth-first, memoised, cycle-checked).
void expand_all(Builder& b) {
  const auto n = static_cast<std::size_t>(b.n_all);
  std::vector<std::vector<Term>> exp(n);
  std::vector<char> state(n, 0);  // 0 new, 1 in progress, 2 done
  // Recursive lambda through std::function-free helper.
  struct Rec {
    Builder& b;
    std::vector<std::vector<Term>>& exp;
    std::vector<char>& state;
    void run(int d) {
      const auto s = static_cast<std::size_t>(d);
      if (state[s] == 2) return;
      if (state[s] == 1) {
        const RigidElement& r = *b.dependent_of[s];
        throw InputError(r.where, fmt::format("rigid_elements[id {}]", r.id),
                         "rigid elements without circular dependencies",
                         "a chain of rigid elements that depends on itself");
      }
      state[s] = 1;
      std::vector<Term> out;
      if (b.constrained[s]) {
        // fixed: no terms
      } else if (!b.is_dependent[s]) {
        out.push_back({d, 1.0});
      } else {
        for (const Term& t : b.depends[s]) {
          run(t.first);
          for (const Term& u : exp[static_cast<std::size_t>(t.first)]) {
            out.push_back({u.first, t.second * u.second});
          }
        }
        std::sort(out.begin(), out.end(),
                  [](const Term& x, const Term& y) { return x.first < y.first; });
        std::vector<Term> merged;
        for (const Term& t : out) {
          if (!merged.empty() && merged.back().first == t.first) {
            merged.back().second += t.second;
          } else {
            merged.push_back(t);
          }
        }
        out.clear();
        for (const Term& t : merged) {
          if (t.second != 0) out.push_back(t);
        }
      }
      exp[s] = std::move(out);
      state[s] = 2;
    }
  } rec{b, exp, state};
  for (int d = 0; d < b.n_all; ++d) rec.run(d);
  b.exp_start.assign(n + 1, 0);
  for (std::size_t d = 0; d < n; ++d) {
    b.exp_start[d + 1] = b.exp_start[d] + static_cast<int>(exp[d].size());
  }
  b.exp_terms.clear();
  b.exp_terms.reserve(static_cast<std::size_t>(b.exp_start[n]));
  for (auto& e : exp) {
    for (const Term& t : e) b.exp_terms.push_back(t);
  }
}

// The sparse pattern (CSC, both triangles; a view on the compressed K) and the scatter of dense
// blocks into it.
struct Pattern {
  const int* outer = nullptr;  // n + 1
  const int* inner = nullptr;
  int find(int row, int col) const {
    const int* lo = inner + outer[col];
    const int* hi = inner + outer[col + 1];
    return static_cast<int>(std::lower_bound(lo, hi, row) - inner);
  }
};

// Expansion of a list of all-DOFs into reduced DOFs: per local DOF a range of (reduced, coef).
struct LocalExpansion {
  std::vector<int> start;
  std::vector<Term> terms;
  std::vector<int> local;   // per term: its local DOF
  std::vector<int> by_row;  // term indices sorted by reduced row index
  int min_col = 0, max_col = -1;
  void sort_rows() {
    local.resize(terms.size());
    for (std::size_t p = 0; p + 1 < start.size(); ++p) {
      for (int i = start[p]; i < start[p + 1]; ++i)
        local[static_cast<std::size_t>(i)] = static_cast<int>(p);
    }
    by_row.resize(terms.size());
    for (std::size_t i = 0; i < by_row.size(); ++i) by_row[i] = static_cast<int>(i);
    std::sort(by_row.begin(), by_row.end(), [&](int x, int y) {
      return terms[static_cast<std::size_t>(x)].first < terms[static_cast<std::size_t>(y)].first;
    });
  }
  void build(const Builder& b, const std::vector<int>& all_dofs) {
    start.assign(all_dofs.size() + 1, 0);
    terms.clear();
    min_col = std::numeric_limits<int>::max();
    max_col = -1;
    for (std::size_t p = 0; p < all_dofs.size(); ++p) {
      const int d = all_dofs[p];
      if (d >= 0) {
        const auto s = static_cast<std::size_t>(d);
        for (int k = b.exp_start[s]; k < b.exp_start[s + 1]; ++k) {
          const Term& t = b.exp_terms[static_cast<std::size_t>(k)];
          const int r = b.reduced[static_cast<std::size_t>(t.first)];
          terms.push_back({r, t.second});
          min_col = std::min(min_col, r);
          max_col = std::max(max_col, r);
        }
      }
      start[p + 1] = static_cast<int>(terms.size());
    }
  }
};

// values[pos(r1, r2)] += c1 c2 A(p, q) for columns r2 in [col_lo, col_hi).
void scatter(const Pattern& pattern, const LocalExpansion& e, const Eigen::MatrixXd& A,
             double* values, int col_lo, int col_hi) {
  const int n = static_cast<int>(e.start.size()) - 1;
  for (int q = 0; q < n; ++q) {
    for (int j = e.start[static_cast<std::size_t>(q)]; j < e.start[static_cast<std::size_t>(q) + 1];
         ++j) {
      const auto [col, cq] = e.terms[static_cast<std::size_t>(j)];
      if (col < col_lo || col >= col_hi) continue;
      for (int p = 0; p < n; ++p) {
        const double a = A(p, q);
        if (a == 0) continue;
        for (int i = e.start[static_cast<std::size_t>(p)];
             i < e.start[static_cast<std::size_t>(p) + 1]; ++i) {
          const auto [row, cp] = e.terms[static_cast<std::size_t>(i)];
          values[pattern.find(row, col)] += cp * cq * a;
        }
      }
    }
  }
}

// Element scatter, the inner loop of assembly: for every column term, one merge walk through
// the column's sorted row indices and the element's row-sorted terms finds all positions
// (instead of a binary search per entry). K and the consistent mass rho m ⊗ I_3 share the
// positions.
void scatter_element(const Pattern& pattern, const LocalExpansion& e, const Eigen::MatrixXd& K,
                     const Eigen::MatrixXd* m, double rho, double* kv, double* mv, int col_lo,
                     int col_hi) {
  const std::size_t nt = e.terms.size();
  for (std::size_t j = 0; j < nt; ++j) {
    const auto [col, cq] = e.terms[j];
    if (col < col_lo || col >= col_hi) continue;
    const int q = e.local[j];
    const int* inner = pattern.inner;
    int pos = pattern.outer[col];
    for (std::size_t k = 0; k < nt; ++k) {
      const auto i = static_cast<std::size_t>(e.by_row[k]);
      const auto [row, cp] = e.terms[i];
      while (inner[pos] < row) ++pos;
      const int p = e.local[i];
      const double c = cp * cq;
      kv[pos] += c * K(p, q);
      if (m != nullptr && p % 3 == q % 3) mv[pos] += c * rho * (*m)(p / 3, q / 3);
    }
  }
}

}  // namespace

std::vector<int> node_dof_counts(const Mesh& mesh) {
  const auto n = static_cast<std::size_t>(mesh.num_nodes());
  std::vector<char> in_solid(n, 0), referenced(n, 0), rotations(n, 0);
  for (const Element& e : mesh.elements) {
    for (int node : e.nodes) {
      if (node >= 0 && static_cast<std::size_t>(node) < n)
        in_solid[static_cast<std::size_t>(node)] = 1;
    }
  }
  auto mark = [&](int node, bool rot) {
    if (node < 0 || static_cast<std::size_t>(node) >= n) return;
    referenced[static_cast<std::size_t>(node)] = 1;
    if (rot) rotations[static_cast<std::size_t>(node)] = 1;
  };
  for (const RigidElement& r : mesh.rigid_elements) {
    bool any_rotation = false;
    for (int k = 3; k < 6; ++k)
      any_rotation = any_rotation || r.components[static_cast<std::size_t>(k)];
    mark(r.reference, r.kind == RigidElement::Kind::Rigid || any_rotation);
    for (int node : r.nodes) mark(node, false);
  }
  for (const PointMass& p : mesh.point_masses) {
    mark(p.node, !p.inertia.isZero(0.0) || !p.offset.isZero(0.0));
  }
  for (const Spring& s : mesh.springs) {
    mark(s.node1, s.component1 >= 3);
    if (s.node2 != -1) mark(s.node2, s.component2 >= 3);
  }
  for (const Constraint& c : mesh.constraints) mark(c.node, false);
  std::vector<int> dofs(n, 0);
  for (std::size_t i = 0; i < n; ++i) {
    if (rotations[i] || (referenced[i] && !in_solid[i])) {
      dofs[i] = 6;
    } else if (in_solid[i]) {
      dofs[i] = 3;
    }
  }
  return dofs;
}

int SolidSystem::all_dof(int node, int component) const {
  if (node < 0 || node >= static_cast<int>(node_dofs.size()) || component < 0) return -1;
  const auto n = static_cast<std::size_t>(node);
  return component < node_dofs[n] ? node_offset[n] + component : -1;
}

int SolidSystem::node_dof(int node, int component) const {
  const int d = all_dof(node, component);
  return d < 0 ? -1 : reduced_index[static_cast<std::size_t>(d)];
}

namespace {

// Numbers every node's DOFs, applies constraints and rigid elements, expands the dependencies and
// numbers the remaining (reduced) DOFs. Returns the number of reduced DOFs.
int number_dofs(Builder& b, const Mesh& mesh) {
  const int n_nodes = mesh.num_nodes();
  b.node_dofs = node_dof_counts(mesh);
  b.node_offset.assign(static_cast<std::size_t>(n_nodes), 0);
  for (int i = 0; i < n_nodes; ++i) {
    b.node_offset[static_cast<std::size_t>(i)] = b.n_all;
    b.n_all += b.node_dofs[static_cast<std::size_t>(i)];
  }
  const auto n_all = static_cast<std::size_t>(b.n_all);
  b.constrained.assign(n_all, 0);
  for (const Constraint& c : mesh.constraints) {
    for (int k = 0; k < 6; ++k) {
      const int d = b.dof(c.node, k);
      if (c.components[static_cast<std::size_t>(k)] && d >= 0)
        b.constrained[static_cast<std::size_t>(d)] = 1;
    }
  }
  b.depends.assign(n_all, {});
  b.dependent_of.assign(n_all, nullptr);
  b.is_dependent.assign(n_all, 0);
  for (const RigidElement& r : mesh.rigid_elements) {
    if (r.kind == RigidElement::Kind::Rigid) {
      add_rigid(b, r);
    } else {
      add_averaging(b, r);
    }
  }
  for (const Constraint& c : mesh.constraints) {
    for (int k = 0; k < 6; ++k) {
      const int d = b.dof(c.node, k);
      if (d >= 0 && c.components[static_cast<std::size_t>(k)] &&
          b.is_dependent[static_cast<std::size_t>(d)]) {
        const RigidElement& r = *b.dependent_of[static_cast<std::size_t>(d)];
        throw InputError(
            c.where, fmt::format("constraints[node {}]", external_id(mesh, c.node)),
            "constraints on independent DOFs only",
            fmt::format("component {} of node {}, dependent in rigid element {} "
                        "(components {})",
                        k + 1, external_id(mesh, c.node), r.id, component_list(r.components)),
            "constrain the independent node of the rigid element instead");
      }
    }
  }
  expand_all(b);
  b.reduced.assign(n_all, -1);
  int n_red = 0;
  for (std::size_t d = 0; d < n_all; ++d) {
    if (!b.constrained[d] && !b.is_dependent[d]) b.reduced[d] = n_red++;
  }
  return n_red;
}

// Node adjacency over coupling groups (elements, point masses, springs), through the master
// nodes of each node (the owners of the reduced DOFs in the expansions of its DOFs).
std::vector<std::vector<int>> node_adjacency(const Builder& b, const Mesh& mesh, int n_red) {
  const int n_nodes = mesh.num_nodes();
  // Node that owns each reduced DOF.
  std::vector<int> owner(static_cast<std::size_t>(n_red));
  for (int i = 0; i < n_nodes; ++i) {
    for (int k = 0; k < b.node_dofs[static_cast<std::size_t>(i)]; ++k) {
      const int r =
          b.reduced[static_cast<std::size_t>(b.node_offset[static_cast<std::size_t>(i)] + k)];
      if (r >= 0) owner[static_cast<std::size_t>(r)] = i;
    }
  }
  // Master nodes of each node: owners of the reduced DOFs in the expansions of its DOFs.
  std::vector<int> master_start(static_cast<std::size_t>(n_nodes) + 1, 0);
  std::vector<int> masters;
  for (int i = 0; i < n_nodes; ++i) {
    const auto s = static_cast<std::size_t>(i);
    const std::size_t first = masters.size();
    for (int k = 0; k < b.node_dofs[s]; ++k) {
      const auto d = static_cast<std::size_t>(b.node_offset[s] + k);
      for (int t = b.exp_start[d]; t < b.exp_start[d + 1]; ++t) {
        const int r =
            b.reduced[static_cast<std::size_t>(b.exp_terms[static_cast<std::size_t>(t)].first)];
        masters.push_back(owner[static_cast<std::size_t>(r)]);
      }
    }
    std::sort(masters.begin() + static_cast<std::ptrdiff_t>(first), masters.end());
    masters.erase(std::unique(masters.begin() + static_cast<std::ptrdiff_t>(first), masters.end()),
                  masters.end());
    master_start[s + 1] = static_cast<int>(masters.size());
  }
  // Node adjacency over coupling groups (elements, point masses, springs).
  std::vector<std::vector<int>> adjacency(static_cast<std::size_t>(n_nodes));
  std::vector<int> group;
  auto couple = [&](const std::vector<int>& nodes) {
    group.clear();
    for (int node : nodes) {
      const auto s = static_cast<std::size_t>(node);
      group.insert(group.end(), masters.begin() + master_start[s],
                   masters.begin() + master_start[s + 1]);
    }
    std::sort(group.begin(), group.end());
    group.erase(std::unique(group.begin(), group.end()), group.end());
    for (int a : group) {
      auto& adj = adjacency[static_cast<std::size_t>(a)];
      adj.insert(adj.end(), group.begin(), group.end());
    }
  };
  for (const Element& e : mesh.elements) couple(e.nodes);
  for (const PointMass& p : mesh.point_masses) couple({p.node});
  for (const Spring& s : mesh.springs) {
    if (s.node2 == -1) {
      couple({s.node1});
    } else {
      couple({s.node1, s.node2});
    }
  }
  return adjacency;
}

// Allocates K once, compressed, with its final pattern (the adjacency is consumed).
void allocate_pattern(Eigen::SparseMatrix<double>& K, const Builder& b, const Mesh& mesh,
                      std::vector<std::vector<int>>& adjacency, int n_red) {
  const int n_nodes = mesh.num_nodes();
  K.resize(n_red, n_red);
  std::vector<int> outer(static_cast<std::size_t>(n_red) + 1, 0);
  // Reduced DOFs of each node are contiguous: [first_red[i], first_red[i] + count_red[i]).
  std::vector<int> first_red(static_cast<std::size_t>(n_nodes), 0),
      count_red(static_cast<std::size_t>(n_nodes), 0);
  for (int i = 0; i < n_nodes; ++i) {
    const auto s = static_cast<std::size_t>(i);
    first_red[s] = -1;
    for (int k = 0; k < b.node_dofs[s]; ++k) {
      const int r = b.reduced[static_cast<std::size_t>(b.node_offset[s] + k)];
      if (r < 0) continue;
      if (first_red[s] < 0) first_red[s] = r;
      ++count_red[s];
    }
  }
  std::size_t nnz = 0;
  for (auto& adj : adjacency) {
    std::sort(adj.begin(), adj.end());
    adj.erase(std::unique(adj.begin(), adj.end()), adj.end());
  }
  for (int i = 0; i < n_nodes; ++i) {
    const auto s = static_cast<std::size_t>(i);
    if (count_red[s] == 0) continue;
    std::size_t rows = 0;
    for (int a : adjacency[s])
      rows += static_cast<std::size_t>(count_red[static_cast<std::size_t>(a)]);
    for (int k = 0; k < count_red[s]; ++k) {
      outer[static_cast<std::size_t>(first_red[s] + k) + 1] = static_cast<int>(rows);
    }
    nnz += rows * static_cast<std::size_t>(count_red[s]);
  }
  if (nnz > static_cast<std::size_t>(std::numeric_limits<int>::max())) {
    throw InputError({}, mesh.source.empty() ? std::string("mesh") : mesh.source,
                     "a model with fewer than 2^31 stiffness non-zeros",
                     fmt::format("{} non-zeros", nnz), "reduce the mesh size");
  }
  for (int c = 0; c < n_red; ++c) {
    outer[static_cast<std::size_t>(c) + 1] += outer[static_cast<std::size_t>(c)];
  }
  K.resizeNonZeros(static_cast<Eigen::Index>(nnz));
  std::copy(outer.begin(), outer.end(), K.outerIndexPtr());
  int* inner = K.innerIndexPtr();
  for (int i = 0; i < n_nodes; ++i) {
    const auto s = static_cast<std::size_t>(i);
    for (int k = 0; k < count_red[s]; ++k) {
      int pos = outer[static_cast<std::size_t>(first_red[s] + k)];
      for (int a : adjacency[s]) {
        const auto sa = static_cast<std::size_t>(a);
        for (int j = 0; j < count_red[sa]; ++j) inner[pos++] = first_red[sa] + j;
      }
    }
  }
  adjacency.clear();
  adjacency.shrink_to_fit();
}

// Element loop. Thread t owns the columns [lo_t, hi_t) and integrates every element that has a
// column there (elements on a boundary between ranges are integrated twice): no two threads
// write the same value, and the result does not depend on the thread count. Returns the volume
// of each element.
std::vector<double> assemble_elements(const Builder& b, const Mesh& mesh,
                                      const AssemblyOptions& options, const Pattern& pattern,
                                      int n_red, double* kv, double* mv) {
  std::vector<double> element_volume(mesh.elements.size(), 0.0);
  int threads = options.threads == 0
                    ? static_cast<int>(std::max(1u, std::thread::hardware_concurrency()))
                    : options.threads;
  threads = std::max(1, std::min(threads, std::max(1, n_red / 3000)));
  Progress& progress = options.progress ? *options.progress : null_progress();
  progress.start("solid element assembly", mesh.elements.size());
  std::vector<std::exception_ptr> errors(static_cast<std::size_t>(threads));
  auto work = [&](int t) {
    try {
      const int lo = static_cast<int>(static_cast<long long>(n_red) * t / threads);
      const int hi = static_cast<int>(static_cast<long long>(n_red) * (t + 1) / threads);
      LocalExpansion e;
      std::vector<int> all_dofs;
      std::vector<Eigen::Vector3d> x;
      Eigen::MatrixXd Ke, me;
      std::size_t counted = 0;
      for (std::size_t k = 0; k < mesh.elements.size(); ++k) {
        const Element& el = mesh.elements[k];
        all_dofs.clear();
        x.clear();
        for (int node : el.nodes) {
          x.push_back(mesh.coords[static_cast<std::size_t>(node)]);
          for (int c = 0; c < 3; ++c) all_dofs.push_back(b.dof(node, c));
        }
        e.build(b, all_dofs);
        if (t == 0 && ++counted % 1024 == 0) progress.update(counted);
        if (e.max_col < lo || e.min_col >= hi) continue;
        e.sort_rows();
        const Material& mat = mesh.materials[static_cast<std::size_t>(el.material)];
        const double v = element_kernel(el.type).compute(x.data(), mat.E, mat.nu, el.id, el.where,
                                                         Ke, options.mass ? &me : nullptr);
        if (e.min_col >= lo) element_volume[k] = v;  // one owner per element
        scatter_element(pattern, e, Ke, options.mass ? &me : nullptr, mat.rho, kv, mv, lo, hi);
      }
    } catch (...) {
      errors[static_cast<std::size_t>(t)] = std::current_exception();
    }
  };
  if (threads == 1) {
    work(0);
  } else {
    std::vector<std::thread> pool;
    for (int t = 0; t < threads; ++t) pool.emplace_back(work, t);
    for (auto& th : pool) th.join();
  }
  for (auto& err : errors) {
    if (err) std::rethrow_exception(err);
  }
  progress.finish();
  return element_volume;
}

// Point masses and springs (few; serial).
void add_point_masses_and_springs(const Builder& b, const Mesh& mesh,
                                  const AssemblyOptions& options, const Pattern& pattern, int n_red,
                                  double* kv, double* mv) {
  LocalExpansion e;
  std::vector<int> all_dofs;
  for (const PointMass& p : mesh.point_masses) {
    if (!options.mass) break;
    const int nd = b.node_dofs[static_cast<std::size_t>(p.node)];
    all_dofs.clear();
    for (int c = 0; c < nd; ++c) all_dofs.push_back(b.dof(p.node, c));
    Eigen::MatrixXd Mp = Eigen::MatrixXd::Zero(nd, nd);
    Mp.topLeftCorner(3, 3) = p.mass * Eigen::Matrix3d::Identity();
    if (nd == 6) {
      const Eigen::Matrix3d S = skew(p.offset);
      Mp.block(0, 3, 3, 3) = -p.mass * S;
      Mp.block(3, 0, 3, 3) = p.mass * S;
      Mp.block(3, 3, 3, 3) =
          p.inertia + p.mass * (p.offset.squaredNorm() * Eigen::Matrix3d::Identity() -
                                p.offset * p.offset.transpose());
    }
    e.build(b, all_dofs);
    scatter(pattern, e, Mp, mv, 0, n_red);
  }
  // Spring: stretch d = c . u_local over the DOFs of its ends (one DOF for an end along its
  // component, the node's triple for an end with a direction), K_s = k c c^T.
  std::vector<double> c;
  const auto add_end = [&](int node, int component, const Eigen::Vector3d& direction, double sign) {
    if (direction.isZero(0.0)) {
      all_dofs.push_back(b.dof(node, component));
      c.push_back(sign);
      return;
    }
    const int first = 3 * (component / 3);
    for (int j = 0; j < 3; ++j) {
      all_dofs.push_back(b.dof(node, first + j));
      c.push_back(sign * direction[j]);
    }
  };
  for (const Spring& s : mesh.springs) {
    all_dofs.clear();
    c.clear();
    add_end(s.node1, s.component1, s.direction1, 1.0);
    if (s.node2 != -1) add_end(s.node2, s.component2, s.direction2, -1.0);
    const Eigen::Map<const Eigen::VectorXd> cv(c.data(), static_cast<Eigen::Index>(c.size()));
    const Eigen::MatrixXd Ks = s.stiffness * cv * cv.transpose();
    e.build(b, all_dofs);
    scatter(pattern, e, Ks, kv, 0, n_red);
  }
}

// DOFs with no stiffness and no mass at all: removed from K and M (when the options ask for
// it). Returns the final index of each reduced DOF (-1: removed) and sets n_final.
std::vector<int> remove_unconnected(SolidSystem& sys, const AssemblyOptions& options,
                                    const Pattern& pattern, int n_red, const double* kv,
                                    const double* mv, int& n_final) {
  std::vector<int> final_index(static_cast<std::size_t>(n_red));
  n_final = 0;
  std::vector<char> remove(static_cast<std::size_t>(n_red), 0);
  if (options.remove_unconnected_dofs) {
    for (int c = 0; c < n_red; ++c) {
      bool empty = true;
      for (int k = pattern.outer[c]; k < pattern.outer[c + 1] && empty; ++k) {
        empty = kv[k] == 0 && (mv == nullptr || mv[k] == 0);
      }
      remove[static_cast<std::size_t>(c)] = empty;
    }
  }
  for (int c = 0; c < n_red; ++c) {
    final_index[static_cast<std::size_t>(c)] = remove[static_cast<std::size_t>(c)] ? -1 : n_final++;
  }
  if (n_final < n_red) {
    // Drop the removed columns and rows (all their values are zero) from K and M.
    const int n_kept = n_final;
    auto compact = [&](const Eigen::SparseMatrix<double>& A) {
      std::vector<Eigen::Triplet<double>> t;
      t.reserve(static_cast<std::size_t>(A.nonZeros()));
      for (int c = 0; c < n_red; ++c) {
        const int fc = final_index[static_cast<std::size_t>(c)];
        if (fc < 0) continue;
        for (Eigen::SparseMatrix<double>::InnerIterator it(A, c); it; ++it) {
          const int fr = final_index[static_cast<std::size_t>(it.row())];
          if (fr >= 0) t.emplace_back(fr, fc, it.value());
        }
      }
      Eigen::SparseMatrix<double> B(n_kept, n_kept);
      B.setFromTriplets(t.begin(), t.end());
      return B;
    };
    sys.K = compact(sys.K);
    if (options.mass) sys.M = compact(sys.M);
  }
  return final_index;
}

// The recovery matrix (all DOFs from the final ones), the reduced index of every DOF and the
// description of the final and the removed DOFs.
void describe_dofs(SolidSystem& sys, const Builder& b, const Mesh& mesh,
                   const std::vector<int>& final_index, int n_final) {
  const auto n_all = static_cast<std::size_t>(b.n_all);
  sys.reduced_index.assign(n_all, -1);
  std::vector<Eigen::Triplet<double>> rec;
  rec.reserve(b.exp_terms.size());
  for (std::size_t d = 0; d < n_all; ++d) {
    for (int k = b.exp_start[d]; k < b.exp_start[d + 1]; ++k) {
      const Term& t = b.exp_terms[static_cast<std::size_t>(k)];
      const int f =
          final_index[static_cast<std::size_t>(b.reduced[static_cast<std::size_t>(t.first)])];
      if (f >= 0) rec.emplace_back(static_cast<int>(d), f, t.second);
    }
    if (b.reduced[d] >= 0)
      sys.reduced_index[d] = final_index[static_cast<std::size_t>(b.reduced[d])];
  }
  sys.recovery.resize(b.n_all, n_final);
  sys.recovery.setFromTriplets(rec.begin(), rec.end());

  sys.dofs.resize(static_cast<std::size_t>(n_final));
  for (int i = 0; i < mesh.num_nodes(); ++i) {
    const auto s = static_cast<std::size_t>(i);
    for (int k = 0; k < b.node_dofs[s]; ++k) {
      const auto d = static_cast<std::size_t>(b.node_offset[s] + k);
      const DofInfo info{external_id(mesh, i), k, mesh.coords[s]};
      if (sys.reduced_index[d] >= 0) {
        sys.dofs[static_cast<std::size_t>(sys.reduced_index[d])] = info;
      } else if (b.reduced[d] >= 0) {
        sys.removed_dofs.push_back(info);
      }
    }
  }
}

}  // namespace

SolidSystem assemble(const Mesh& mesh, const AssemblyOptions& options) {
  const auto t0 = std::chrono::steady_clock::now();
  if (options.threads < 0) {
    throw InputError({}, "assembly.threads", "a thread count >= 0 (0: all cores)",
                     fmt::format("{}", options.threads));
  }
  validate(mesh);
  Builder b(mesh);
  const int n_red = number_dofs(b, mesh);
  std::vector<std::vector<int>> adjacency = node_adjacency(b, mesh, n_red);
  // K is allocated once, compressed, with its final pattern; M shares it.
  SolidSystem sys;
  Eigen::SparseMatrix<double>& K = sys.K;
  allocate_pattern(K, b, mesh, adjacency, n_red);
  std::fill_n(K.valuePtr(), K.nonZeros(), 0.0);
  Eigen::SparseMatrix<double>& M = sys.M;
  if (options.mass) M = K;
  const Pattern pattern{K.outerIndexPtr(), K.innerIndexPtr()};
  double* kv = K.valuePtr();
  double* mv = options.mass ? M.valuePtr() : nullptr;
  const std::vector<double> element_volume =
      assemble_elements(b, mesh, options, pattern, n_red, kv, mv);
  add_point_masses_and_springs(b, mesh, options, pattern, n_red, kv, mv);

  sys.node_dofs = b.node_dofs;
  sys.node_offset = b.node_offset;
  sys.num_elements = mesh.num_elements();
  for (std::size_t k = 0; k < mesh.elements.size(); ++k) {
    sys.volume += element_volume[k];
    sys.solid_mass +=
        element_volume[k] * mesh.materials[static_cast<std::size_t>(mesh.elements[k].material)].rho;
  }

  int n_final = 0;
  const std::vector<int> final_index =
      remove_unconnected(sys, options, pattern, n_red, kv, mv, n_final);
  describe_dofs(sys, b, mesh, final_index, n_final);
  sys.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return sys;
}

std::vector<int> nodes_of_set(const Mesh& mesh, const std::string& name, SourceLocation where) {
  const auto it = mesh.node_sets.find(name);
  if (it != mesh.node_sets.end()) return it->second;
  std::string available;
  for (const auto& [key, nodes] : mesh.node_sets) {
    available +=
        (available.empty() ? "" : ", ") + fmt::format("'{}' ({} nodes)", key, nodes.size());
  }
  throw InputError(
      std::move(where), name, "the name of a node set of the mesh",
      fmt::format("'{}', which the mesh{} does not define", name,
                  mesh.source.empty() ? "" : " " + mesh.source),
      available.empty() ? "the mesh has no node sets" : "available node sets: " + available);
}

}  // namespace geardyn::solid
