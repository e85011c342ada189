#include "geardyn/io/time_history_h5.hpp"

#include <fmt/format.h>
#include <hdf5.h>

#include <algorithm>
#include <cmath>
#include <set>
#include <stdexcept>
#include <system_error>

#include "geardyn/io/hdf5_handle.hpp"

namespace geardyn::io {

namespace {

namespace fs = std::filesystem;
using Handle = Hdf5Handle;

constexpr const char* kFormatAttribute = "format";
constexpr const char* kRateAttribute = "sample_rate_hz";
constexpr const char* kUnitAttribute = "unit";

// ---------------------------------------------------------------------------------------------
// Writing

void check_arguments(double sample_rate_hz, const std::vector<double>& time,
                     const std::vector<TimeHistoryChannel>& channels, const Eigen::MatrixXd& values,
                     std::size_t samples,
                     const std::vector<std::pair<std::string, std::string>>& attributes) {
  auto bad = [](const std::string& what) {
    throw std::invalid_argument("write_time_history_h5: " + what);
  };
  if (!std::isfinite(sample_rate_hz) || sample_rate_hz <= 0.0)
    bad(fmt::format("sample_rate_hz must be finite and positive, not {}", sample_rate_hz));
  if (time.size() < samples)
    bad(fmt::format("{} samples asked but only {} times given", samples, time.size()));
  if (static_cast<std::size_t>(values.rows()) < samples)
    bad(fmt::format("{} samples asked but the values have only {} rows", samples, values.rows()));
  if (static_cast<std::size_t>(values.cols()) != channels.size())
    bad(fmt::format("{} channels but the values have {} columns", channels.size(), values.cols()));
  std::set<std::string> seen;
  for (const auto& channel : channels) {
    if (!is_time_history_channel_name(channel.name))
      bad(fmt::format("channel name '{}' is not a column name (letters, digits, underscores)",
                      channel.name));
    if (!seen.insert(channel.name).second)
      bad(fmt::format("channel name '{}' repeats", channel.name));
  }
  seen.clear();
  for (const auto& [name, value] : attributes) {
    if (name.empty() || name == kFormatAttribute || name == kRateAttribute)
      bad(fmt::format("attribute name '{}' is empty or reserved ('{}', '{}')", name,
                      kFormatAttribute, kRateAttribute));
    if (!seen.insert(name).second) bad(fmt::format("attribute name '{}' repeats", name));
  }
}

struct Writer {
  std::string path;  // the final path, for messages
  hid_t file = -1;

  [[noreturn]] void failed(const std::string& what) const {
    throw std::runtime_error(fmt::format("cannot write time history '{}': {}", path, what));
  }
  void check(herr_t status, const std::string& what) const {
    if (status < 0) failed(what);
  }

  void string_attribute(hid_t object, const std::string& name, const std::string& value) const {
    Handle type(H5Tcopy(H5T_C_S1), H5Tclose);
    check(H5Tset_size(type.get(), value.size() + 1), "string type of attribute " + name);
    check(H5Tset_strpad(type.get(), H5T_STR_NULLTERM), "string type of attribute " + name);
    Handle space(H5Screate(H5S_SCALAR), H5Sclose);
    Handle attribute(
        H5Acreate2(object, name.c_str(), type.get(), space.get(), H5P_DEFAULT, H5P_DEFAULT),
        H5Aclose);
    if (!attribute.ok()) failed("attribute " + name);
    check(H5Awrite(attribute.get(), type.get(), value.c_str()), "attribute " + name);
  }

  void double_attribute(hid_t object, const std::string& name, double value) const {
    Handle space(H5Screate(H5S_SCALAR), H5Sclose);
    Handle attribute(
        H5Acreate2(object, name.c_str(), H5T_IEEE_F64LE, space.get(), H5P_DEFAULT, H5P_DEFAULT),
        H5Aclose);
    if (!attribute.ok()) failed("attribute " + name);
    check(H5Awrite(attribute.get(), H5T_NATIVE_DOUBLE, &value), "attribute " + name);
  }

