#include "geardyn/solid/element_kernel.hpp"

#include <fmt/format.h>

#include <array>
#include <cmath>
#include <limits>
#include <utility>
#include <vector>

namespace geardyn::solid {
namespace {

struct QuadraturePoint {
  Eigen::Vector3d xi;
  double weight;
};
using Rule = std::vector<QuadraturePoint>;

Rule gauss_line(int n, std::vector<double>& w) {
  Rule r;
  std::vector<double> x;
  if (n == 2) {
    const double a = 1.0 / std::sqrt(3.0);
    x = {-a, a};
    w = {1.0, 1.0};
  } else {
    const double a = std::sqrt(0.6);
    x = {-a, 0.0, a};
    w = {5.0 / 9.0, 8.0 / 9.0, 5.0 / 9.0};
  }
  for (double v : x) r.push_back({Eigen::Vector3d(v, 0, 0), 0});
  return r;
}

Rule gauss_hex(int n) {
  std::vector<double> w;
  const Rule line = gauss_line(n, w);
  Rule r;
  for (int i = 0; i < n; ++i) {
    for (int j = 0; j < n; ++j) {
      for (int k = 0; k < n; ++k) {
        const auto si = static_cast<std::size_t>(i), sj = static_cast<std::size_t>(j),
                   sk = static_cast<std::size_t>(k);
        r.push_back({Eigen::Vector3d(line[si].xi[0], line[sj].xi[0], line[sk].xi[0]),
                     w[si] * w[sj] * w[sk]});
      }
    }
  }
  return r;
}

Rule tet_rule(int degree) {
  Rule r;
  if (degree <= 1) {
    r.push_back({Eigen::Vector3d(0.25, 0.25, 0.25), 1.0 / 6.0});
  } else if (degree == 2) {
    const double a = (5.0 - std::sqrt(5.0)) / 20.0, b = (5.0 + 3.0 * std::sqrt(5.0)) / 20.0;
    for (const auto& p : {Eigen::Vector3d(a, a, a), Eigen::Vector3d(b, a, a),
                          Eigen::Vector3d(a, b, a), Eigen::Vector3d(a, a, b)}) {
      r.push_back({p, 1.0 / 24.0});
    }
  } else {
    // Degree-5 rule with 14 points and positive weights (Walkington, "Quadrature on simplices of
    // arbitrary dimension", CNA report 00-CNA-023, Carnegie Mellon 2000; also Keast 1986 #6),
    // weights for the reference volume 1/6: orbits (a,a,b,b) x 6, (a,a,a,1-3a) x 4 twice.
    const double a = 0.0455037041256496, b = 0.5 - a;
    for (const auto& p :
         {Eigen::Vector3d(a, a, b), Eigen::Vector3d(a, b, a), Eigen::Vector3d(b, a, a),
          Eigen::Vector3d(a, b, b), Eigen::Vector3d(b, a, b), Eigen::Vector3d(b, b, a)}) {
      r.push_back({p, 0.007091003462846911});
    }
    for (const auto& [c, w] : {std::pair{0.0927352503108912, 0.01224884051939366},
                               std::pair{0.3108859192633006, 0.01878132095300264}}) {
      const double d = 1 - 3 * c;
      for (const auto& p : {Eigen::Vector3d(c, c, c), Eigen::Vector3d(d, c, c),
                            Eigen::Vector3d(c, d, c), Eigen::Vector3d(c, c, d)}) {
        r.push_back({p, w});
      }
    }
  }
  return r;
}

// Triangle rule x Gauss line. Triangle: degree 2 (3 interior points) or degree 5 (7 points,
// Strang & Fix 1973, table 4.1; Radon's rule).
Rule wedge_rule(int tri_degree, int line_points) {
  std::vector<std::pair<Eigen::Vector2d, double>> tri;
  if (tri_degree <= 2) {
    tri = {{Eigen::Vector2d(1.0 / 6, 1.0 / 6), 1.0 / 6},
           {Eigen::Vector2d(2.0 / 3, 1.0 / 6), 1.0 / 6},
           {Eigen::Vector2d(1.0 / 6, 2.0 / 3), 1.0 / 6}};
  } else {
    const double s = std::sqrt(15.0);
    const double a1 = (6 - s) / 21, b1 = (9 + 2 * s) / 21, w1 = (155 - s) / 2400;
    const double a2 = (6 + s) / 21, b2 = (9 - 2 * s) / 21, w2 = (155 + s) / 2400;
    tri = {{Eigen::Vector2d(1.0 / 3, 1.0 / 3), 9.0 / 80},
           {Eigen::Vector2d(a1, a1), w1},
           {Eigen::Vector2d(b1, a1), w1},
           {Eigen::Vector2d(a1, b1), w1},
           {Eigen::Vector2d(a2, a2), w2},
           {Eigen::Vector2d(b2, a2), w2},
           {Eigen::Vector2d(a2, b2), w2}};
  }
  std::vector<double> w;
  const Rule line = gauss_line(line_points, w);
  Rule r;
  for (const auto& [p, wt] : tri) {
    for (std::size_t k = 0; k < line.size(); ++k) {
      r.push_back({Eigen::Vector3d(p[0], p[1], line[k].xi[0]), wt * w[k]});
    }
  }
  return r;
}

double reference_volume(ElementType t) {
  switch (t) {
    case ElementType::Tet4:
    case ElementType::Tet10:
      return 1.0 / 6.0;
    case ElementType::Hex8:
    case ElementType::Hex20:
      return 8.0;
    case ElementType::Wedge6:
    case ElementType::Wedge15:
      return 1.0;
  }
  return 1.0;
}

template <int N>
class Kernel final : public ElementKernel {
 public:
  using NodeMatrix = Eigen::Matrix<double, N, 3>;
  using NodeVector = Eigen::Matrix<double, N, 1>;
  struct Point {
    double weight;
    NodeVector N_;
    NodeMatrix dN;
  };

