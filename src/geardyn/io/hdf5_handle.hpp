#pragma once
// Two small helpers shared by geardyn's HDF5 readers and writers (reduced components,
// time histories): silencing HDF5's own error printing while geardyn reports the error itself,
// and closing every HDF5 identifier on every path out of a function.
#include <hdf5.h>

namespace geardyn::io {

/// HDF5 prints its error stack to stderr by default; geardyn reports errors itself (as
/// exceptions naming the file and what failed), so the printing is switched off while an
/// object of this class lives and restored afterwards.
class QuietHdf5 {
 public:
  QuietHdf5() {
    H5Eget_auto2(H5E_DEFAULT, &func_, &data_);
    H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr);
  }
  ~QuietHdf5() { H5Eset_auto2(H5E_DEFAULT, func_, data_); }
  QuietHdf5(const QuietHdf5&) = delete;
  QuietHdf5& operator=(const QuietHdf5&) = delete;

 private:
  H5E_auto2_t func_ = nullptr;
  void* data_ = nullptr;
};

/// Owns one HDF5 identifier (a negative one, from a failed call, is not closed).
class Hdf5Handle {
 public:
  Hdf5Handle(hid_t id, herr_t (*close)(hid_t)) : id_(id), close_(close) {}
  ~Hdf5Handle() {
    if (id_ >= 0) close_(id_);
  }
  Hdf5Handle(const Hdf5Handle&) = delete;
  Hdf5Handle& operator=(const Hdf5Handle&) = delete;
  hid_t get() const { return id_; }
  bool ok() const { return id_ >= 0; }

 private:
  hid_t id_;
  herr_t (*close_)(hid_t);
};

}  // namespace geardyn::io
