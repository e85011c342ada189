#pragma once
// Long time histories (virtual sensors of a transient run sampled at a fixed rate) as one HDF5
// file, `time_history.h5`; short records stay CSV tables. Layout (docs/output-reference.md,
// "time_history.h5"):
//
//   /                       attributes: format = "geardyn time history 1" (string),
//                           sample_rate_hz (double), and the writer's string attributes
//                           (analysis name, model file, ...), in the order given
//   /time                   n doubles [s]
//   /channels/<name>        n doubles each, one dataset per channel, in column order (the
//                           group tracks link creation order); string attribute "unit";
//                           chunked (up to 65536 samples) with the shuffle and deflate filters
//
// Channel names are the CSV column names of the same quantities: letters, digits, underscores.
#include <Eigen/Core>
#include <cstddef>
#include <filesystem>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace geardyn::io {

/// The value of the root attribute "format"; raised when the layout changes meaning.
inline constexpr std::string_view kTimeHistoryFormat = "geardyn time history 1";

/// Samples per chunk of a channel (512 KiB of doubles: read and compressed at once, inside
/// HDF5's default 1 MiB chunk cache).
inline constexpr std::size_t kTimeHistoryChunk = 65536;

struct TimeHistoryChannel {
  std::string name;  ///< letters, digits and underscores, e.g. "housing_acc_z_m_per_s2"
  std::string unit;  ///< e.g. "m/s^2"; may be empty (dimensionless)
};

/// True for a usable channel name: not empty, only ASCII letters, digits and underscores.
bool is_time_history_channel_name(std::string_view name);

/// Writes the first `samples` entries of `time` [s] and the first `samples` rows of `values`
/// (row = sample, column = channel, in the order of `channels`) to `path`, replacing it in one
/// step (the file is written as `path.partial` and renamed). `attributes` become string
/// attributes of the root group (names not empty, distinct, not "format" or "sample_rate_hz").
/// Throws std::invalid_argument (nothing written) for a bad channel name (see
/// is_time_history_channel_name), a repeated channel or attribute name, a sample rate that is not
/// finite and positive, fewer than `samples` times or rows, or a column count different from
/// the channel count; std::runtime_error naming the path and what failed when writing fails.
/// HDF5 prints nothing on stderr.
void write_time_history_h5(const std::filesystem::path& path, double sample_rate_hz,
                           const std::vector<double>& time,
                           const std::vector<TimeHistoryChannel>& channels,
                           const Eigen::MatrixXd& values, std::size_t samples,
                           const std::vector<std::pair<std::string, std::string>>& attributes);

struct TimeHistory {
  double sample_rate_hz = 0.0;
  std::vector<double> time;                  ///< [s], n samples
  std::vector<TimeHistoryChannel> channels;  ///< in column order
  Eigen::MatrixXd values;                    ///< n x channels.size(), row = sample
  std::vector<std::pair<std::string, std::string>> attributes;  ///< the writer's, in order
};

/// Reads a file written by write_time_history_h5. Throws std::runtime_error naming the path and
/// the dataset or attribute at fault for a missing file, a file that is not HDF5 or not a
/// geardyn time history of this format, a missing or unreadable dataset or attribute, or a
/// channel whose length differs from /time. HDF5 prints nothing on stderr.
TimeHistory read_time_history_h5(const std::filesystem::path& path);

}  // namespace geardyn::io
