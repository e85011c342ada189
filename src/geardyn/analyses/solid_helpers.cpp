#include "geardyn/analyses/solid_helpers.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "geardyn/core/error.hpp"
#include "geardyn/core/units.hpp"
#include "geardyn/meshio/gmsh_view_writer.hpp"

namespace geardyn::analyses {

double hz(double lambda) { return std::sqrt(std::max(lambda, 0.0)) / units::kTwoPi; }

std::vector<double> node_translations(const solid::SolidSystem& system, int num_nodes,
                                      const Eigen::VectorXd& u) {
  const Eigen::VectorXd all = system.recovery * u;
  std::vector<double> out(static_cast<std::size_t>(num_nodes) * 3, 0.0);
  for (int n = 0; n < num_nodes; ++n) {
    if (system.node_dofs[static_cast<std::size_t>(n)] < 3) continue;
    const int offset = system.node_offset[static_cast<std::size_t>(n)];
    for (int c = 0; c < 3; ++c) out[static_cast<std::size_t>(n) * 3 + c] = all[offset + c];
  }
  return out;
}

void normalise(std::vector<double>& values) {
  double peak = 0.0;
  for (std::size_t i = 0; i + 2 < values.size(); i += 3)
    peak = std::max(peak, std::hypot(values[i], values[i + 1], values[i + 2]));
  if (peak > 0.0)
    for (double& v : values) v /= peak;
}

void add_shape_files(AnalysisOutput& out, std::shared_ptr<const solid::Mesh> mesh,
                     std::vector<meshio::Field> fields, std::vector<double> frequencies,
                     const std::string& stem, const std::string& what) {
  if (fields.empty()) return;
  auto shared_fields = std::make_shared<const std::vector<meshio::Field>>(std::move(fields));
  auto times = std::make_shared<const std::vector<double>>(std::move(frequencies));
  out.files.push_back(
      {stem + ".pvd",
       fmt::format("{} for ParaView: a .pvd collection of {}_<k>.vtu files (binary, compressed), "
                   "array 'mode_shape', time = frequency [Hz]",
                   what, stem),
       [mesh, shared_fields, times](const std::filesystem::path& path) {
         // One array name in every step ("mode_shape"), so that ParaView filters set on it
         // (Warp By Vector) keep working while stepping through the modes; the step's time is
         // the frequency. The Gmsh views below keep one name per mode.
         std::vector<std::vector<meshio::Field>> states;
         for (const auto& f : *shared_fields) {
           states.push_back({f});
           states.back().front().name = "mode_shape";
         }
         meshio::write_vtu_series(path, *mesh, states, *times);
       }});
  out.files.push_back({stem + ".msh", fmt::format("{} as Gmsh post-processing views", what),
                       [mesh, shared_fields](const std::filesystem::path& path) {
                         meshio::write_gmsh_views(path, *mesh, *shared_fields);
                       }});
}

eig::SymmetricEigenResult solve_modes(const Eigen::SparseMatrix<double>& K,
                                      const Eigen::SparseMatrix<double>& M, int n_modes,
                                      double f_max, const std::string& name) {
  eig::SymmetricEigenOptions o;
  o.n_modes = std::min<int>(n_modes, static_cast<int>(K.rows()));
  if (!std::isnan(f_max)) {
    o.band_max = f_max * f_max;
    o.band_min = -1e-3 * o.band_max;
  }
  eig::SymmetricEigenResult r = eig::solve_symmetric(K, M, o);
  if (r.status != Status::Ok)
    throw NumericalError(name, fmt::format("eigen-solve: {} ({})", r.message, r.brief_report()));
  // A negative eigenvalue beyond round-off means K is indefinite (a negative stiffness from an
  // imported matrix, a spring or a material): say so instead of reporting it as 0 Hz. Round-off
  // of the eigenvalues is about eps max_i(K_ii / M_ii) (rigid-body modes land there, of either
  // sign); 1e-8 of that scale leaves eight orders of margin.
  const Eigen::VectorXd k_diag = K.diagonal(), m_diag = M.diagonal();
  double scale = 0.0;
  for (Eigen::Index i = 0; i < k_diag.size(); ++i)
    if (m_diag(i) > 0.0) scale = std::max(scale, k_diag(i) / m_diag(i));
  for (Eigen::Index j = 0; j < r.eigenvalues.size(); ++j)
    if (r.eigenvalues[j] < -1e-8 * scale)
      throw NumericalError(
          name, fmt::format("the stiffness matrix is not positive semi-definite: mode {} has "
                            "omega^2 = {:.6g} (rad/s)^2 < 0 (below the round-off level {:.3g}); "
                            "check for a negative stiffness in imported matrices, springs or "
                            "materials",
                            j + 1, r.eigenvalues[j], -1e-8 * scale));
  return r;
}

std::vector<int> master_dofs(const assembly::SolidComponent& c,
                             const std::vector<std::string>& sets) {
  std::vector<int> out;
  for (const auto& set : sets)
    for (int node : c.mesh.node_sets.at(set))
      for (int comp = 0; comp < 6; ++comp)
        if (const int d = c.system.node_dof(node, comp); d >= 0) out.push_back(d);
  std::sort(out.begin(), out.end());
  out.erase(std::unique(out.begin(), out.end()), out.end());
  return out;
}

std::string trust_from_residual(double residual) {
  return fmt::format(
      "Largest backward error of the eigenpairs {:.1e}: the frequencies are exact for the "
      "discrete model to about that relative accuracy; the discretisation error of the mesh is "
      "not included (check it by refining the mesh).",
      residual);
}

}  // namespace geardyn::analyses