  Kernel(ElementType type, const Rule& stiffness, const Rule& mass) : type_(type) {
    fill(stiffness, stiffness_);
    fill(mass, mass_);
    const Eigen::MatrixXd r = reference_nodes(type);
    Rule at_nodes;
    for (int i = 0; i < N; ++i) at_nodes.push_back({r.row(i).transpose(), 0.0});
    fill(at_nodes, nodes_);
    reference_volume_ = reference_volume(type);
  }

  ElementType type() const override { return type_; }
  int nodes() const override { return N; }

  double compute(const Eigen::Vector3d* x, double E, double nu, long id,
                 const SourceLocation& where, Eigen::MatrixXd& K,
                 Eigen::MatrixXd* m) const override {
    NodeMatrix X;
    for (int a = 0; a < N; ++a) X.row(a) = x[a].transpose();
    const ElementQuality q = quality_of(X);
    if (!(q.min_ratio > kMinJacobianRatio) || !(q.volume > 0) || !std::isfinite(q.volume)) {
      throw InputError(where, fmt::format("elements[id {}]", id),
                       fmt::format("a valid {} element (det J > {} x mean det J at every node and "
                                   "integration point)",
                                   to_string(type_), kMinJacobianRatio),
                       q.min_ratio <= 0
                           ? fmt::format("an inverted or degenerate element (min det J / mean "
                                         "det J = {:.3g}, volume {:.3g} m^3)",
                                         q.min_ratio, q.volume)
                           : fmt::format("a nearly degenerate element (min det J / mean det J = "
                                         "{:.3g})",
                                         q.min_ratio),
                       "check the node order (Gmsh convention) and the node coordinates");
    }
    // Isotropic stiffness in Lame form: K_ab = ∫ (lambda g_a g_b^T + mu g_b g_a^T
    // + mu (g_a . g_b) I) dV with g = grad N; equal to ∫ B^T D B dV but without the 6 x 3n B.
    const double lambda = E * nu / ((1 + nu) * (1 - 2 * nu));
    const double mu = E / (2 * (1 + nu));
    Eigen::Matrix<double, 3 * N, 3 * N> Ke;
    Ke.setZero();
    for (const Point& p : stiffness_) {
      const Eigen::Matrix3d J = X.transpose() * p.dN;
      const double det = J.determinant();
      const NodeMatrix G = p.dN * J.inverse();
      const double wd = p.weight * det;
      for (int a = 0; a < N; ++a) {
        const Eigen::RowVector3d ga = G.row(a) * wd;
        for (int b = a; b < N; ++b) {
          const Eigen::RowVector3d gb = G.row(b);
          Eigen::Matrix3d kab = lambda * ga.transpose() * gb + mu * gb.transpose() * ga;
          kab.diagonal().array() += mu * ga.dot(gb);
          Ke.template block<3, 3>(3 * a, 3 * b) += kab;
        }
      }
    }
    for (int a = 0; a < N; ++a) {
      for (int b = a + 1; b < N; ++b) {
        Ke.template block<3, 3>(3 * b, 3 * a) = Ke.template block<3, 3>(3 * a, 3 * b).transpose();
      }
    }
    K = Ke;
    if (m != nullptr) {
      Eigen::Matrix<double, N, N> me;
      me.setZero();
      for (const Point& p : mass_) {
        const double det = (X.transpose() * p.dN).determinant();
        me.noalias() += (p.weight * det) * p.N_ * p.N_.transpose();
      }
      *m = me;
    }
    return q.volume;
  }

