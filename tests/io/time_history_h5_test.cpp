#include "geardyn/io/time_history_h5.hpp"

#include <gtest/gtest.h>
#include <hdf5.h>
#include <unistd.h>

#include <bit>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <limits>
#include <numbers>
#include <random>
#include <stdexcept>
#include <string>

#include "geardyn/io/hdf5_handle.hpp"

namespace geardyn::io {
namespace {

namespace fs = std::filesystem;
using Attributes = std::vector<std::pair<std::string, std::string>>;

class TimeHistoryH5 : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           ("geardyn_th5_" + std::to_string(getpid()) + "_" +
            std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()));
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  fs::path dir_;
};

// Bit patterns, so that NaN, -0.0 and subnormals are compared exactly.
void expect_bit_identical(const double* a, const double* b, std::size_t n,
                          const std::string& what) {
  std::size_t differing = 0;
  for (std::size_t k = 0; k < n; ++k)
    if (std::bit_cast<std::uint64_t>(a[k]) != std::bit_cast<std::uint64_t>(b[k])) ++differing;
  EXPECT_EQ(differing, 0u) << what;
}

// Expects `call` to throw E whose message contains every one of `parts`.
template <class E, class F>
void expect_throw_naming(F call, const std::vector<std::string>& parts) {
  try {
    call();
    ADD_FAILURE() << "no exception";
  } catch (const E& e) {
    const std::string message = e.what();
    for (const auto& part : parts)
      EXPECT_NE(message.find(part), std::string::npos) << message << " lacks " << part;
  }
}

TEST_F(TimeHistoryH5, RoundTripIsBitIdenticalWithUnitsAttributesAndRate) {
  const std::size_t n = 1000;
  const double fs_hz = 20000.0;
  std::vector<double> time(n + 7);  // longer than `samples`: only the first n are written
  for (std::size_t k = 0; k < time.size(); ++k) time[k] = 0.125 + static_cast<double>(k) / fs_hz;
  const std::vector<TimeHistoryChannel> channels = {
      {"housing_acc_z_m_per_s2", "m/s^2"}, {"dte_rad", "rad"}, {"flag", ""}};
  Eigen::MatrixXd values(n + 10, 3);  // extra rows are not written
  std::mt19937_64 rng(16);
  std::normal_distribution<double> normal(0.0, 1e3);
  for (Eigen::Index i = 0; i < values.rows(); ++i)
    for (Eigen::Index j = 0; j < values.cols(); ++j) values(i, j) = normal(rng);
  values(0, 0) = std::numeric_limits<double>::quiet_NaN();
  values(1, 0) = -0.0;
  values(2, 1) = std::numeric_limits<double>::infinity();
  values(3, 1) = std::numeric_limits<double>::denorm_min();
  values(4, 2) = -std::numeric_limits<double>::max();
  const Attributes attributes = {
      {"analysis", "runup"}, {"model_file", "ptu, run-up.toml"}, {"comment", ""}};
  const fs::path file = dir_ / "time_history.h5";

  testing::internal::CaptureStderr();
  write_time_history_h5(file, fs_hz, time, channels, values, n, attributes);
  const TimeHistory th = read_time_history_h5(file);
  EXPECT_EQ(testing::internal::GetCapturedStderr(), "");

  EXPECT_FALSE(fs::exists(dir_ / "time_history.h5.partial"));
  EXPECT_EQ(std::bit_cast<std::uint64_t>(th.sample_rate_hz), std::bit_cast<std::uint64_t>(fs_hz));
  ASSERT_EQ(th.time.size(), n);
  expect_bit_identical(th.time.data(), time.data(), n, "time");
  ASSERT_EQ(th.channels.size(), 3u);
  for (std::size_t c = 0; c < 3; ++c) {
    EXPECT_EQ(th.channels[c].name, channels[c].name);  // column order kept, not name order
    EXPECT_EQ(th.channels[c].unit, channels[c].unit);
  }
  ASSERT_EQ(th.values.rows(), static_cast<Eigen::Index>(n));
  ASSERT_EQ(th.values.cols(), 3);
  for (Eigen::Index c = 0; c < 3; ++c)
    expect_bit_identical(th.values.col(c).data(), values.col(c).data(), n,
                         "channel " + channels[static_cast<std::size_t>(c)].name);
  EXPECT_EQ(th.attributes, attributes);  // in the order given
}

