#include "geardyn/assembly/system_pencil.hpp"

namespace geardyn::assembly {

eig::QuadraticPencil pencil_at(const fe::LinearSystem& system, double speed) {
  eig::QuadraticPencil p;
  const Eigen::Index n = system.size();
  p.M = system.M;
  p.K = system.K_at(speed);
  p.C = system.C_at(speed);
  if (speed != 0.0 && system.G.rows() == n && system.G.nonZeros() > 0) p.C += speed * system.G;
  if (p.C.rows() != n) p.C.resize(n, n);  // an empty damping matrix
  p.C.makeCompressed();
  if (system.has_modal_damping()) {
    p.low_rank_basis = system.modal_basis;
    p.low_rank_coefficients = system.modal_coefficients;
  }
  return p;
}

}  // namespace geardyn::assembly
