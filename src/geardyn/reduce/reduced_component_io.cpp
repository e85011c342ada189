#include "geardyn/reduce/reduced_component_io.hpp"

#include <fmt/format.h>
#include <hdf5.h>

#include <cstdint>
#include <filesystem>
#include <functional>
#include <stdexcept>
#include <vector>

#include "geardyn/core/error.hpp"
#include "geardyn/io/hdf5_handle.hpp"

namespace geardyn::reduce {

namespace {

namespace fs = std::filesystem;
using RowMajor = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;

using Handle = io::Hdf5Handle;
using io::QuietHdf5;

// ---------------------------------------------------------------------------------------------
// Writing

[[noreturn]] void write_failed(const std::string& path, const std::string& what) {
  throw std::runtime_error(fmt::format("cannot write reduced component '{}': {}", path, what));
}

struct Writer {
  std::string path;  // the final path, for messages
  hid_t file = -1;

  void check(herr_t status, const std::string& what) const {
    if (status < 0) write_failed(path, what);
  }

  void group(const std::string& name) const {
    Handle g(H5Gcreate2(file, name.c_str(), H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT), H5Gclose);
    if (!g.ok()) write_failed(path, "group " + name);
  }

  // Row-major 1-D or 2-D dataset of `type` (the file and memory type are the same native type).
  void dataset(const std::string& name, hid_t type, std::vector<hsize_t> dims, const void* data,
               bool compress) const {
    Handle space(H5Screate_simple(static_cast<int>(dims.size()), dims.data(), nullptr), H5Sclose);
    if (!space.ok()) write_failed(path, "dataspace of " + name);
    Handle plist(H5Pcreate(H5P_DATASET_CREATE), H5Pclose);
    bool empty = false;
    for (hsize_t d : dims) empty = empty || d == 0;
    if (compress && !empty) {
      // Chunks of up to 1024 rows x 64 columns (512 KiB of doubles): whole chunks are read and
      // written at once, and they stay well inside HDF5's default chunk cache.
      std::vector<hsize_t> chunk = dims;
      chunk[0] = std::min<hsize_t>(dims[0], 1024);
      if (chunk.size() > 1) chunk[1] = std::min<hsize_t>(dims[1], 64);
      check(H5Pset_chunk(plist.get(), static_cast<int>(chunk.size()), chunk.data()),
            "chunk layout of " + name);
      check(H5Pset_shuffle(plist.get()), "shuffle filter of " + name);
      check(H5Pset_deflate(plist.get(), 4), "deflate filter of " + name);
    }
    Handle set(
        H5Dcreate2(file, name.c_str(), type, space.get(), H5P_DEFAULT, plist.get(), H5P_DEFAULT),
        H5Dclose);
    if (!set.ok()) write_failed(path, "dataset " + name);
    if (!empty)
      check(H5Dwrite(set.get(), type, H5S_ALL, H5S_ALL, H5P_DEFAULT, data), "data of " + name);
  }

  void matrix(const std::string& name, const Eigen::MatrixXd& A, bool compress) const {
    const RowMajor R = A;
    dataset(name, H5T_NATIVE_DOUBLE,
            {static_cast<hsize_t>(A.rows()), static_cast<hsize_t>(A.cols())}, R.data(), compress);
  }

  void vector(const std::string& name, const Eigen::VectorXd& v) const {
    dataset(name, H5T_NATIVE_DOUBLE, {static_cast<hsize_t>(v.size())}, v.data(), false);
  }

  void integers(const std::string& name, const std::vector<std::int64_t>& v, bool compress) const {
    dataset(name, H5T_NATIVE_INT64, {static_cast<hsize_t>(v.size())}, v.data(), compress);
  }

  void components(const std::string& name, const std::vector<std::int32_t>& v,
                  bool compress) const {
    dataset(name, H5T_NATIVE_INT32, {static_cast<hsize_t>(v.size())}, v.data(), compress);
  }

  void string_attribute(hid_t object, const std::string& name, const std::string& value) const {
    Handle type(H5Tcopy(H5T_C_S1), H5Tclose);
    check(H5Tset_size(type.get(), value.size() + 1), "string type of " + name);
    check(H5Tset_strpad(type.get(), H5T_STR_NULLTERM), "string type of " + name);
    Handle space(H5Screate(H5S_SCALAR), H5Sclose);
    Handle attribute(
        H5Acreate2(object, name.c_str(), type.get(), space.get(), H5P_DEFAULT, H5P_DEFAULT),
        H5Aclose);
    if (!attribute.ok()) write_failed(path, "attribute " + name);
    check(H5Awrite(attribute.get(), type.get(), value.c_str()), "attribute " + name);
  }