  // A 1-D dataset of n doubles, chunked, shuffled and deflated unless empty (a chunk may not be
  // larger than a fixed-size dataset, and an empty one has nothing to compress).
  void doubles(const std::string& name, const double* data, std::size_t n,
               const std::string* unit) const {
    const hsize_t dims[1] = {static_cast<hsize_t>(n)};
    Handle space(H5Screate_simple(1, dims, nullptr), H5Sclose);
    if (!space.ok()) failed("dataspace of " + name);
    Handle plist(H5Pcreate(H5P_DATASET_CREATE), H5Pclose);
    if (n > 0) {
      const hsize_t chunk[1] = {std::min<hsize_t>(n, kTimeHistoryChunk)};
      check(H5Pset_chunk(plist.get(), 1, chunk), "chunk layout of " + name);
      check(H5Pset_shuffle(plist.get()), "shuffle filter of " + name);
      check(H5Pset_deflate(plist.get(), 4), "deflate filter of " + name);
    }
    Handle set(H5Dcreate2(file, name.c_str(), H5T_IEEE_F64LE, space.get(), H5P_DEFAULT, plist.get(),
                          H5P_DEFAULT),
               H5Dclose);
    if (!set.ok()) failed("dataset " + name);
    if (n > 0)
      check(H5Dwrite(set.get(), H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, data),
            "data of " + name);
    if (unit) string_attribute(set.get(), kUnitAttribute, *unit);
  }
};

// ---------------------------------------------------------------------------------------------
// Reading

struct Reader {
  std::string path;
  hid_t file = -1;

  [[noreturn]] void bad(const std::string& where, const std::string& what) const {
    throw std::runtime_error(
        fmt::format("cannot read time history '{}': {}: {}", path, where, what));
  }

  // The names of `object`'s attributes, in creation order when the file tracks it.
  std::vector<std::string> attribute_names(hid_t object, const std::string& where) const {
    std::vector<std::string> names;
    auto collect = [](hid_t, const char* name, const H5A_info_t*, void* out) -> herr_t {
      static_cast<std::vector<std::string>*>(out)->emplace_back(name);
      return 0;
    };
    if (H5Aiterate2(object, H5_INDEX_CRT_ORDER, H5_ITER_INC, nullptr, collect, &names) >= 0)
      return names;
    names.clear();
    if (H5Aiterate2(object, H5_INDEX_NAME, H5_ITER_INC, nullptr, collect, &names) < 0)
      bad(where, "unreadable attribute list");
    return names;
  }

  hid_t open_attribute(hid_t object, const std::string& where, const std::string& name) const {
    if (H5Aexists(object, name.c_str()) <= 0) bad(where, "no attribute '" + name + "'");
    const hid_t a = H5Aopen(object, name.c_str(), H5P_DEFAULT);
    if (a < 0) bad(where, "unreadable attribute '" + name + "'");
    return a;
  }

  // A fixed-length or variable-length (as h5py writes them) string attribute.
  std::string string_attribute(hid_t object, const std::string& where,
                               const std::string& name) const {
    const Handle a(open_attribute(object, where, name), H5Aclose);
    const Handle type(H5Aget_type(a.get()), H5Tclose);
    if (H5Tget_class(type.get()) != H5T_STRING)
      bad(where, "attribute '" + name + "' is not a string");
    if (H5Tis_variable_str(type.get()) > 0) {
      char* text = nullptr;
      const Handle memory(H5Tcopy(H5T_C_S1), H5Tclose);
      H5Tset_size(memory.get(), H5T_VARIABLE);
      if (H5Aread(a.get(), memory.get(), &text) < 0)
        bad(where, "unreadable attribute '" + name + "'");
      std::string out = text ? text : "";
      H5free_memory(text);
      return out;
    }
    std::vector<char> buffer(H5Tget_size(type.get()) + 1, '\0');
    if (H5Aread(a.get(), type.get(), buffer.data()) < 0)
      bad(where, "unreadable attribute '" + name + "'");
    return std::string(buffer.data());
  }

  double double_attribute(hid_t object, const std::string& where, const std::string& name) const {
    const Handle a(open_attribute(object, where, name), H5Aclose);
    const Handle type(H5Aget_type(a.get()), H5Tclose);
    const Handle space(H5Aget_space(a.get()), H5Sclose);
    if (H5Tget_class(type.get()) != H5T_FLOAT || H5Sget_simple_extent_npoints(space.get()) != 1)
      bad(where, "attribute '" + name + "' is not one floating-point number");
    double value = 0.0;
    if (H5Aread(a.get(), H5T_NATIVE_DOUBLE, &value) < 0)
      bad(where, "unreadable attribute '" + name + "'");
    return value;
  }

