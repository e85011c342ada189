#include "geardyn/eig/rigid_body.hpp"

#include <algorithm>
#include <cmath>
#include <complex>
#include <vector>

namespace geardyn::eig {

RigidBodySpace rigid_body_space(const Eigen::SparseMatrix<double>& K,
                                const Eigen::SparseMatrix<double>& M,
                                const Eigen::MatrixXd& candidates, double tolerance) {
  RigidBodySpace space;
  const Eigen::Index n = K.cols();
  space.basis.resize(n, 0);
  if (candidates.cols() == 0 || n == 0) return space;
  // Orthonormal basis of the candidates, dependent ones dropped.
  const Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr(candidates);
  const Eigen::MatrixXd R = qr.matrixR().template triangularView<Eigen::Upper>();
  const double largest = R.rows() > 0 ? std::abs(R(0, 0)) : 0.0;
  Eigen::Index rank = 0;
  while (rank < std::min(R.rows(), R.cols()) && std::abs(R(rank, rank)) > 1e-8 * largest) ++rank;
  if (rank == 0) return space;
  const Eigen::MatrixXd Q = qr.householderQ() * Eigen::MatrixXd::Identity(n, rank);

  // Residual of each row relative to the size of its terms, |K| |Q| (per row, the norm over
  // the candidates): rounding gives eps-sized entries whatever the element size.
  const Eigen::VectorXd q_norm = Q.rowwise().norm();
  Eigen::VectorXd scale = Eigen::VectorXd::Zero(K.rows());
  for (Eigen::Index j = 0; j < K.outerSize(); ++j)
    for (Eigen::SparseMatrix<double>::InnerIterator it(K, j); it; ++it)
      scale[it.row()] += std::abs(it.value()) * q_norm[j];
  Eigen::MatrixXd W = K * Q;
  for (Eigen::Index i = 0; i < W.rows(); ++i) W.row(i) *= scale[i] > 0.0 ? 1.0 / scale[i] : 0.0;
  const Eigen::JacobiSVD<Eigen::MatrixXd, Eigen::ColPivHouseholderQRPreconditioner> svd(
      W, Eigen::ComputeFullV);
  const Eigen::VectorXd& sigma = svd.singularValues();
  std::vector<Eigen::Index> null_columns;
  for (Eigen::Index k = 0; k < sigma.size(); ++k)
    if (sigma[k] <= tolerance) null_columns.push_back(k);
  if (null_columns.empty()) return space;
  Eigen::MatrixXd V(rank, static_cast<Eigen::Index>(null_columns.size()));
  for (std::size_t k = 0; k < null_columns.size(); ++k)
    V.col(static_cast<Eigen::Index>(k)) = svd.matrixV().col(null_columns[k]);
  const Eigen::MatrixXd B = Q * V;
  // M-orthonormalise: B L^{-T} with B^T M B = L L^T. A null motion without mass (massless DOFs
  // only) cannot hold kinetic energy: it is left out.
  const Eigen::MatrixXd G = B.transpose() * (M * B);
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eg(G);
  const double g_max = eg.eigenvalues().size() > 0 ? eg.eigenvalues().maxCoeff() : 0.0;
  std::vector<Eigen::Index> kept;
  for (Eigen::Index k = 0; k < eg.eigenvalues().size(); ++k)
    if (eg.eigenvalues()[k] > 1e-12 * g_max && eg.eigenvalues()[k] > 0.0) kept.push_back(k);
  space.basis.resize(n, static_cast<Eigen::Index>(kept.size()));
  for (std::size_t k = 0; k < kept.size(); ++k)
    space.basis.col(static_cast<Eigen::Index>(k)) =
        B * eg.eigenvectors().col(kept[k]) / std::sqrt(eg.eigenvalues()[kept[k]]);
  return space;
}

double rigid_body_fraction(const RigidBodySpace& space, const Eigen::SparseMatrix<double>& M,
                           const Eigen::VectorXcd& x) {
  if (space.dimension() == 0 || x.size() != space.basis.rows()) return 0.0;
  const Eigen::VectorXcd Mx = M * x;
  const double energy = std::abs(x.dot(Mx));
  if (!(energy > 0.0)) return 0.0;
  const Eigen::VectorXd p_re = space.basis.transpose() * Mx.real();
  const Eigen::VectorXd p_im = space.basis.transpose() * Mx.imag();
  return std::min(1.0, (p_re.squaredNorm() + p_im.squaredNorm()) / energy);
}

}  // namespace geardyn::eig