  void int_attribute(hid_t object, const std::string& name, int value) const {
    Handle space(H5Screate(H5S_SCALAR), H5Sclose);
    Handle attribute(
        H5Acreate2(object, name.c_str(), H5T_STD_I32LE, space.get(), H5P_DEFAULT, H5P_DEFAULT),
        H5Aclose);
    if (!attribute.ok()) write_failed(path, "attribute " + name);
    check(H5Awrite(attribute.get(), H5T_NATIVE_INT, &value), "attribute " + name);
  }
};

void dof_columns(const std::vector<solid::DofInfo>& dofs, std::vector<std::int64_t>& ids,
                 std::vector<std::int32_t>& components, Eigen::MatrixXd& x) {
  ids.resize(dofs.size());
  components.resize(dofs.size());
  x.resize(static_cast<Eigen::Index>(dofs.size()), 3);
  for (std::size_t k = 0; k < dofs.size(); ++k) {
    ids[k] = dofs[k].node_id;
    components[k] = dofs[k].component;
    x.row(static_cast<Eigen::Index>(k)) = dofs[k].x.transpose();
  }
}

void check_consistent(const ReducedComponent& rc) {
  const Eigen::Index m = rc.size(), nb = rc.n_masters(), n = rc.n_full();
  const Eigen::Index ni = static_cast<Eigen::Index>(rc.interior_index.size());
  auto bad = [](const std::string& what, const std::string& expected, const std::string& found) {
    throw InputError({}, "reduce.save_reduced." + what, expected, found);
  };
  if (rc.K.rows() != m || rc.K.cols() != m)
    bad("K", fmt::format("{0}x{0}", m), fmt::format("{}x{}", rc.K.rows(), rc.K.cols()));
  if (rc.M.rows() != m || rc.M.cols() != m)
    bad("M", fmt::format("{0}x{0}", m), fmt::format("{}x{}", rc.M.rows(), rc.M.cols()));
  if (rc.fixed_interface_hz.size() != rc.n_modal)
    bad("fixed_interface_hz", std::to_string(rc.n_modal),
        std::to_string(rc.fixed_interface_hz.size()));
  if (static_cast<Eigen::Index>(rc.master_index.size()) != nb || nb + ni != n)
    bad("master_index", fmt::format("{} masters and {} interior DOFs making {}", nb, ni, n),
        fmt::format("{} master indices", rc.master_index.size()));
  if (rc.Psi.rows() != ni || rc.Psi.cols() != nb)
    bad("Psi", fmt::format("{}x{}", ni, nb), fmt::format("{}x{}", rc.Psi.rows(), rc.Psi.cols()));
  if (rc.Phi.rows() != ni || rc.Phi.cols() != rc.n_modal)
    bad("Phi", fmt::format("{}x{}", ni, rc.n_modal),
        fmt::format("{}x{}", rc.Phi.rows(), rc.Phi.cols()));
}

// ---------------------------------------------------------------------------------------------
// Reading

struct Reader {
  std::string path;
  hid_t file = -1;

  [[noreturn]] void bad(const std::string& key, const std::string& expected,
                        const std::string& found) const {
    throw InputError({path}, key, expected, found,
                     "the file is not a complete geardyn reduced component (format_version " +
                         std::to_string(kReducedFormatVersion) +
                         "); write it again with save_reduced");
  }

  bool exists(const std::string& name) const {
    // H5Lexists needs every parent to exist, so walk the path one link at a time.
    std::string partial;
    std::size_t start = 1;
    while (start <= name.size()) {
      const std::size_t end = name.find('/', start);
      partial = name.substr(0, end == std::string::npos ? name.size() : end);
      if (H5Lexists(file, partial.c_str(), H5P_DEFAULT) <= 0) return false;
      if (end == std::string::npos) break;
      start = end + 1;
    }
    return true;
  }