  // The identifier of dataset `name` (the caller owns it), after checking it exists.
  hid_t open_dataset(const std::string& name) const {
    if (H5Lexists(file, name.c_str(), H5P_DEFAULT) <= 0) bad(name, "missing dataset");
    const hid_t set = H5Dopen2(file, name.c_str(), H5P_DEFAULT);
    if (set < 0) bad(name, "not a readable dataset");
    return set;
  }

  // The length of a 1-D floating-point dataset.
  hsize_t doubles_length(hid_t set, const std::string& name) const {
    const Handle type(H5Dget_type(set), H5Tclose);
    if (H5Tget_class(type.get()) != H5T_FLOAT) bad(name, "not floating-point values");
    const Handle space(H5Dget_space(set), H5Sclose);
    if (H5Sget_simple_extent_ndims(space.get()) != 1) bad(name, "not one-dimensional");
    hsize_t n = 0;
    H5Sget_simple_extent_dims(space.get(), &n, nullptr);
    return n;
  }

  void read_doubles(hid_t set, const std::string& name, hsize_t n, double* out) const {
    if (n > 0 && H5Dread(set, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, out) < 0)
      bad(name, "unreadable data (corrupt or truncated file)");
  }

  // The names of the links in `group`, in creation order when the file tracks it.
  std::vector<std::string> link_names(const std::string& group) const {
    if (H5Lexists(file, group.c_str(), H5P_DEFAULT) <= 0) bad(group, "missing group");
    const Handle g(H5Gopen2(file, group.c_str(), H5P_DEFAULT), H5Gclose);
    if (!g.ok()) bad(group, "not a readable group");
    H5G_info_t info;
    if (H5Gget_info(g.get(), &info) < 0) bad(group, "unreadable group");
    std::vector<std::string> names;
    for (H5_index_t index : {H5_INDEX_CRT_ORDER, H5_INDEX_NAME}) {
      names.clear();
      for (hsize_t k = 0; k < info.nlinks; ++k) {
        const ssize_t size =
            H5Lget_name_by_idx(g.get(), ".", index, H5_ITER_INC, k, nullptr, 0, H5P_DEFAULT);
        if (size < 0) break;
        std::vector<char> buffer(static_cast<std::size_t>(size) + 1, '\0');
        H5Lget_name_by_idx(g.get(), ".", index, H5_ITER_INC, k, buffer.data(), buffer.size(),
                           H5P_DEFAULT);
        names.emplace_back(buffer.data());
      }
      if (names.size() == info.nlinks) return names;
    }
    bad(group, "unreadable list of links");
  }
};

}  // namespace

bool is_time_history_channel_name(std::string_view name) {
  return !name.empty() && std::all_of(name.begin(), name.end(), [](char c) {
    return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '_';
  });
}

void write_time_history_h5(const fs::path& path, double sample_rate_hz,
                           const std::vector<double>& time,
                           const std::vector<TimeHistoryChannel>& channels,
                           const Eigen::MatrixXd& values, std::size_t samples,
                           const std::vector<std::pair<std::string, std::string>>& attributes) {
  check_arguments(sample_rate_hz, time, channels, values, samples, attributes);
  const QuietHdf5 quiet;
  const fs::path partial = fs::path(path).concat(".partial");
  Writer w{path.string(), -1};
  if (H5Zfilter_avail(H5Z_FILTER_DEFLATE) <= 0 || H5Zfilter_avail(H5Z_FILTER_SHUFFLE) <= 0)
    w.failed("the HDF5 library has no deflate (zlib) or shuffle filter");
  std::error_code ec;
  fs::remove(partial, ec);
  try {
    {
      // Attributes of the root group and links of /channels keep their creation order, which
      // is the order of the attributes and channels given.
      Handle fcpl(H5Pcreate(H5P_FILE_CREATE), H5Pclose);
      w.check(H5Pset_attr_creation_order(fcpl.get(), H5P_CRT_ORDER_TRACKED | H5P_CRT_ORDER_INDEXED),
              "file creation properties");
      Handle file(H5Fcreate(partial.c_str(), H5F_ACC_TRUNC, fcpl.get(), H5P_DEFAULT), H5Fclose);
      if (!file.ok())
        w.failed("cannot create " + partial.string() +
                 " (does its folder exist and is it writable?)");
      w.file = file.get();
      w.string_attribute(file.get(), kFormatAttribute, std::string(kTimeHistoryFormat));
      w.double_attribute(file.get(), kRateAttribute, sample_rate_hz);
      for (const auto& [name, value] : attributes) w.string_attribute(file.get(), name, value);
      w.doubles("/time", time.data(), samples, nullptr);

      Handle gcpl(H5Pcreate(H5P_GROUP_CREATE), H5Pclose);
      w.check(H5Pset_link_creation_order(gcpl.get(), H5P_CRT_ORDER_TRACKED | H5P_CRT_ORDER_INDEXED),
              "group creation properties");
      Handle group(H5Gcreate2(file.get(), "/channels", H5P_DEFAULT, gcpl.get(), H5P_DEFAULT),
                   H5Gclose);
      if (!group.ok()) w.failed("group /channels");
      for (std::size_t c = 0; c < channels.size(); ++c) {
        // Column c of a column-major matrix: its first `samples` entries are contiguous.
        const double* column = values.data() + static_cast<std::ptrdiff_t>(c) * values.rows();
        w.doubles("/channels/" + channels[c].name, column, samples, &channels[c].unit);
      }
      if (H5Fflush(file.get(), H5F_SCOPE_GLOBAL) < 0) w.failed("flush");
    }
    fs::rename(partial, path, ec);
    if (ec) w.failed("cannot rename " + partial.string() + " into place: " + ec.message());
  } catch (...) {
    fs::remove(partial, ec);
    throw;
  }
}

TimeHistory read_time_history_h5(const fs::path& path) {
  const QuietHdf5 quiet;
  const std::string name = path.string();
  auto fail = [&](const std::string& what) -> void {
    throw std::runtime_error(fmt::format("cannot read time history '{}': {}", name, what));
  };
  std::error_code ec;
  if (!fs::is_regular_file(path, ec)) fail("no such file");
  if (H5Fis_hdf5(name.c_str()) <= 0) fail("not an HDF5 file");
  const Handle file(H5Fopen(name.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT), H5Fclose);
  if (!file.ok()) fail("HDF5 cannot open it");
  const Reader r{name, file.get()};

  const std::string format = r.string_attribute(file.get(), "/", kFormatAttribute);
  if (format != kTimeHistoryFormat)
    r.bad("/",
          fmt::format("attribute 'format' is '{}', expected '{}'", format, kTimeHistoryFormat));
  TimeHistory out;
  out.sample_rate_hz = r.double_attribute(file.get(), "/", kRateAttribute);
  for (const std::string& attribute : r.attribute_names(file.get(), "/"))
    if (attribute != kFormatAttribute && attribute != kRateAttribute)
      out.attributes.emplace_back(attribute, r.string_attribute(file.get(), "/", attribute));

  hsize_t n = 0;
  {
    const Handle time(r.open_dataset("/time"), H5Dclose);
    n = r.doubles_length(time.get(), "/time");
    out.time.resize(static_cast<std::size_t>(n));
    r.read_doubles(time.get(), "/time", n, out.time.data());
  }
  const std::vector<std::string> names = r.link_names("/channels");
  out.values.resize(static_cast<Eigen::Index>(n), static_cast<Eigen::Index>(names.size()));
  for (std::size_t c = 0; c < names.size(); ++c) {
    const std::string dataset = "/channels/" + names[c];
    const Handle set(r.open_dataset(dataset), H5Dclose);
    const hsize_t length = r.doubles_length(set.get(), dataset);
    if (length != n) r.bad(dataset, fmt::format("{} samples where /time has {}", length, n));
    r.read_doubles(set.get(), dataset, n, out.values.col(static_cast<Eigen::Index>(c)).data());
    out.channels.push_back({names[c], r.string_attribute(set.get(), dataset, kUnitAttribute)});
  }
  return out;
}

}  // namespace geardyn::io
