#include "geardyn/reduce/interface_reduction.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <string>

#include "geardyn/core/error.hpp"

namespace geardyn::reduce {

namespace {

constexpr const char* kKey = "reduce.interface_mode_reduction";
constexpr Eigen::Index kDenseMax = 5000;

template <class Matrix>
Matrix pick(const Matrix& A, const std::vector<int>& rows, const std::vector<int>& cols) {
  Matrix out(static_cast<Eigen::Index>(rows.size()), static_cast<Eigen::Index>(cols.size()));
  for (std::size_t c = 0; c < cols.size(); ++c)
    for (std::size_t r = 0; r < rows.size(); ++r)
      out(static_cast<Eigen::Index>(r), static_cast<Eigen::Index>(c)) = A(rows[r], cols[c]);
  return out;
}

template <class Matrix>
Matrix hermitian_part(const Matrix& A) {
  const Matrix Ah = A.adjoint();
  return Matrix((A + Ah) * 0.5);
}

}  // namespace

template <class Scalar>
InterfaceReduction<Scalar> interface_mode_reduction(
    const Eigen::Matrix<Scalar, Eigen::Dynamic, Eigen::Dynamic>& K,
    const Eigen::Matrix<Scalar, Eigen::Dynamic, Eigen::Dynamic>& M,
    const std::vector<int>& interface_dofs, int n_interface_modes) {
  using Matrix = Eigen::Matrix<Scalar, Eigen::Dynamic, Eigen::Dynamic>;
  const Eigen::Index n = K.rows();
  if (K.cols() != n || M.rows() != n || M.cols() != n)
    throw InputError({}, kKey, "square K and M of the same size",
                     fmt::format("K {}x{}, M {}x{}", K.rows(), K.cols(), M.rows(), M.cols()));
  if (n > kDenseMax)
    throw InputError({}, kKey, fmt::format("at most {} coordinates (dense work)", kDenseMax),
                     std::to_string(n), "reduce the component first (Craig-Bampton)");
  std::vector<bool> on_interface(static_cast<std::size_t>(n), false);
  for (std::size_t k = 0; k < interface_dofs.size(); ++k) {
    const int d = interface_dofs[k];
    if (d < 0 || d >= n)
      throw InputError({}, fmt::format("{}.interface_dofs[{}]", kKey, k),
                       fmt::format("an index in 0 .. {}", n - 1), std::to_string(d));
    if (on_interface[static_cast<std::size_t>(d)])
      throw InputError({}, fmt::format("{}.interface_dofs[{}]", kKey, k), "each index once",
                       fmt::format("{} repeated", d));
    on_interface[static_cast<std::size_t>(d)] = true;
  }
  const auto ni = static_cast<int>(interface_dofs.size());
  if (n_interface_modes < 6)
    throw InputError({}, std::string(kKey) + ".n_interface_modes", "at least 6",
                     std::to_string(n_interface_modes),
                     "with fewer than six interface modes the rigid-body motions of the "
                     "component are lost (Tran 2001); about a third of the Craig-Bampton mode "
                     "count is a usual choice");
  if (n_interface_modes > ni)
    throw InputError({}, std::string(kKey) + ".n_interface_modes",
                     fmt::format("at most {} (the number of interface DOFs)", ni),
                     std::to_string(n_interface_modes));

  InterfaceReduction<Scalar> out;
  out.interface_dofs = interface_dofs;
  for (Eigen::Index j = 0; j < n; ++j)
    if (!on_interface[static_cast<std::size_t>(j)]) out.other_dofs.push_back(static_cast<int>(j));
  const auto no = static_cast<Eigen::Index>(out.other_dofs.size());
  const Matrix Kh = hermitian_part(K), Mh = hermitian_part(M);
  const auto& I = out.interface_dofs;
  const auto& O = out.other_dofs;

  // Guyan reduction onto the interface: x_O = -K_OO^{-1} K_OI x_I.
  Matrix G(ni, ni);
  G.setIdentity();
  Matrix static_shapes(no, ni);
  if (no > 0) {
    const Matrix Koo = pick(Kh, O, O);
    const Eigen::LLT<Matrix> llt(Koo);
    const double rcond = llt.info() == Eigen::Success ? llt.rcond() : 0.0;
    if (!(rcond > 1e-13))
      throw InputError(
          {}, std::string(kKey) + ".interface_dofs",
          "interface DOFs that hold every motion of the other coordinates (K_OO positive "
          "definite)",
          fmt::format("K_OO of the {} other coordinates is singular or indefinite (reciprocal "
                      "condition estimate {:.3e})",
                      no, rcond),
          "the coordinates outside the interface have a free motion: add the DOFs that hold it "
          "to the interface");
    static_shapes = -llt.solve(pick(Kh, O, I));
  }
  // K_g = K_II + K_IO S + S^H K_OI + S^H K_OO S, M_g likewise, with S the static shapes.
  auto condense = [&](const Matrix& A) {
    Matrix g = pick(A, I, I);
    if (no > 0) {
      const Matrix AoI = pick(A, O, I);
      const Matrix AoS = pick(A, O, O) * static_shapes + AoI;  // (A G) rows O
      g += AoI.adjoint() * static_shapes + static_shapes.adjoint() * AoS;
    }
    return hermitian_part(g);
  };
  const Matrix Kg = condense(Kh), Mg = condense(Mh);
  const Eigen::LLT<Matrix> mass_llt(Mg);
  if (mass_llt.info() != Eigen::Success)
    throw NumericalError("interface_mode_reduction",
                         "the Guyan-reduced interface mass matrix is not positive definite "
                         "(interface DOFs without mass?); check the interface selection");
  const Eigen::GeneralizedSelfAdjointEigenSolver<Matrix> ges(Kg, Mg);
  if (ges.info() != Eigen::Success)
    throw NumericalError("interface_mode_reduction",
                         "the dense Hermitian eigen-solver did not converge on the Guyan-reduced "
                         "interface problem");
  out.interface_eigenvalues = ges.eigenvalues();
  out.n_interface_modes = n_interface_modes;
  // Eigen returns B-normalised vectors (Phi^H M_g Phi = I) with eigenvalues ascending.
  const Matrix Phi = ges.eigenvectors().leftCols(n_interface_modes);

  const Eigen::Index m = n_interface_modes + no;
  out.transformation = Matrix::Zero(n, m);
  for (int r = 0; r < ni; ++r)
    out.transformation.row(I[static_cast<std::size_t>(r)]).head(n_interface_modes) = Phi.row(r);
  for (Eigen::Index k = 0; k < no; ++k)
    out.transformation(O[static_cast<std::size_t>(k)], n_interface_modes + k) = Scalar(1);
  const Matrix& T = out.transformation;
  out.K = hermitian_part(Matrix(T.adjoint() * (Kh * T)));
  out.M = hermitian_part(Matrix(T.adjoint() * (Mh * T)));
  return out;
}

template InterfaceReduction<double> interface_mode_reduction<double>(const Eigen::MatrixXd&,
                                                                     const Eigen::MatrixXd&,
                                                                     const std::vector<int>&, int);
template InterfaceReduction<std::complex<double>> interface_mode_reduction<std::complex<double>>(
    const Eigen::MatrixXcd&, const Eigen::MatrixXcd&, const std::vector<int>&, int);

}  // namespace geardyn::reduce
