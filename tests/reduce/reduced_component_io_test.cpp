// HDF5 reduced-component file: round trip and error reporting (docs/reduced-component-format.md).
#include "geardyn/reduce/reduced_component_io.hpp"

#include <gtest/gtest.h>
#include <hdf5.h>

#include <filesystem>
#include <string>

#include "geardyn/core/error.hpp"
#include "geardyn/reduce/craig_bampton.hpp"
#include "reduce/reduce_test_support.hpp"

namespace geardyn::reduce {
namespace {

namespace fs = std::filesystem;

fs::path scratch(const std::string& name) {
  const fs::path dir = fs::path(GEARDYN_BINARY_DIR) / "test_reduce_io";
  fs::create_directories(dir);
  const fs::path p = dir / name;
  fs::remove(p);
  return p;
}

ReducedComponent beam_component(int n_modes) {
  const auto t = test::beam(12);
  CraigBamptonOptions o;
  o.n_modes = n_modes;
  return craig_bampton(t.K, t.M, t.dofs, select_dofs(t.dofs, {1, 7, 13}), o,
                       "0123456789abcdef0123456789abcdef0123456789abcdef0123456789abcdef",
                       "0.0.0-test");
}

void expect_identical(const ReducedComponent& a, const ReducedComponent& b) {
  // Bit-exact: HDF5 stores the IEEE doubles as they are.
  EXPECT_TRUE(a.K == b.K);
  EXPECT_TRUE(a.M == b.M);
  EXPECT_TRUE(a.Psi == b.Psi);
  EXPECT_TRUE(a.Phi == b.Phi);
  EXPECT_TRUE(a.fixed_interface_hz == b.fixed_interface_hz);
  EXPECT_EQ(a.n_modal, b.n_modal);
  EXPECT_EQ(a.master_index, b.master_index);
  EXPECT_EQ(a.interior_index, b.interior_index);
  ASSERT_EQ(a.full_dofs.size(), b.full_dofs.size());
  for (std::size_t k = 0; k < a.full_dofs.size(); ++k) {
    EXPECT_EQ(a.full_dofs[k].node_id, b.full_dofs[k].node_id);
    EXPECT_EQ(a.full_dofs[k].component, b.full_dofs[k].component);
    EXPECT_TRUE(a.full_dofs[k].x == b.full_dofs[k].x);
  }
  ASSERT_EQ(a.masters.size(), b.masters.size());
  for (std::size_t k = 0; k < a.masters.size(); ++k) {
    EXPECT_EQ(a.masters[k].node_id, b.masters[k].node_id);
    EXPECT_EQ(a.masters[k].component, b.masters[k].component);
    EXPECT_TRUE(a.masters[k].x == b.masters[k].x);
  }
  EXPECT_EQ(a.provenance.method, b.provenance.method);
  EXPECT_EQ(a.provenance.options_json, b.provenance.options_json);
  EXPECT_EQ(a.provenance.source_sha256, b.provenance.source_sha256);
  EXPECT_EQ(a.provenance.geardyn_version, b.provenance.geardyn_version);
  EXPECT_EQ(a.provenance.created_utc, b.provenance.created_utc);
  EXPECT_EQ(a.provenance.solver_report, b.provenance.solver_report);
}

TEST(ReducedComponentIo, RoundTripIsBitExact) {
  const ReducedComponent rc = beam_component(6);
  const fs::path p = scratch("beam_cb.h5");
  save_reduced(p.string(), rc);
  EXPECT_TRUE(fs::exists(p));
  EXPECT_FALSE(fs::exists(p.string() + ".partial"));
  expect_identical(rc, load_reduced(p.string()));

  // Recovery datasets are chunked and deflate-compressed.
  const hid_t file = H5Fopen(p.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  ASSERT_GE(file, 0);
  const hid_t set = H5Dopen2(file, "/recovery/Psi", H5P_DEFAULT);
  const hid_t plist = H5Dget_create_plist(set);
  EXPECT_EQ(H5Pget_layout(plist), H5D_CHUNKED);
  bool deflate = false;
  for (int k = 0; k < H5Pget_nfilters(plist); ++k) {
    unsigned flags = 0;
    std::size_t n = 0;
    deflate = deflate || H5Pget_filter2(plist, static_cast<unsigned>(k), &flags, &n, nullptr, 0,
                                        nullptr, nullptr) == H5Z_FILTER_DEFLATE;
  }
  EXPECT_TRUE(deflate);
  H5Pclose(plist);
  H5Dclose(set);
  H5Fclose(file);
}

TEST(ReducedComponentIo, GuyanRoundTripWithNoModes) {
  const ReducedComponent rc = beam_component(0);
  const fs::path p = scratch("beam_guyan.h5");
  save_reduced(p.string(), rc);
  const ReducedComponent back = load_reduced(p.string());
  EXPECT_EQ(back.n_modal, 0);
  expect_identical(rc, back);
}

TEST(ReducedComponentIo, MissingDatasetIsNamed) {
  const fs::path p = scratch("missing_phi.h5");
  save_reduced(p.string(), beam_component(4));
  const hid_t file = H5Fopen(p.c_str(), H5F_ACC_RDWR, H5P_DEFAULT);
  ASSERT_GE(file, 0);
  ASSERT_GE(H5Ldelete(file, "/recovery/Phi", H5P_DEFAULT), 0);
  H5Fclose(file);
  try {
    load_reduced(p.string());
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    EXPECT_EQ(e.key_path(), "/recovery/Phi");
    EXPECT_EQ(e.where().file, p.string());
    EXPECT_NE(std::string(e.what()).find("/recovery/Phi"), std::string::npos) << e.what();
  }
}

TEST(ReducedComponentIo, WrongShapeAndVersionAreRejected) {
  const fs::path p = scratch("bad_version.h5");
  save_reduced(p.string(), beam_component(2));
  {
    const hid_t file = H5Fopen(p.c_str(), H5F_ACC_RDWR, H5P_DEFAULT);
    const hid_t group = H5Gopen2(file, "/provenance", H5P_DEFAULT);
    ASSERT_GE(H5Adelete(group, "format_version"), 0);
    const hid_t space = H5Screate(H5S_SCALAR);
    const hid_t a =
        H5Acreate2(group, "format_version", H5T_STD_I32LE, space, H5P_DEFAULT, H5P_DEFAULT);
    const int version = 99;
    ASSERT_GE(H5Awrite(a, H5T_NATIVE_INT, &version), 0);
    H5Aclose(a);
    H5Sclose(space);
    H5Gclose(group);
    H5Fclose(file);
  }
  try {
    load_reduced(p.string());
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    EXPECT_EQ(e.key_path(), "/provenance/format_version");
    EXPECT_EQ(e.found(), "99");
  }

  const fs::path q = scratch("bad_shape.h5");
  save_reduced(q.string(), beam_component(2));
  {
    const hid_t file = H5Fopen(q.c_str(), H5F_ACC_RDWR, H5P_DEFAULT);
    H5Ldelete(file, "/matrices/M", H5P_DEFAULT);
    const hsize_t dims[2] = {3, 3};
    const hid_t space = H5Screate_simple(2, dims, nullptr);
    const hid_t set = H5Dcreate2(file, "/matrices/M", H5T_NATIVE_DOUBLE, space, H5P_DEFAULT,
                                 H5P_DEFAULT, H5P_DEFAULT);
    const double zeros[9] = {};
    H5Dwrite(set, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, zeros);
    H5Dclose(set);
    H5Sclose(space);
    H5Fclose(file);
  }
  try {
    load_reduced(q.string());
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    EXPECT_EQ(e.key_path(), "/matrices/M");
    EXPECT_EQ(e.found(), "shape 3 x 3");
  }
}

TEST(ReducedComponentIo, MissingOrForeignFileIsInputError) {
  EXPECT_THROW(load_reduced(scratch("does_not_exist.h5").string()), InputError);
  const fs::path p = scratch("not_hdf5.h5");
  {
    std::FILE* f = std::fopen(p.c_str(), "w");
    std::fputs("not an HDF5 file\n", f);
    std::fclose(f);
  }
  EXPECT_THROW(load_reduced(p.string()), InputError);
}

}  // namespace
}  // namespace geardyn::reduce
