// Test-side reading of run files with the HDF5 C API (independent of the writer's code).
#pragma once

#include <hdf5.h>

#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

namespace h5read {

/// Opens a file read-only for the scope; throws if it cannot be opened.
class File {
public:
  explicit File(const std::string &path) {
    id_ = H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
    if (id_ < 0)
      throw std::runtime_error("cannot open '" + path + "' with H5Fopen");
  }
  ~File() {
    if (id_ >= 0)
      H5Fclose(id_);
  }
  File(const File &) = delete;
  File &operator=(const File &) = delete;
  hid_t id() const { return id_; }

private:
  hid_t id_ = -1;
};

inline void require(bool ok, const std::string &what) {
  if (!ok)
    throw std::runtime_error("HDF5 read failed: " + what);
}

inline std::vector<hsize_t> dims(hid_t file, const std::string &path,
                                 std::vector<hsize_t> *maxdims = nullptr) {
  hid_t ds = H5Dopen2(file, path.c_str(), H5P_DEFAULT);
  require(ds >= 0, "open " + path);
  hid_t space = H5Dget_space(ds);
  const int rank = H5Sget_simple_extent_ndims(space);
  std::vector<hsize_t> d(rank), m(rank);
  H5Sget_simple_extent_dims(space, d.data(), m.data());
  H5Sclose(space);
  H5Dclose(ds);
  if (maxdims != nullptr)
    *maxdims = m;
  return d;
}

/// Chunk dimensions; empty if the dataset is not chunked.
inline std::vector<hsize_t> chunk(hid_t file, const std::string &path) {
  hid_t ds = H5Dopen2(file, path.c_str(), H5P_DEFAULT);
  require(ds >= 0, "open " + path);
  hid_t dcpl = H5Dget_create_plist(ds);
  std::vector<hsize_t> c;
  if (H5Pget_layout(dcpl) == H5D_CHUNKED) {
    c.resize(8);
    const int rank = H5Pget_chunk(dcpl, 8, c.data());
    c.resize(rank);
  }
  H5Pclose(dcpl);
  H5Dclose(ds);
  return c;
}

/// The dataset's file type class and size in bytes.
inline std::pair<H5T_class_t, std::size_t> type_of(hid_t file, const std::string &path) {
  hid_t ds = H5Dopen2(file, path.c_str(), H5P_DEFAULT);
  require(ds >= 0, "open " + path);
  hid_t t = H5Dget_type(ds);
  auto r = std::make_pair(H5Tget_class(t), H5Tget_size(t));
  H5Tclose(t);
  H5Dclose(ds);
  return r;
}

template <class T> std::vector<T> read_all(hid_t file, const std::string &path, hid_t mem_type) {
  std::vector<hsize_t> d = dims(file, path);
  std::size_t n = 1;
  for (hsize_t x : d)
    n *= x;
  std::vector<T> out(n);
  hid_t ds = H5Dopen2(file, path.c_str(), H5P_DEFAULT);
  require(ds >= 0, "open " + path);
  const bool ok = n == 0 || H5Dread(ds, mem_type, H5S_ALL, H5S_ALL, H5P_DEFAULT, out.data()) >= 0;
  H5Dclose(ds);
  require(ok, "read " + path);
  return out;
}
inline std::vector<std::int64_t> int64s(hid_t f, const std::string &p) {
  return read_all<std::int64_t>(f, p, H5T_NATIVE_INT64);
}
inline std::vector<double> doubles(hid_t f, const std::string &p) {
  return read_all<double>(f, p, H5T_NATIVE_DOUBLE);
}

/// A variable-length string attribute `attr` of object `path`.
inline std::string string_attr(hid_t file, const std::string &path, const std::string &attr) {
  hid_t a = H5Aopen_by_name(file, path.c_str(), attr.c_str(), H5P_DEFAULT, H5P_DEFAULT);
  require(a >= 0, "open attribute " + path + ":" + attr);
  hid_t t = H5Aget_type(a);
  require(H5Tget_class(t) == H5T_STRING && H5Tis_variable_str(t) > 0,
          path + ":" + attr + " is not a variable-length string");
  char *s = nullptr;
  require(H5Aread(a, t, &s) >= 0, "read attribute " + path + ":" + attr);
  std::string out = s != nullptr ? s : "";
  H5free_memory(s);
  H5Tclose(t);
  H5Aclose(a);
  return out;
}

inline std::vector<int> int_attr(hid_t file, const std::string &path, const std::string &attr) {
  hid_t a = H5Aopen_by_name(file, path.c_str(), attr.c_str(), H5P_DEFAULT, H5P_DEFAULT);
  require(a >= 0, "open attribute " + path + ":" + attr);
  hid_t space = H5Aget_space(a);
  std::vector<int> out(H5Sget_simple_extent_npoints(space));
  H5Sclose(space);
  require(H5Aread(a, H5T_NATIVE_INT, out.data()) >= 0, "read attribute " + path + ":" + attr);
  H5Aclose(a);
  return out;
}

/// A scalar variable-length string dataset.
inline std::string string_dataset(hid_t file, const std::string &path) {
  hid_t ds = H5Dopen2(file, path.c_str(), H5P_DEFAULT);
  require(ds >= 0, "open " + path);
  hid_t t = H5Dget_type(ds);
  char *s = nullptr;
  require(H5Dread(ds, t, H5S_ALL, H5S_ALL, H5P_DEFAULT, &s) >= 0, "read " + path);
  std::string out = s != nullptr ? s : "";
  H5free_memory(s);
  H5Tclose(t);
  H5Dclose(ds);
  return out;
}

inline bool exists(hid_t file, const std::string &path) {
  return H5Lexists(file, path.c_str(), H5P_DEFAULT) > 0;
}

} // namespace h5read