TEST_F(TimeHistoryH5, ZeroSamplesKeepChannelsUnitsAndAttributes) {
  const fs::path file = dir_ / "empty.h5";
  const std::vector<TimeHistoryChannel> channels = {{"speed_rpm", "rpm"}, {"torque_nm", "N m"}};
  write_time_history_h5(file, 1000.0, {}, channels, Eigen::MatrixXd(0, 2), 0,
                        {{"analysis", "stopped"}});
  const TimeHistory th = read_time_history_h5(file);
  EXPECT_EQ(th.sample_rate_hz, 1000.0);
  EXPECT_TRUE(th.time.empty());
  EXPECT_EQ(th.values.rows(), 0);
  EXPECT_EQ(th.values.cols(), 2);
  ASSERT_EQ(th.channels.size(), 2u);
  EXPECT_EQ(th.channels[0].name, "speed_rpm");
  EXPECT_EQ(th.channels[1].unit, "N m");
  EXPECT_EQ(th.attributes, (Attributes{{"analysis", "stopped"}}));
}

// One channel of 10^6 samples (50 s at 20 kHz): written in chunks of kTimeHistoryChunk samples
// through the shuffle and deflate filters, read back bit-identical, and a smooth signal takes
// less room than its raw doubles.
TEST_F(TimeHistoryH5, LongChannelIsChunkedAndCompressed) {
  const std::size_t n = 1000000;
  const double fs_hz = 20000.0;
  std::vector<double> time(n);
  Eigen::MatrixXd values(static_cast<Eigen::Index>(n), 1);
  for (std::size_t k = 0; k < n; ++k) {
    time[k] = static_cast<double>(k) / fs_hz;
    // A run-up's slowly swept tone: smooth, but with full-precision mantissas.
    values(static_cast<Eigen::Index>(k), 0) =
        0.01 * std::sin(2.0 * std::numbers::pi * (5.0 + 2.0 * time[k]) * time[k]);
  }
  const fs::path file = dir_ / "long.h5";
  write_time_history_h5(file, fs_hz, time, {{"bearing_acc_y_m_per_s2", "m/s^2"}}, values, n, {});

  const TimeHistory th = read_time_history_h5(file);
  ASSERT_EQ(th.values.rows(), static_cast<Eigen::Index>(n));
  expect_bit_identical(th.values.data(), values.data(), n, "channel");
  expect_bit_identical(th.time.data(), time.data(), n, "time");

  {
    const QuietHdf5 quiet;
    const Hdf5Handle f(H5Fopen(file.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT), H5Fclose);
    ASSERT_TRUE(f.ok());
    const Hdf5Handle set(H5Dopen2(f.get(), "/channels/bearing_acc_y_m_per_s2", H5P_DEFAULT),
                         H5Dclose);
    ASSERT_TRUE(set.ok());
    const Hdf5Handle plist(H5Dget_create_plist(set.get()), H5Pclose);
    ASSERT_EQ(H5Pget_layout(plist.get()), H5D_CHUNKED);
    hsize_t chunk = 0;
    ASSERT_EQ(H5Pget_chunk(plist.get(), 1, &chunk), 1);
    EXPECT_EQ(chunk, kTimeHistoryChunk);
    ASSERT_EQ(H5Pget_nfilters(plist.get()), 2);
    unsigned flags = 0;
    std::size_t nelmts = 0;
    EXPECT_EQ(H5Pget_filter2(plist.get(), 0, &flags, &nelmts, nullptr, 0, nullptr, nullptr),
              H5Z_FILTER_SHUFFLE);
    nelmts = 0;
    EXPECT_EQ(H5Pget_filter2(plist.get(), 1, &flags, &nelmts, nullptr, 0, nullptr, nullptr),
              H5Z_FILTER_DEFLATE);
    // The stored (compressed) channel is smaller than its 8 * 10^6 raw bytes.
    const hsize_t stored = H5Dget_storage_size(set.get());
    EXPECT_GT(stored, 0u);
    std::cout << "channel: " << stored << " bytes stored for " << 8 * n << " raw\n";
    EXPECT_LT(stored, 8 * n);
  }
  // The whole file (time + channel + metadata) is smaller than the raw doubles it holds.
  const auto raw_bytes = static_cast<std::uintmax_t>(2 * 8 * n);
  EXPECT_LT(fs::file_size(file), raw_bytes);
}

TEST_F(TimeHistoryH5, ChannelNamesMustBeColumnNames) {
  const fs::path file = dir_ / "bad.h5";
  const Eigen::MatrixXd values = Eigen::MatrixXd::Zero(4, 1);
  const std::vector<double> time(4, 0.0);
  for (const std::string name : {"a-b", "", "speed rpm", "x/y", "acc.z", "\xc3\xa4"}) {
    expect_throw_naming<std::invalid_argument>(
        [&] {
          write_time_history_h5(file, 10.0, time, {{name, ""}}, values, 4, {});
        },
        {"'" + name + "'", "letters, digits, underscores"});
  }
  EXPECT_TRUE(is_time_history_channel_name("Shaft_2_speed_rpm"));
  EXPECT_FALSE(fs::exists(file));
  EXPECT_FALSE(fs::exists(dir_ / "bad.h5.partial"));
}