  // Opens `name`, checks its class and shape (a dimension of -1 is free), asks `buffer` for
  // storage of the found dimensions and reads the data into it.
  void read(const std::string& name, H5T_class_t type_class, hid_t memory_type,
            const std::vector<long long>& expected,
            const std::function<void*(const std::vector<hsize_t>&)>& buffer) const {
    if (!exists(name)) bad(name, "a dataset", "missing");
    Handle set(H5Dopen2(file, name.c_str(), H5P_DEFAULT), H5Dclose);
    if (!set.ok()) bad(name, "a dataset", "a link that is not a readable dataset");
    Handle type(H5Dget_type(set.get()), H5Tclose);
    if (H5Tget_class(type.get()) != type_class)
      bad(name, type_class == H5T_FLOAT ? "floating-point values" : "integer values",
          "another type");
    Handle space(H5Dget_space(set.get()), H5Sclose);
    const int rank = H5Sget_simple_extent_ndims(space.get());
    if (rank != static_cast<int>(expected.size()))
      bad(name, fmt::format("{} dimension(s)", expected.size()), fmt::format("{}", rank));
    std::vector<hsize_t> dims(expected.size());
    H5Sget_simple_extent_dims(space.get(), dims.data(), nullptr);
    std::string want, got;
    bool match = true;
    hsize_t count = 1;
    for (std::size_t k = 0; k < dims.size(); ++k) {
      want +=
          (k ? " x " : "") + (expected[k] < 0 ? std::string("any") : std::to_string(expected[k]));
      got += (k ? " x " : "") + std::to_string(dims[k]);
      if (expected[k] >= 0 && dims[k] != static_cast<hsize_t>(expected[k])) match = false;
      count *= dims[k];
    }
    if (!match) bad(name, "shape " + want, "shape " + got);
    void* data = buffer(dims);
    if (count > 0 && H5Dread(set.get(), memory_type, H5S_ALL, H5S_ALL, H5P_DEFAULT, data) < 0)
      bad(name, "readable data", "a read error (corrupt or truncated file)");
  }

  Eigen::MatrixXd matrix(const std::string& name, long long rows, long long cols) const {
    RowMajor R;
    read(name, H5T_FLOAT, H5T_NATIVE_DOUBLE, {rows, cols}, [&](const std::vector<hsize_t>& d) {
      R.resize(static_cast<Eigen::Index>(d[0]), static_cast<Eigen::Index>(d[1]));
      return static_cast<void*>(R.data());
    });
    return R;
  }

  Eigen::VectorXd doubles(const std::string& name, long long size) const {
    Eigen::VectorXd v;
    read(name, H5T_FLOAT, H5T_NATIVE_DOUBLE, {size}, [&](const std::vector<hsize_t>& d) {
      v.resize(static_cast<Eigen::Index>(d[0]));
      return static_cast<void*>(v.data());
    });
    return v;
  }

  template <class Int>
  std::vector<Int> integers(const std::string& name, hid_t memory_type, long long size) const {
    std::vector<Int> v;
    read(name, H5T_INTEGER, memory_type, {size}, [&](const std::vector<hsize_t>& d) {
      v.resize(d[0]);
      return static_cast<void*>(v.data());
    });
    return v;
  }
  std::vector<std::int64_t> int64s(const std::string& name, long long size) const {
    return integers<std::int64_t>(name, H5T_NATIVE_INT64, size);
  }
  std::vector<std::int32_t> int32s(const std::string& name, long long size) const {
    return integers<std::int32_t>(name, H5T_NATIVE_INT32, size);
  }

  // The attribute's identifier (the caller owns it), after checking it exists.
  hid_t open_attribute(const std::string& group, const std::string& name) const {
    const std::string key = group + "/" + name;
    if (!exists(group)) bad(key, "an attribute", "missing (no group " + group + ")");
    if (H5Aexists_by_name(file, group.c_str(), name.c_str(), H5P_DEFAULT) <= 0)
      bad(key, "an attribute", "missing");
    const hid_t a = H5Aopen_by_name(file, group.c_str(), name.c_str(), H5P_DEFAULT, H5P_DEFAULT);
    if (a < 0) bad(key, "a readable attribute", "unreadable");
    return a;
  }

