#pragma once
// Reduced-component file (HDF5): the reduced matrices, the masters, the recovery data and the
// provenance. Layout and conventions: docs/reduced-component-format.md (format_version 1).
#include <string>

#include "geardyn/reduce/reduced_component.hpp"

namespace geardyn::reduce {

/// The file layout version written by save_reduced and accepted by load_reduced.
inline constexpr int kReducedFormatVersion = 1;

/// Writes `rc` to `path` (HDF5). The file is written under `<path>.partial` and renamed into
/// place when complete, so a failed save never leaves a truncated file under `path`. Recovery
/// datasets are chunked and deflate-compressed. Throws InputError when rc is inconsistent
/// (sizes that do not match), std::runtime_error when the file cannot be written.
void save_reduced(const std::string& path, const ReducedComponent& rc);

/// Reads a file written by save_reduced. Values round-trip bit for bit. Throws InputError
/// (SourceLocation = the file, key path = the dataset or attribute) for a missing file, a file
/// that is not HDF5, a wrong format_version, and a missing, mistyped or mis-shaped dataset.
ReducedComponent load_reduced(const std::string& path);

}  // namespace geardyn::reduce
