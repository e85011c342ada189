#pragma once
// Internal to the solid-component analyses (solid_modal, cyclic_modal, reduction): the pieces
// more than one of their drivers uses. Not part of the analyses' interface.
#include <Eigen/Sparse>
#include <memory>
#include <string>
#include <vector>

#include "geardyn/assembly/solid_component.hpp"
#include "geardyn/core/table.hpp"
#include "geardyn/eig/symmetric_eigen.hpp"
#include "geardyn/meshio/vtu_writer.hpp"

namespace geardyn::analyses {

/// Frequency [Hz] of an eigenvalue lambda = omega^2 (negative round-off counts as 0).
double hz(double lambda);

/// Translations (ux, uy, uz per node) of the mesh from a solution on the assembled DOFs.
std::vector<double> node_translations(const solid::SolidSystem& system, int num_nodes,
                                      const Eigen::VectorXd& u);

/// Scales a nodal field to a largest displacement magnitude of 1.
void normalise(std::vector<double>& values);

/// The mode-shape files: a VTU series (ParaView) and one Gmsh file with a view per mode.
void add_shape_files(AnalysisOutput& out, std::shared_ptr<const solid::Mesh> mesh,
                     std::vector<meshio::Field> fields, std::vector<double> frequencies,
                     const std::string& stem, const std::string& what);

/// The lowest n_modes modes (or all up to f_max [rad/s]) of (K, M); NumericalError on failure.
eig::SymmetricEigenResult solve_modes(const Eigen::SparseMatrix<double>& K,
                                      const Eigen::SparseMatrix<double>& M, int n_modes,
                                      double f_max, const std::string& name);

/// The DOFs of the nodes of `sets` that have any (nodes fully fixed or eliminated by a rigid
/// element have none and are skipped: they cannot be masters).
std::vector<int> master_dofs(const assembly::SolidComponent& c,
                             const std::vector<std::string>& sets);

/// The note on how far to trust the frequencies, from the largest eigenpair backward error.
std::string trust_from_residual(double residual);

}  // namespace geardyn::analyses
