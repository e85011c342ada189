#pragma once
// Internal: the per-type element kernels behind elements.hpp and assembly.cpp. Fixed-size Eigen
// types per node count; quadrature tables and shape-function derivatives precomputed once.
#include <Eigen/Dense>

#include "geardyn/core/error.hpp"
#include "geardyn/solid/elements.hpp"
#include "geardyn/solid/mesh.hpp"

namespace geardyn::solid {

class ElementKernel {
 public:
  virtual ~ElementKernel() = default;
  virtual ElementType type() const = 0;
  virtual int nodes() const = 0;
  /// Throws InputError (key "elements[id <id>].nodes") if n != nodes().
  void check_node_count(int n, long id, const SourceLocation& where) const;
  /// K (3n x 3n, node-major) of the element with node coordinates x[0..n) for modulus E and
  /// Poisson ratio nu, and, if m != nullptr, the shape mass m_ab = ∫ N_a N_b dV (n x n).
  /// Returns the volume. Throws InputError for a degenerate / inverted element.
  virtual double compute(const Eigen::Vector3d* x, double E, double nu, long id,
                         const SourceLocation& where, Eigen::MatrixXd& K,
                         Eigen::MatrixXd* m) const = 0;
  virtual ElementQuality quality(const Eigen::Vector3d* x) const = 0;
};

const ElementKernel& element_kernel(ElementType type);

}  // namespace geardyn::solid
