// The RAII layer over the HDF5 C API: files, groups, datasets (lub/io/h5.hpp). Attributes
// are in h5_attribute.cpp, the shared error and type helpers in h5_detail.cpp, tables and
// dimension scales in h5_table.cpp.
#include "lub/io/h5.hpp"

#include <hdf5.h>

#include <algorithm>
#include <numeric>
#include <utility>

#include "io/h5_detail.hpp"

namespace lub::h5 {
namespace detail {
namespace {

// ---------------------------------------------------------------------------------
// Property lists

/// Link creation list that creates missing intermediate groups.
Hid intermediate_lcpl(hid_t err_loc) {
  Hid p(H5Pcreate(H5P_LINK_CREATE));
  if (!p.ok() || H5Pset_create_intermediate_group(p.get(), 1) < 0) {
    fail(err_loc, "cannot build a link-creation property list");
  }
  return p;
}

/// File access list: latest-compatible defaults; file locking that is ignored on file
/// systems without lock support (HDF5 >= 1.10.7).
Hid file_access_list(const std::string& path) {
  Hid p(H5Pcreate(H5P_FILE_ACCESS));
  if (!p.ok()) fail_file(path, "cannot build a file-access property list");
#if H5_VERSION_GE(1, 10, 7)
  if (H5Pset_file_locking(p.get(), 1, 1) < 0) fail_file(path, "cannot set file locking");
#endif
  return p;
}

// ---------------------------------------------------------------------------------
// Datasets

/// All elements of dataset `ds`, `count` of them, read as `mem_type`.
template <class T>
std::vector<T> read_all(hid_t ds, std::size_t count, hid_t mem_type) {
  std::vector<T> out(count);
  if (!out.empty() && H5Dread(ds, mem_type, H5S_ALL, H5S_ALL, H5P_DEFAULT, out.data()) < 0) {
    fail(ds, "cannot read the dataset");
  }
  return out;
}

/// The number of values `shape` holds; throws if the data holds `count` values instead.
std::size_t checked_total(hid_t loc, const std::string& name, const std::vector<std::size_t>& shape,
                          std::size_t count) {
  const std::size_t total =
      std::accumulate(shape.begin(), shape.end(), std::size_t{1}, std::multiplies<>());
  if (total != count) {
    fail(loc, "shape holds " + std::to_string(total) + " values, data has " +
                  std::to_string(count), name);
  }
  return total;
}

/// A dataspace of `shape` for dataset `name`.
Hid shaped_space(hid_t loc, const std::string& name, const std::vector<std::size_t>& shape) {
  const std::vector<hsize_t> dims(shape.begin(), shape.end());
  Hid space(H5Screate_simple(static_cast<int>(dims.size()), dims.data(), nullptr));
  if (!space.ok()) fail(loc, "cannot create a dataspace", name);
  return space;
}

/// Whether `count` values are written compressed (shuffle + gzip, chunked).
bool compresses(const WriteOptions& options, std::size_t count) {
  return options.gzip_level > 0 && count > options.compress_min_size &&
         H5Zfilter_avail(H5Z_FILTER_DEFLATE) > 0;
}

/// Chunks of a compressed N-D dataset: the largest dimension halved until a chunk holds at
/// most chunk_size values.
std::vector<hsize_t> halved_chunk(const std::vector<hsize_t>& dims, std::size_t chunk_size) {
  std::vector<hsize_t> chunk = dims;
  const hsize_t target = std::max<std::size_t>(chunk_size, 1);
  auto product = [&] {
    return std::accumulate(chunk.begin(), chunk.end(), hsize_t{1}, std::multiplies<>());
  };
  while (product() > target) {
    auto it = std::max_element(chunk.begin(), chunk.end());
    *it = (*it + 1) / 2;
  }
  return chunk;
}

/// Creates dataset `name` of `file_type` under `loc` (and missing groups on the way), then
/// writes `buf` as `mem_type` unless `count` is 0.
Hid create_written(hid_t loc, const std::string& name, hid_t file_type, hid_t space, hid_t dcpl,
                   hid_t mem_type, const void* buf, std::size_t count) {
  Hid lcpl = intermediate_lcpl(loc);
  Hid ds(H5Dcreate2(loc, name.c_str(), file_type, space, lcpl.get(), dcpl, H5P_DEFAULT));
  if (!ds.ok()) fail(loc, "cannot create dataset", name);
  if (count > 0 && H5Dwrite(ds.get(), mem_type, H5S_ALL, H5S_ALL, H5P_DEFAULT, buf) < 0) {
    fail(loc, "cannot write dataset", name);
  }
  return ds;
}

/// Writes a double dataset of `dims` (`count` values); `chunk` non-empty: chunked as
/// `chunk`, shuffled and gzipped at `gzip_level`.
Hid write_double_dataset(hid_t loc, const std::string& name, const double* values, std::size_t count,
                         const std::vector<hsize_t>& dims, const std::vector<hsize_t>& chunk,
                         int gzip_level) {
  const int rank = static_cast<int>(dims.size());
  Hid space(H5Screate_simple(rank, dims.data(), nullptr));
  Hid dcpl(H5Pcreate(H5P_DATASET_CREATE));
  if (!space.ok() || !dcpl.ok()) fail(loc, "cannot prepare dataset", name);
  if (!chunk.empty() &&
      (H5Pset_chunk(dcpl.get(), rank, chunk.data()) < 0 || H5Pset_shuffle(dcpl.get()) < 0 ||
       H5Pset_deflate(dcpl.get(), static_cast<unsigned>(std::min(gzip_level, 9))) < 0)) {
    fail(loc, "cannot set compression", name);
  }
  return create_written(loc, name, H5T_IEEE_F64LE, space.get(), dcpl.get(), H5T_NATIVE_DOUBLE,
                        values, count);
}

}  // namespace
}  // namespace detail

using namespace detail;

// =================================================================================
// Object

Object::Object(Object&& other) noexcept : id_(std::exchange(other.id_, -1)) {}

Object& Object::operator=(Object&& other) noexcept {
  if (this != &other) {
    close_handle();
    id_ = std::exchange(other.id_, -1);
  }
  return *this;
}

Object::~Object() { close_handle(); }

void Object::close_handle() noexcept {
  close_id(id_);
  id_ = -1;
}

std::string Object::path() const { return name_or_empty(id_, object_path_of); }

std::string Object::file_name() const { return name_or_empty(id_, file_name_of); }

// =================================================================================
// Dataset (dimension scales: h5_table.cpp)

std::vector<std::size_t> Dataset::shape() const {
  quiet();
  Hid space(H5Dget_space(id_));
  if (!space.ok()) fail(id_, "cannot get the dataspace");
  const int rank = H5Sget_simple_extent_ndims(space.get());
  if (rank < 0) fail(id_, "cannot get the rank");
  std::vector<hsize_t> dims(static_cast<std::size_t>(rank));
  if (rank > 0 && H5Sget_simple_extent_dims(space.get(), dims.data(), nullptr) < 0) {
    fail(id_, "cannot get the dimensions");
  }
  return std::vector<std::size_t>(dims.begin(), dims.end());
}

std::size_t Dataset::size() const {
  quiet();
  Hid space(H5Dget_space(id_));
  if (!space.ok()) fail(id_, "cannot get the dataspace");
  return npoints(space.get());
}

std::vector<double> Dataset::read_doubles() const {
  quiet();
  Hid type(H5Dget_type(id_));
  const H5T_class_t cls = H5Tget_class(type.get());
  if (cls != H5T_FLOAT && cls != H5T_INTEGER) fail(id_, "not a numeric dataset");
  return read_all<double>(id_, size(), H5T_NATIVE_DOUBLE);
}

std::vector<std::int64_t> Dataset::read_int64s() const {
  quiet();
  Hid type(H5Dget_type(id_));
  if (H5Tget_class(type.get()) != H5T_INTEGER) fail(id_, "not an integer dataset");
  return read_all<std::int64_t>(id_, size(), H5T_NATIVE_INT64);
}

std::vector<std::string> Dataset::read_strings() const {
  quiet();
  return read_dataset_strings(id_, size());
}

std::string Dataset::units() const {
  return has_attribute("units") ? attribute_string("units") : std::string();
}

// =================================================================================
// Group (tables: h5_table.cpp)

bool Group::exists(const std::string& path) const {
  quiet();
  if (path.empty() || path == "/" || path == ".") return true;
  // H5Lexists needs every intermediate link to exist: check prefix by prefix.
  std::size_t pos = path.front() == '/' ? 1 : 0;
  while (pos <= path.size()) {
    std::size_t next = path.find('/', pos);
    if (next == std::string::npos) next = path.size();
    if (next > pos) {
      const std::string prefix = path.substr(0, next);
      const htri_t e = H5Lexists(id_, prefix.c_str(), H5P_DEFAULT);
      if (e <= 0) {  // absent, or an intermediate that is not a group
        H5Eclear2(H5E_DEFAULT);
        return false;
      }
    }
    pos = next + 1;
  }
  return true;
}

Group Group::require_group(const std::string& path) {
  quiet();
  if (exists(path)) return open_group(path);
  Hid lcpl = intermediate_lcpl(id_);
  const hid_t g = H5Gcreate2(id_, path.c_str(), lcpl.get(), H5P_DEFAULT, H5P_DEFAULT);
  if (g < 0) fail(id_, "cannot create group", path);
  return Group(g);
}

Group Group::open_group(const std::string& path) const {
  quiet();
  const hid_t g = H5Gopen2(id_, path.empty() ? "." : path.c_str(), H5P_DEFAULT);
  if (g < 0) fail(id_, "cannot open group", path);
  return Group(g);
}

std::vector<std::string> Group::list() const {
  quiet();
  H5G_info_t info;
  if (H5Gget_info(id_, &info) < 0) fail(id_, "cannot list the group");
  std::vector<std::string> names;
  for (hsize_t i = 0; i < info.nlinks; ++i) {
    const ssize_t n =
        H5Lget_name_by_idx(id_, ".", H5_INDEX_NAME, H5_ITER_INC, i, nullptr, 0, H5P_DEFAULT);
    if (n < 0) fail(id_, "cannot list the group");
    std::string s(static_cast<std::size_t>(n) + 1, '\0');
    H5Lget_name_by_idx(id_, ".", H5_INDEX_NAME, H5_ITER_INC, i, s.data(), s.size(), H5P_DEFAULT);
    s.resize(static_cast<std::size_t>(n));
    names.push_back(std::move(s));
  }
  return names;
}

void Group::copy_to(const std::string& path, Group& to) const {
  quiet();
  Hid lcpl = intermediate_lcpl(to.id_);
  if (H5Ocopy(id_, path.c_str(), to.id_, path.c_str(), H5P_DEFAULT, lcpl.get()) < 0)
    fail(id_, "cannot copy", path);
}

Dataset Group::write_dataset(const std::string& name, const std::vector<double>& values,
                             const std::string& units, const WriteOptions& options) {
  return write_dataset(name, values.data(), values.size(), units, options);
}

Dataset Group::write_dataset(const std::string& name, const double* values, std::size_t count,
                             const std::string& units, const WriteOptions& options) {
  quiet();
  if (count > 0 && values == nullptr) fail(id_, "null data", name);
  if (exists(name)) fail(id_, "already exists", name);
  std::vector<hsize_t> chunk;  // none: contiguous, uncompressed
  if (compresses(options, count)) {
    chunk = {static_cast<hsize_t>(std::min(count, std::max<std::size_t>(options.chunk_size, 1)))};
  }
  Dataset out(write_double_dataset(id_, name, values, count, {static_cast<hsize_t>(count)}, chunk,
                                   options.gzip_level)
                  .release());
  out.set_attribute("units", units);
  return out;
}

Dataset Group::write_dataset(const std::string& name, const std::vector<double>& values,
                             const std::vector<std::size_t>& shape, const std::string& units,
                             const WriteOptions& options) {
  quiet();
  if (shape.empty()) fail(id_, "a dataset needs at least one dimension", name);
  const std::size_t total = checked_total(id_, name, shape, values.size());
  if (exists(name)) fail(id_, "already exists", name);
  const std::vector<hsize_t> dims(shape.begin(), shape.end());
  std::vector<hsize_t> chunk;  // none: contiguous, uncompressed
  if (compresses(options, total)) chunk = halved_chunk(dims, options.chunk_size);
  Dataset out(
      write_double_dataset(id_, name, values.data(), total, dims, chunk, options.gzip_level).release());
  out.set_attribute("units", units);
  return out;
}

Dataset Group::write_dataset(const std::string& name, const std::vector<std::int64_t>& values,
                             const std::string& units) {
  quiet();
  if (exists(name)) fail(id_, "already exists", name);
  Hid space = simple_space(id_, values.size());
  Dataset out(create_written(id_, name, H5T_STD_I64LE, space.get(), H5P_DEFAULT, H5T_NATIVE_INT64,
                             values.data(), values.size())
                  .release());
  out.set_attribute("units", units);
  return out;
}

Dataset Group::write_dataset(const std::string& name, const std::vector<std::int64_t>& values,
                             const std::vector<std::size_t>& shape, const std::string& units) {
  quiet();
  const std::size_t total = checked_total(id_, name, shape, values.size());
  if (exists(name)) fail(id_, "already exists", name);
  Hid space = shaped_space(id_, name, shape);
  Dataset out(create_written(id_, name, H5T_STD_I64LE, space.get(), H5P_DEFAULT, H5T_NATIVE_INT64,
                             values.data(), total)
                  .release());
  if (!units.empty()) out.set_attribute("units", units);
  return out;
}

Dataset Group::write_strings(const std::string& name, const std::vector<std::string>& values,
                             const std::vector<std::size_t>& shape_in) {
  quiet();
  const std::vector<std::size_t> shape =
      shape_in.empty() ? std::vector<std::size_t>{values.size()} : shape_in;
  const std::size_t total = checked_total(id_, name, shape, values.size());
  if (exists(name)) fail(id_, "already exists", name);
  Hid space = shaped_space(id_, name, shape);
  Hid type = vlen_string_type(id_);
  std::vector<const char*> p;
  p.reserve(values.size());
  for (const std::string& v : values) p.push_back(v.c_str());
  return Dataset(
      create_written(id_, name, type.get(), space.get(), H5P_DEFAULT, type.get(), p.data(), total)
          .release());
}

Dataset Group::open_dataset(const std::string& path) const {
  quiet();
  const hid_t d = H5Dopen2(id_, path.c_str(), H5P_DEFAULT);
  if (d < 0) fail(id_, "cannot open dataset", path);
  return Dataset(d);
}

// =================================================================================
// File

File File::create(const std::string& path) {
  quiet();
  Hid fapl = file_access_list(path);
  const hid_t f = H5Fcreate(path.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, fapl.get());
  if (f < 0) fail_file(path, "cannot create the file");
  return File(f, path);
}

File File::open(const std::string& path, Mode mode) {
  quiet();
  Hid fapl = file_access_list(path);
  const unsigned flags = mode == Mode::ReadWrite ? H5F_ACC_RDWR : H5F_ACC_RDONLY;
  const hid_t f = H5Fopen(path.c_str(), flags, fapl.get());
  if (f < 0) {
    fail_file(path, mode == Mode::ReadWrite ? "cannot open the file read-write"
                                            : "cannot open the file read-only");
  }
  return File(f, path);
}

void File::flush() {
  quiet();
  if (H5Fflush(id_, H5F_SCOPE_LOCAL) < 0) fail(id_, "cannot flush the file");
}

void File::close() {
  if (id_ < 0) return;
  quiet();
  const hid_t f = std::exchange(id_, -1);
  if (H5Fclose(f) < 0) fail_file(filename_, "cannot close the file");
}

}  // namespace lub::h5