TEST_F(TimeHistoryH5, InconsistentArgumentsAreRefused) {
  const fs::path file = dir_ / "bad.h5";
  const Eigen::MatrixXd two = Eigen::MatrixXd::Zero(4, 2);
  const std::vector<double> time(4, 0.0);
  const std::vector<TimeHistoryChannel> ab = {{"a", ""}, {"b", ""}};
  auto refused = [&](double rate, const std::vector<TimeHistoryChannel>& ch,
                     const Eigen::MatrixXd& v, std::size_t samples, const Attributes& at,
                     const std::string& part) {
    expect_throw_naming<std::invalid_argument>(
        [&] { write_time_history_h5(file, rate, time, ch, v, samples, at); }, {part});
  };
  refused(0.0, ab, two, 4, {}, "sample_rate_hz");
  refused(std::nan(""), ab, two, 4, {}, "sample_rate_hz");
  refused(10.0, {{"a", ""}, {"a", ""}}, two, 4, {}, "'a' repeats");
  refused(10.0, {{"a", ""}}, two, 4, {}, "columns");
  refused(10.0, ab, two, 5, {}, "times");
  refused(10.0, ab, Eigen::MatrixXd::Zero(3, 2), 4, {}, "rows");
  refused(10.0, ab, two, 4, {{"format", "x"}}, "reserved");
  refused(10.0, ab, two, 4, {{"sample_rate_hz", "x"}}, "reserved");
  refused(10.0, ab, two, 4, {{"a", "x"}, {"a", "y"}}, "'a' repeats");
  EXPECT_FALSE(fs::exists(file));
}

TEST_F(TimeHistoryH5, UnwritablePathNamesThePathQuietly) {
  const fs::path file = dir_ / "no_such_folder" / "time_history.h5";
  testing::internal::CaptureStderr();
  expect_throw_naming<std::runtime_error>(
      [&] {
        write_time_history_h5(file, 10.0, {0.0}, {{"a", "m"}}, Eigen::MatrixXd::Zero(1, 1), 1, {});
      },
      {file.string(), "cannot create"});
  EXPECT_EQ(testing::internal::GetCapturedStderr(), "");  // no HDF5 error stack printed
  EXPECT_FALSE(fs::exists(dir_ / "no_such_folder"));
}

// A valid file, then `edit` applied to it with the HDF5 API, then the read error expected.
class BrokenTimeHistory : public TimeHistoryH5 {
 protected:
  fs::path broken(const std::function<void(hid_t)>& edit) {
    const fs::path file = dir_ / "broken.h5";
    write_time_history_h5(file, 100.0, {0.0, 0.01, 0.02}, {{"a", "m"}, {"b", "N"}},
                          Eigen::MatrixXd::Ones(3, 2), 3, {{"analysis", "t"}});
    const QuietHdf5 quiet;
    const Hdf5Handle f(H5Fopen(file.c_str(), H5F_ACC_RDWR, H5P_DEFAULT), H5Fclose);
    edit(f.get());
    return file;
  }
  void expect_read_error(const fs::path& file, const std::vector<std::string>& parts) {
    std::vector<std::string> all = parts;
    all.push_back(file.string());
    testing::internal::CaptureStderr();
    expect_throw_naming<std::runtime_error>([&] { read_time_history_h5(file); }, all);
    EXPECT_EQ(testing::internal::GetCapturedStderr(), "");
  }
};

TEST_F(BrokenTimeHistory, MissingOrForeignFiles) {
  expect_read_error(dir_ / "absent.h5", {"no such file"});
  std::ofstream(dir_ / "text.h5") << "time,a\n0,1\n";
  expect_read_error(dir_ / "text.h5", {"not an HDF5 file"});
  const fs::path file = broken([](hid_t f) { H5Adelete(f, "format"); });
  expect_read_error(file, {"no attribute 'format'"});
}

TEST_F(BrokenTimeHistory, MissingTimeOrChannelOfWrongLength) {
  expect_read_error(broken([](hid_t f) { H5Ldelete(f, "/time", H5P_DEFAULT); }),
                    {"/time", "missing dataset"});
  const fs::path file = broken([](hid_t f) {
    H5Ldelete(f, "/channels/b", H5P_DEFAULT);
    const hsize_t dims[1] = {2};
    const Hdf5Handle space(H5Screate_simple(1, dims, nullptr), H5Sclose);
    const Hdf5Handle set(H5Dcreate2(f, "/channels/b", H5T_IEEE_F64LE, space.get(), H5P_DEFAULT,
                                    H5P_DEFAULT, H5P_DEFAULT),
                         H5Dclose);
  });
  expect_read_error(file, {"/channels/b", "2 samples where /time has 3"});
}

}  // namespace
}  // namespace geardyn::io