  ElementQuality quality(const Eigen::Vector3d* x) const override {
    NodeMatrix X;
    for (int a = 0; a < N; ++a) X.row(a) = x[a].transpose();
    return quality_of(X);
  }

 private:
  void fill(const Rule& rule, std::vector<Point>& out) const {
    Eigen::VectorXd Nv;
    Eigen::MatrixXd dN;
    for (const QuadraturePoint& q : rule) {
      shape_functions(type_, q.xi, Nv, dN);
      out.push_back({q.weight, Nv, dN});
    }
  }

  ElementQuality quality_of(const NodeMatrix& X) const {
    ElementQuality q;
    q.min_det_j = std::numeric_limits<double>::infinity();
    q.max_det_j = -std::numeric_limits<double>::infinity();
    auto visit = [&](const std::vector<Point>& pts, bool integrate) {
      for (const Point& p : pts) {
        const double det = (X.transpose() * p.dN).determinant();
        q.min_det_j = std::min(q.min_det_j, det);
        q.max_det_j = std::max(q.max_det_j, det);
        if (integrate) q.volume += p.weight * det;
      }
    };
    visit(mass_, true);
    visit(stiffness_, false);
    visit(nodes_, false);
    const double mean = q.volume / reference_volume_;
    q.min_ratio = mean > 0 ? q.min_det_j / mean : (q.min_det_j > 0 ? 0.0 : -1.0);
    if (!std::isfinite(q.min_ratio)) q.min_ratio = -1.0;
    return q;
  }

  ElementType type_;
  std::vector<Point> stiffness_, mass_, nodes_;
  double reference_volume_ = 1;
};

}  // namespace

void ElementKernel::check_node_count(int n, long id, const SourceLocation& where) const {
  if (n != nodes()) {
    throw InputError(where, fmt::format("elements[id {}].nodes", id),
                     fmt::format("{} nodes for a {} element", nodes(), to_string(type())),
                     fmt::format("{} nodes", n));
  }
}

const ElementKernel& element_kernel(ElementType type) {
  // Built once (thread-safe static initialisation).
  static const Kernel<4> tet4(ElementType::Tet4, tet_rule(1), tet_rule(2));
  static const Kernel<10> tet10(ElementType::Tet10, tet_rule(2), tet_rule(5));
  static const Kernel<8> hex8(ElementType::Hex8, gauss_hex(2), gauss_hex(2));
  static const Kernel<20> hex20(ElementType::Hex20, gauss_hex(3), gauss_hex(3));
  static const Kernel<6> wedge6(ElementType::Wedge6, wedge_rule(2, 2), wedge_rule(2, 2));
  static const Kernel<15> wedge15(ElementType::Wedge15, wedge_rule(5, 3), wedge_rule(5, 3));
  switch (type) {
    case ElementType::Tet4:
      return tet4;
    case ElementType::Tet10:
      return tet10;
    case ElementType::Hex8:
      return hex8;
    case ElementType::Hex20:
      return hex20;
    case ElementType::Wedge6:
      return wedge6;
    case ElementType::Wedge15:
      return wedge15;
  }
  return tet4;
}

}  // namespace geardyn::solid