  std::string string_attribute(const std::string& group, const std::string& name) const {
    const std::string key = group + "/" + name;
    const Handle a(open_attribute(group, name), H5Aclose);
    Handle type(H5Aget_type(a.get()), H5Tclose);
    if (H5Tget_class(type.get()) != H5T_STRING) bad(key, "a string", "another type");
    if (H5Tis_variable_str(type.get()) > 0) {
      char* text = nullptr;
      Handle memory(H5Tcopy(H5T_C_S1), H5Tclose);
      H5Tset_size(memory.get(), H5T_VARIABLE);
      if (H5Aread(a.get(), memory.get(), &text) < 0) bad(key, "a readable string", "unreadable");
      std::string out = text ? text : "";
      H5free_memory(text);
      return out;
    }
    const std::size_t size = H5Tget_size(type.get());
    std::vector<char> buffer(size + 1, '\0');
    if (H5Aread(a.get(), type.get(), buffer.data()) < 0)
      bad(key, "a readable string", "unreadable");
    return std::string(buffer.data());
  }

  int int_attribute(const std::string& group, const std::string& name) const {
    const std::string key = group + "/" + name;
    const Handle a(open_attribute(group, name), H5Aclose);
    Handle type(H5Aget_type(a.get()), H5Tclose);
    if (H5Tget_class(type.get()) != H5T_INTEGER) bad(key, "an integer", "another type");
    int value = 0;
    if (H5Aread(a.get(), H5T_NATIVE_INT, &value) < 0) bad(key, "a readable integer", "unreadable");
    return value;
  }
};

std::vector<solid::DofInfo> dof_infos(const std::vector<std::int64_t>& ids,
                                      const std::vector<std::int32_t>& components,
                                      const Eigen::MatrixXd& x) {
  std::vector<solid::DofInfo> out(ids.size());
  for (std::size_t k = 0; k < ids.size(); ++k) {
    out[k].node_id = ids[k];
    out[k].component = components[k];
    out[k].x = x.row(static_cast<Eigen::Index>(k)).transpose();
  }
  return out;
}

}  // namespace

void save_reduced(const std::string& path, const ReducedComponent& rc) {
  check_consistent(rc);
  const QuietHdf5 quiet;
  if (H5Zfilter_avail(H5Z_FILTER_DEFLATE) <= 0)
    write_failed(path, "the HDF5 library has no deflate (zlib) filter");
  const std::string partial = path + ".partial";
  std::error_code ec;
  fs::remove(partial, ec);
  try {
    {
      Handle file(H5Fcreate(partial.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT), H5Fclose);
      if (!file.ok()) write_failed(path, "cannot create " + partial);
      const Writer w{path, file.get()};
      w.group("/matrices");
      w.matrix("/matrices/K", rc.K, false);
      w.matrix("/matrices/M", rc.M, false);

      std::vector<std::int64_t> ids;
      std::vector<std::int32_t> components;
      Eigen::MatrixXd x;
      w.group("/masters");
      dof_columns(rc.masters, ids, components, x);
      w.integers("/masters/node_id", ids, false);
      w.components("/masters/component", components, false);
      w.matrix("/masters/x", x, false);

      w.group("/modal");
      w.vector("/modal/frequency_hz", rc.fixed_interface_hz);

      w.group("/recovery");
      w.matrix("/recovery/Psi", rc.Psi, true);
      w.matrix("/recovery/Phi", rc.Phi, true);
      w.integers("/recovery/master_index",
                 std::vector<std::int64_t>(rc.master_index.begin(), rc.master_index.end()), false);
      w.integers("/recovery/interior_index",
                 std::vector<std::int64_t>(rc.interior_index.begin(), rc.interior_index.end()),
                 true);
      dof_columns(rc.full_dofs, ids, components, x);
      w.integers("/recovery/node_id", ids, true);
      w.components("/recovery/component", components, true);
      w.matrix("/recovery/x", x, true);

      w.group("/provenance");
      Handle prov(H5Gopen2(file.get(), "/provenance", H5P_DEFAULT), H5Gclose);
      w.int_attribute(prov.get(), "format_version", kReducedFormatVersion);
      w.string_attribute(prov.get(), "method", rc.provenance.method);
      w.string_attribute(prov.get(), "geardyn_version", rc.provenance.geardyn_version);
      w.string_attribute(prov.get(), "source_sha256", rc.provenance.source_sha256);
      w.string_attribute(prov.get(), "options", rc.provenance.options_json);
      w.string_attribute(prov.get(), "created_utc", rc.provenance.created_utc);
      w.string_attribute(prov.get(), "solver_report", rc.provenance.solver_report);
      if (H5Fflush(file.get(), H5F_SCOPE_GLOBAL) < 0) write_failed(path, "flush");
    }
    fs::rename(partial, path);
  } catch (...) {
    fs::remove(partial, ec);
    throw;
  }
}

ReducedComponent load_reduced(const std::string& path) {
  const QuietHdf5 quiet;
  std::error_code ec;
  if (!fs::is_regular_file(path, ec))
    throw InputError({path}, "", "a reduced-component file (HDF5)", "no such file");
  if (H5Fis_hdf5(path.c_str()) <= 0)
    throw InputError({path}, "", "a reduced-component file (HDF5)", "a file that is not HDF5");
  Handle file(H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT), H5Fclose);
  if (!file.ok()) throw InputError({path}, "", "a readable HDF5 file", "a file HDF5 cannot open");
  const Reader r{path, file.get()};

