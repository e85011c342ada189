#pragma once
// Matrix Market matrices (NIST format, https://math.nist.gov/MatrixMarket/formats.html) and the
// DOF map of a component described by external stiffness and mass matrices (e.g. reduced by
// another FE code).
//
// Read: "%%MatrixMarket matrix coordinate|array real|integer general|symmetric". Symmetric files
// list the lower triangle (i >= j, column by column for array); the matrix returned holds both
// triangles. Anything else (pattern, complex, hermitian, skew-symmetric, entries above the
// diagonal of a symmetric file, duplicate entries, indices out of range, NaN or infinite values,
// too few or too many entries, a non-square size) is an InputError with file:line:column.
//
// DOF map: a CSV file with a header naming the columns node_id, component, x, y, z (any order,
// case-insensitive), then one row per matrix row/column in the same order:
//   node_id    integer id of the node the DOF belongs to (mode number for component q)
//   component  1..6 or ux, uy, uz, rx, ry, rz (global axes); q = a generalised (modal) coordinate
//   x, y, z    the node's position [m]
// Blank lines and lines starting with '#' are skipped. A (node_id, component) pair may appear
// once; all rows of one node must give the same position.
#include <Eigen/Sparse>
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include "geardyn/solid/mesh.hpp"

namespace geardyn::meshio {

/// One Matrix Market file: the matrix (both triangles stored) and what the header said.
struct MatrixMarketMatrix {
  Eigen::SparseMatrix<double> matrix;
  bool symmetric = false;    ///< header said symmetric
  SourceLocation size_line;  ///< where the size line is (for size-mismatch messages)
  /// Where each diagonal entry A_ii was given (line 0: not in the file, i.e. zero).
  std::vector<SourceLocation> diagonal;
};

MatrixMarketMatrix read_matrix_market(const std::filesystem::path& path);
MatrixMarketMatrix parse_matrix_market(std::string_view text, const std::string& file_name);

std::vector<solid::DofInfo> read_dof_map_csv(const std::filesystem::path& path);
std::vector<solid::DofInfo> parse_dof_map_csv(std::string_view text, const std::string& file_name);

/// A component given by external matrices: K and M (square, symmetric, both triangles stored,
/// size n) and the n DOFs they act on.
struct ExternalMatrices {
  Eigen::SparseMatrix<double> K;
  Eigen::SparseMatrix<double> M;
  std::vector<solid::DofInfo> dofs;
};

/// Reads K, M and the DOF map and checks that they fit: K and M square with as many rows as
/// the DOF map has rows, and symmetric (|A_ij - A_ji| <= 1e-10 max|A|; a "general" file must
/// still describe a symmetric matrix), every M_ii > 0 and every K_ii >= 0 (located at the
/// entry's line, naming the DOF). Throws InputError otherwise. Definiteness beyond the diagonal
/// (a Cholesky factorisation) is checked by the caller (assembly::check_imported_matrices).
ExternalMatrices read_matrix_market_component(const std::filesystem::path& path_K,
                                              const std::filesystem::path& path_M,
                                              const std::filesystem::path& path_dofmap);

/// Writes `A` as "coordinate real general", or with `symmetric` as "coordinate real symmetric"
/// (lower triangle only; throws std::invalid_argument if A is not symmetric to 1e-12 max|A|).
/// Values are written in the shortest form that reads back to the same double. Throws
/// std::runtime_error if the file cannot be written.
void write_matrix_market(const std::filesystem::path& path, const Eigen::SparseMatrix<double>& A,
                         bool symmetric);

/// Writes a DOF map in the CSV form read_dof_map_csv reads (header node_id,component,x,y,z;
/// components 1..6, q for component < 0; coordinates in shortest round-trip form). Throws
/// std::runtime_error if the file cannot be written.
void write_dof_map_csv(const std::filesystem::path& path, const std::vector<solid::DofInfo>& dofs);

}  // namespace geardyn::meshio
