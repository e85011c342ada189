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

eig::SpeedPencilParts pencil_parts(const fe::LinearSystem& system) {
  eig::SpeedPencilParts parts;
  const Eigen::Index n = system.size();
  parts.M = system.M;
  parts.K0 = system.K;
  parts.C0 = system.C.rows() == n ? system.C : Eigen::SparseMatrix<double>(n, n);
  parts.G = system.G.rows() == n ? system.G : Eigen::SparseMatrix<double>(n, n);
  if (system.has_modal_damping()) {
    parts.low_rank_basis = system.modal_basis;
    parts.low_rank_coefficients = system.modal_coefficients;
  }
  parts.rigid_candidates = fe::rigid_body_candidates(system.dofs);
  return parts;
}

SpeedIncrements speed_increments(const fe::LinearSystem& system, double speed) {
  const Eigen::Index n = system.size();
  SpeedIncrements inc;
  inc.dK.resize(n, n);
  inc.dC.resize(n, n);
  if (system.speed_bearings.empty()) return inc;
  std::vector<Eigen::Triplet<double>> tk, tc;
  for (const auto& b : system.speed_bearings) {
    b.add_tangent(speed, 1.0, 0.0, tk);
    b.add_tangent(speed, 0.0, 1.0, tc);
  }
  inc.dK.setFromTriplets(tk.begin(), tk.end());
  inc.dC.setFromTriplets(tc.begin(), tc.end());
  return inc;
}

}  // namespace geardyn::assembly