  const int version = r.int_attribute("/provenance", "format_version");
  if (version != kReducedFormatVersion)
    r.bad("/provenance/format_version", std::to_string(kReducedFormatVersion),
          std::to_string(version));

  ReducedComponent rc;
  const auto master_ids = r.int64s("/masters/node_id", -1);
  const auto nb = static_cast<long long>(master_ids.size());
  rc.fixed_interface_hz = r.doubles("/modal/frequency_hz", -1);
  rc.n_modal = static_cast<int>(rc.fixed_interface_hz.size());
  const long long m = nb + rc.n_modal;
  rc.K = r.matrix("/matrices/K", m, m);
  rc.M = r.matrix("/matrices/M", m, m);
  rc.masters =
      dof_infos(master_ids, r.int32s("/masters/component", nb), r.matrix("/masters/x", nb, 3));

  const auto full_ids = r.int64s("/recovery/node_id", -1);
  const auto n = static_cast<long long>(full_ids.size());
  if (n < nb)
    r.bad("/recovery/node_id", fmt::format("at least {} DOFs (the masters)", nb),
          std::to_string(n));
  rc.full_dofs =
      dof_infos(full_ids, r.int32s("/recovery/component", n), r.matrix("/recovery/x", n, 3));
  const auto mi = r.int64s("/recovery/master_index", nb);
  const auto ii = r.int64s("/recovery/interior_index", n - nb);
  // The two index lists must split 0 .. n-1.
  std::vector<bool> seen(static_cast<std::size_t>(n), false);
  auto take = [&](const std::vector<std::int64_t>& list, const std::string& key,
                  std::vector<int>& out) {
    for (std::int64_t g : list) {
      if (g < 0 || g >= n || seen[static_cast<std::size_t>(g)])
        r.bad(key,
              fmt::format("distinct DOF indices 0 .. {} shared with the other index list", n - 1),
              std::to_string(g));
      seen[static_cast<std::size_t>(g)] = true;
      out.push_back(static_cast<int>(g));
    }
  };
  take(mi, "/recovery/master_index", rc.master_index);
  take(ii, "/recovery/interior_index", rc.interior_index);
  for (std::size_t k = 0; k < rc.masters.size(); ++k) {
    const auto& a = rc.masters[k];
    const auto& b = rc.full_dofs[static_cast<std::size_t>(rc.master_index[k])];
    if (a.node_id != b.node_id || a.component != b.component)
      r.bad("/masters/node_id",
            fmt::format("master {} to be full DOF {} (node {}, component {})", k,
                        rc.master_index[k], b.node_id, b.component),
            fmt::format("node {}, component {}", a.node_id, a.component));
  }
  rc.Psi = r.matrix("/recovery/Psi", n - nb, nb);
  rc.Phi = r.matrix("/recovery/Phi", n - nb, rc.n_modal);

  rc.provenance.method = r.string_attribute("/provenance", "method");
  rc.provenance.geardyn_version = r.string_attribute("/provenance", "geardyn_version");
  rc.provenance.source_sha256 = r.string_attribute("/provenance", "source_sha256");
  rc.provenance.options_json = r.string_attribute("/provenance", "options");
  rc.provenance.created_utc = r.string_attribute("/provenance", "created_utc");
  rc.provenance.solver_report = r.string_attribute("/provenance", "solver_report");
  return rc;
}

}  // namespace geardyn::reduce
