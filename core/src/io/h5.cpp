// The RAII layer over the HDF5 C API (files, groups, datasets, attributes): see
// lub/io/h5.hpp. Tables and dimension scales are in h5_table.cpp.
#include "lub/io/h5.hpp"

#include <hdf5.h>

#include <algorithm>
#include <cstring>
#include <numeric>
#include <utility>

#include "io/h5_detail.hpp"

namespace lub::h5 {
namespace detail {

// ---------------------------------------------------------------------------------
// Errors

void quiet() {
  thread_local bool done = false;
  if (!done) {
    H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr);
    done = true;
  }
}

namespace {

herr_t collect_error(unsigned /*n*/, const H5E_error2_t* err, void* data) {
  auto* out = static_cast<std::string*>(data);
  if (!out->empty()) *out += "; ";
  if (err->func_name != nullptr) *out += std::string(err->func_name) + "(): ";
  if (err->desc != nullptr) {
    std::string desc = err->desc;
    std::replace(desc.begin(), desc.end(), '\n', ' ');  // H5F_open embeds ctime()
    *out += desc;
  }
  char minor[160] = "";
  if (H5Eget_msg(err->min_num, nullptr, minor, sizeof minor) > 0) {
    *out += std::string(" [") + minor + "]";
  }
  return 0;
}

/// HDF5's current error stack as one line (outermost call first); clears it.
std::string take_error_stack() {
  std::string out;
  H5Ewalk2(H5E_DEFAULT, H5E_WALK_DOWNWARD, collect_error, &out);
  H5Eclear2(H5E_DEFAULT);
  return out;
}

/// A name HDF5 returns through the two-call protocol of H5Fget_name / H5Iget_name.
std::string name_of(hid_t id, ssize_t (*get_name)(hid_t, char*, std::size_t)) {
  const ssize_t n = get_name(id, nullptr, 0);
  if (n <= 0) return "?";
  std::string s(static_cast<std::size_t>(n) + 1, '\0');
  get_name(id, s.data(), s.size());
  s.resize(static_cast<std::size_t>(n));
  return s;
}

std::string file_name_of(hid_t id) { return name_of(id, H5Fget_name); }
std::string object_path_of(hid_t id) { return name_of(id, H5Iget_name); }

/// `get(id)` for an open id ("" for a closed one), leaving no HDF5 error behind.
std::string name_or_empty(hid_t id, std::string (*get)(hid_t)) {
  if (id < 0) return "";
  quiet();
  std::string name = get(id);
  H5Eclear2(H5E_DEFAULT);
  return name;
}

std::string join_path(const std::string& base, const std::string& name) {
  if (name.empty()) return base;
  if (name.front() == '/') return name;
  if (base.empty() || base.back() == '/') return base + name;
  return base + "/" + name;
}

/// "file.h5:/group/object[/child]" for an open id (for messages).
std::string describe(hid_t id, const std::string& child = "") {
  if (id < 0) return "(closed object)";
  std::string d = file_name_of(id) + ":" + join_path(object_path_of(id), child);
  H5Eclear2(H5E_DEFAULT);
  return d;
}

[[noreturn]] void fail_stack(const std::string& where, const std::string& what,
                             const std::string& stack) {
  std::string msg = "lub::h5: " + where + ": " + what;
  if (!stack.empty()) msg += " (HDF5: " + stack + ")";
  throw std::runtime_error(msg);
}

}  // namespace

void fail(hid_t loc, const std::string& what, const std::string& name) {
  const std::string stack = take_error_stack();  // before any other HDF5 call
  fail_stack(describe(loc, name), what, stack);
}

void fail_file(const std::string& path, const std::string& what) {
  const std::string stack = take_error_stack();
  fail_stack("'" + path + "'", what, stack);
}

void close_id(hid_t id) noexcept {
  if (id < 0) return;
  switch (H5Iget_type(id)) {
    case H5I_FILE: H5Fclose(id); break;
    case H5I_GROUP: H5Gclose(id); break;
    case H5I_DATASET: H5Dclose(id); break;
    case H5I_ATTR: H5Aclose(id); break;
    case H5I_DATATYPE: H5Tclose(id); break;
    case H5I_DATASPACE: H5Sclose(id); break;
    case H5I_GENPROP_LST: H5Pclose(id); break;
    default: H5Idec_ref(id); break;
  }
  H5Eclear2(H5E_DEFAULT);
}

// ---------------------------------------------------------------------------------
// Types and row transfers

namespace {

/// Variable-length string type of character set `cset`.
Hid vlen_string_type(hid_t err_loc, H5T_cset_t cset) {
  Hid t(H5Tcopy(H5T_C_S1));
  if (!t.ok() || H5Tset_size(t.get(), H5T_VARIABLE) < 0 || H5Tset_cset(t.get(), cset) < 0) {
    fail(err_loc, "cannot build the string type");
  }
  return t;
}

void reclaim_vlen(hid_t mem_type, hid_t space, void* buf) {
#if H5_VERSION_GE(1, 12, 0)
  H5Treclaim(mem_type, space, H5P_DEFAULT, buf);
#else
  H5Dvlen_reclaim(mem_type, space, H5P_DEFAULT, buf);
#endif
}

std::size_t npoints(hid_t space) {
  const hssize_t n = H5Sget_simple_extent_npoints(space);
  return n < 0 ? 0 : static_cast<std::size_t>(n);
}

/// `n` fixed-length strings of `size` bytes each, NUL-terminated or padded (trailing
/// spaces dropped too if `space_padded`).
std::vector<std::string> split_fixed_strings(const char* buf, std::size_t n, std::size_t size,
                                             bool space_padded) {
  std::vector<std::string> out;
  out.reserve(n);
  for (std::size_t i = 0; i < n; ++i) {
    const char* p = buf + i * size;
    std::size_t len = 0;
    while (len < size && p[len] != '\0') ++len;
    if (space_padded) {
      while (len > 0 && p[len - 1] == ' ') --len;
    }
    out.emplace_back(p, len);
  }
  return out;
}

/// Reads `count` elements: the first `count` of a 1-D dataset, or all of an N-D one.
void read_rows_or_all(hid_t ds, hid_t mem_type, std::size_t count, void* buf) {
  Hid space(H5Dget_space(ds));
  if (H5Sget_simple_extent_ndims(space.get()) == 1) {
    read_rows(ds, mem_type, count, buf);
  } else if (H5Dread(ds, mem_type, H5S_ALL, H5S_ALL, H5P_DEFAULT, buf) < 0) {
    fail(ds, "cannot read the dataset");
  }
}

}  // namespace

Hid vlen_string_type(hid_t err_loc) { return vlen_string_type(err_loc, H5T_CSET_UTF8); }

bool select_rows(hid_t ds, hsize_t start, hsize_t count, Hid& file_space, Hid& mem_space) {
  file_space = Hid(H5Dget_space(ds));
  const hsize_t offset[1] = {start};
  const hsize_t n[1] = {count};
  mem_space = Hid(H5Screate_simple(1, n, nullptr));
  return file_space.ok() && mem_space.ok() &&
         H5Sselect_hyperslab(file_space.get(), H5S_SELECT_SET, offset, nullptr, n, nullptr) >= 0;
}

void read_rows(hid_t ds, hid_t mem_type, hsize_t count, void* buf) {
  if (count == 0) return;
  Hid fspace, mspace;
  if (!select_rows(ds, 0, count, fspace, mspace) ||
      H5Dread(ds, mem_type, mspace.get(), fspace.get(), H5P_DEFAULT, buf) < 0) {
    fail(ds, "cannot read " + std::to_string(count) + " rows");
  }
}

std::vector<std::string> read_dataset_strings(hid_t ds, std::size_t limit) {
  Hid type(H5Dget_type(ds));
  if (!type.ok() || H5Tget_class(type.get()) != H5T_STRING) fail(ds, "not a string dataset");
  Hid space(H5Dget_space(ds));
  const std::size_t n = std::min(npoints(space.get()), limit);
  std::vector<std::string> out;
  if (n == 0) return out;
  if (H5Tis_variable_str(type.get()) > 0) {
    out.reserve(n);
    Hid mem = vlen_string_type(ds);
    std::vector<char*> buf(n, nullptr);
    read_rows_or_all(ds, mem.get(), n, buf.data());
    for (char* p : buf) out.emplace_back(p != nullptr ? p : "");
    const hsize_t dims[1] = {n};
    Hid mspace(H5Screate_simple(1, dims, nullptr));
    reclaim_vlen(mem.get(), mspace.get(), buf.data());
    return out;
  }
  const std::size_t size = H5Tget_size(type.get());
  Hid mem(H5Tcopy(type.get()));
  std::vector<char> buf(n * size + 1, '\0');
  read_rows_or_all(ds, mem.get(), n, buf.data());
  return split_fixed_strings(buf.data(), n, size, false);
}

namespace {

// ---------------------------------------------------------------------------------
// Property lists and dataspaces

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

Hid simple_space(hid_t err_loc, std::size_t n) {
  const hsize_t dims[1] = {static_cast<hsize_t>(n)};
  Hid s(H5Screate_simple(1, dims, nullptr));
  if (!s.ok()) fail(err_loc, "cannot create a dataspace");
  return s;
}

Hid scalar_space(hid_t err_loc) {
  Hid s(H5Screate(H5S_SCALAR));
  if (!s.ok()) fail(err_loc, "cannot create a dataspace");
  return s;
}

// ---------------------------------------------------------------------------------
// Attributes

/// Open attribute `name` of `obj`, with its type and space.
struct OpenAttr {
  Hid attr, type, space;
};

OpenAttr open_attribute(hid_t obj, const std::string& name) {
  quiet();
  const htri_t e = H5Aexists(obj, name.c_str());
  if (e < 0) fail(obj, "cannot query attribute '" + name + "'");
  if (e == 0) fail(obj, "no attribute '" + name + "'");
  OpenAttr a{Hid(H5Aopen(obj, name.c_str(), H5P_DEFAULT)), Hid(), Hid()};
  if (!a.attr.ok()) fail(obj, "cannot open attribute '" + name + "'");
  a.type = Hid(H5Aget_type(a.attr.get()));
  a.space = Hid(H5Aget_space(a.attr.get()));
  if (!a.type.ok() || !a.space.ok()) fail(obj, "cannot inspect attribute '" + name + "'");
  return a;
}

/// Create attribute `name` (deleting an existing one) and write `buf` as `mem_type`.
void write_attribute(hid_t obj, const std::string& name, hid_t file_type, hid_t mem_type,
                     hid_t space, const void* buf) {
  quiet();
  const htri_t e = H5Aexists(obj, name.c_str());
  if (e < 0) fail(obj, "cannot query attribute '" + name + "'");
  if (e > 0 && H5Adelete(obj, name.c_str()) < 0) {
    fail(obj, "cannot replace attribute '" + name + "'");
  }
  Hid a(H5Acreate2(obj, name.c_str(), file_type, space, H5P_DEFAULT, H5P_DEFAULT));
  if (!a.ok()) fail(obj, "cannot create attribute '" + name + "'");
  if (H5Awrite(a.get(), mem_type, buf) < 0) fail(obj, "cannot write attribute '" + name + "'");
}

/// Read all strings of an attribute (variable- or fixed-length).
std::vector<std::string> read_attribute_strings(hid_t obj, const std::string& name) {
  OpenAttr a = open_attribute(obj, name);
  if (H5Tget_class(a.type.get()) != H5T_STRING) {
    fail(obj, "attribute '" + name + "' is not a string");
  }
  const std::size_t n = npoints(a.space.get());
  std::vector<std::string> out;
  if (n == 0) return out;
  const htri_t is_vlen = H5Tis_variable_str(a.type.get());
  if (is_vlen < 0) fail(obj, "cannot inspect attribute '" + name + "'");
  if (is_vlen > 0) {
    out.reserve(n);
    Hid mem = vlen_string_type(obj, H5Tget_cset(a.type.get()));
    std::vector<char*> buf(n, nullptr);
    if (H5Aread(a.attr.get(), mem.get(), buf.data()) < 0) {
      fail(obj, "cannot read attribute '" + name + "'");
    }
    for (char* p : buf) out.emplace_back(p != nullptr ? p : "");
    reclaim_vlen(mem.get(), a.space.get(), buf.data());
    return out;
  }
  const std::size_t size = H5Tget_size(a.type.get());
  Hid mem(H5Tcopy(a.type.get()));
  if (!mem.ok()) fail(obj, "cannot copy the string type");
  std::vector<char> buf(n * size + 1, '\0');
  if (H5Aread(a.attr.get(), mem.get(), buf.data()) < 0) {
    fail(obj, "cannot read attribute '" + name + "'");
  }
  const bool space_padded = H5Tget_strpad(a.type.get()) == H5T_STR_SPACEPAD;
  return split_fixed_strings(buf.data(), n, size, space_padded);
}

template <class T>
std::vector<T> read_attribute_numbers(hid_t obj, const std::string& name, hid_t mem_type,
                                      bool integer_only) {
  OpenAttr a = open_attribute(obj, name);
  const H5T_class_t cls = H5Tget_class(a.type.get());
  if (cls != H5T_INTEGER && (integer_only || cls != H5T_FLOAT)) {
    fail(obj, std::string("attribute '") + name + "' is not " +
                  (integer_only ? "an integer" : "a number"));
  }
  std::vector<T> out(npoints(a.space.get()));
  if (!out.empty() && H5Aread(a.attr.get(), mem_type, out.data()) < 0) {
    fail(obj, "cannot read attribute '" + name + "'");
  }
  return out;
}

/// The one element of attribute `name`'s `values` (`things`: "values", "strings").
template <class T>
T only_element(hid_t obj, const std::string& name, std::vector<T> values, const char* things) {
  if (values.size() != 1) {
    fail(obj, "attribute '" + name + "' holds " + std::to_string(values.size()) + " " + things +
                  ", expected one");
  }
  return std::move(values.front());
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

bool Object::has_attribute(const std::string& name) const {
  quiet();
  const htri_t e = H5Aexists(id_, name.c_str());
  if (e < 0) fail(id_, "cannot query attribute '" + name + "'");
  return e > 0;
}

void Object::set_attribute(const std::string& name, const std::string& value) {
  quiet();
  Hid type = vlen_string_type(id_);
  Hid space = scalar_space(id_);
  const char* p = value.c_str();
  write_attribute(id_, name, type.get(), type.get(), space.get(), &p);
}

void Object::set_attribute(const std::string& name, const char* value) {
  set_attribute(name, std::string(value != nullptr ? value : ""));
}

void Object::set_attribute(const std::string& name, double value) {
  quiet();
  Hid space = scalar_space(id_);
  write_attribute(id_, name, H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, space.get(), &value);
}

void Object::set_attribute_int64(const std::string& name, std::int64_t value) {
  quiet();
  Hid space = scalar_space(id_);
  write_attribute(id_, name, H5T_STD_I64LE, H5T_NATIVE_INT64, space.get(), &value);
}

void Object::set_attribute(const std::string& name, const std::vector<double>& values) {
  quiet();
  Hid space = simple_space(id_, values.size());
  const double dummy = 0.0;
  write_attribute(id_, name, H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, space.get(),
                  values.empty() ? &dummy : values.data());
}

void Object::set_attribute(const std::string& name, const std::vector<std::string>& values) {
  quiet();
  Hid type = vlen_string_type(id_);
  Hid space = simple_space(id_, values.size());
  std::vector<const char*> ptrs;
  ptrs.reserve(values.size() + 1);
  for (const std::string& v : values) ptrs.push_back(v.c_str());
  ptrs.push_back(nullptr);  // keeps data() non-null for an empty array
  write_attribute(id_, name, type.get(), type.get(), space.get(), ptrs.data());
}

void Object::remove_attribute(const std::string& name) {
  quiet();
  if (H5Adelete(id_, name.c_str()) < 0) fail(id_, "cannot delete attribute '" + name + "'");
}

std::string Object::attribute_string(const std::string& name) const {
  return only_element(id_, name, read_attribute_strings(id_, name), "strings");
}

std::vector<std::string> Object::attribute_strings(const std::string& name) const {
  return read_attribute_strings(id_, name);
}

double Object::attribute_double(const std::string& name) const {
  return only_element(id_, name, attribute_doubles(name), "values");
}

std::vector<double> Object::attribute_doubles(const std::string& name) const {
  return read_attribute_numbers<double>(id_, name, H5T_NATIVE_DOUBLE, false);
}

std::int64_t Object::attribute_int64(const std::string& name) const {
  return only_element(id_, name,
                      read_attribute_numbers<std::int64_t>(id_, name, H5T_NATIVE_INT64, true),
                      "values");
}

std::vector<std::string> Object::attribute_names() const {
  quiet();
  std::vector<std::string> names;
  auto collect = [](hid_t, const char* name, const H5A_info_t*, void* data) -> herr_t {
    static_cast<std::vector<std::string>*>(data)->emplace_back(name);
    return 0;
  };
  hsize_t idx = 0;
  if (H5Aiterate2(id_, H5_INDEX_NAME, H5_ITER_INC, &idx, collect, &names) < 0) {
    fail(id_, "cannot list attributes");
  }
  return names;
}

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
