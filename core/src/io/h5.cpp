// RAII layer over the HDF5 C API: see lub/io/h5.hpp.
#include "lub/io/h5.hpp"

#include <hdf5.h>
#include <hdf5_hl.h>

#include <algorithm>
#include <cstring>
#include <numeric>
#include <utility>

static_assert(std::is_same_v<hid_t, lub::h5::Id>, "lub::h5::Id must be hid_t (HDF5 >= 1.10)");

namespace lub::h5 {
namespace {

// ---------------------------------------------------------------------------------
// Errors

/// Switch off HDF5's automatic error printing (per thread in thread-safe builds).
void quiet() {
  thread_local bool done = false;
  if (!done) {
    H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr);
    done = true;
  }
}

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

std::string file_name_of(hid_t id) {
  const ssize_t n = H5Fget_name(id, nullptr, 0);
  if (n <= 0) return "?";
  std::string s(static_cast<std::size_t>(n) + 1, '\0');
  H5Fget_name(id, s.data(), s.size());
  s.resize(static_cast<std::size_t>(n));
  return s;
}

std::string object_path_of(hid_t id) {
  const ssize_t n = H5Iget_name(id, nullptr, 0);
  if (n <= 0) return "?";
  std::string s(static_cast<std::size_t>(n) + 1, '\0');
  H5Iget_name(id, s.data(), s.size());
  s.resize(static_cast<std::size_t>(n));
  return s;
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

/// Throw for a failure at object `loc` (optionally naming a child `name`).
[[noreturn]] void fail(hid_t loc, const std::string& what, const std::string& name = "") {
  const std::string stack = take_error_stack();  // before any other HDF5 call
  fail_stack(describe(loc, name), what, stack);
}

/// Throw for a failure on a file path (no open id).
[[noreturn]] void fail_file(const std::string& path, const std::string& what) {
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

/// Owner of a temporary id inside this file.
class Hid {
 public:
  explicit Hid(hid_t id = -1) : id_(id) {}
  Hid(const Hid&) = delete;
  Hid& operator=(const Hid&) = delete;
  Hid(Hid&& o) noexcept : id_(std::exchange(o.id_, -1)) {}
  Hid& operator=(Hid&& o) noexcept {
    if (this != &o) {
      close_id(id_);
      id_ = std::exchange(o.id_, -1);
    }
    return *this;
  }
  ~Hid() { close_id(id_); }
  hid_t get() const { return id_; }
  hid_t release() { return std::exchange(id_, -1); }
  bool ok() const { return id_ >= 0; }

 private:
  hid_t id_;
};

void reclaim_vlen(hid_t mem_type, hid_t space, void* buf) {
#if H5_VERSION_GE(1, 12, 0)
  H5Treclaim(mem_type, space, H5P_DEFAULT, buf);
#else
  H5Dvlen_reclaim(mem_type, space, H5P_DEFAULT, buf);
#endif
}

// ---------------------------------------------------------------------------------
// Types and property lists

/// Variable-length UTF-8 string type.
Hid vlen_string_type(hid_t err_loc) {
  Hid t(H5Tcopy(H5T_C_S1));
  if (!t.ok() || H5Tset_size(t.get(), H5T_VARIABLE) < 0 ||
      H5Tset_cset(t.get(), H5T_CSET_UTF8) < 0) {
    fail(err_loc, "cannot build the string type");
  }
  return t;
}

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

std::size_t npoints(hid_t space) {
  const hssize_t n = H5Sget_simple_extent_npoints(space);
  return n < 0 ? 0 : static_cast<std::size_t>(n);
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

Hid simple_space(hid_t err_loc, std::size_t n) {
  const hsize_t dims[1] = {static_cast<hsize_t>(n)};
  Hid s(H5Screate_simple(1, dims, nullptr));
  if (!s.ok()) fail(err_loc, "cannot create a dataspace");
  return s;
}

/// Read all strings of an attribute (variable- or fixed-length).
std::vector<std::string> read_attribute_strings(hid_t obj, const std::string& name) {
  OpenAttr a = open_attribute(obj, name);
  if (H5Tget_class(a.type.get()) != H5T_STRING) {
    fail(obj, "attribute '" + name + "' is not a string");
  }
  const std::size_t n = npoints(a.space.get());
  std::vector<std::string> out;
  out.reserve(n);
  if (n == 0) return out;
  const htri_t is_vlen = H5Tis_variable_str(a.type.get());
  if (is_vlen < 0) fail(obj, "cannot inspect attribute '" + name + "'");
  if (is_vlen > 0) {
    Hid mem(H5Tcopy(H5T_C_S1));
    if (!mem.ok() || H5Tset_size(mem.get(), H5T_VARIABLE) < 0 ||
        H5Tset_cset(mem.get(), H5Tget_cset(a.type.get())) < 0) {
      fail(obj, "cannot build the string type");
    }
    std::vector<char*> buf(n, nullptr);
    if (H5Aread(a.attr.get(), mem.get(), buf.data()) < 0) {
      fail(obj, "cannot read attribute '" + name + "'");
    }
    for (char* p : buf) out.emplace_back(p != nullptr ? p : "");
    reclaim_vlen(mem.get(), a.space.get(), buf.data());
  } else {
    const std::size_t size = H5Tget_size(a.type.get());
    Hid mem(H5Tcopy(a.type.get()));
    if (!mem.ok()) fail(obj, "cannot copy the string type");
    std::vector<char> buf(n * size + 1, '\0');
    if (H5Aread(a.attr.get(), mem.get(), buf.data()) < 0) {
      fail(obj, "cannot read attribute '" + name + "'");
    }
    const bool space_pad = H5Tget_strpad(a.type.get()) == H5T_STR_SPACEPAD;
    for (std::size_t i = 0; i < n; ++i) {
      const char* p = buf.data() + i * size;
      std::size_t len = 0;
      while (len < size && p[len] != '\0') ++len;
      if (space_pad) {
        while (len > 0 && p[len - 1] == ' ') --len;
      }
      out.emplace_back(p, len);
    }
  }
  return out;
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

// ---------------------------------------------------------------------------------
// Tables

const char* type_name(ColumnType t) {
  switch (t) {
    case ColumnType::Float64: return "float64";
    case ColumnType::Int64: return "int64";
    case ColumnType::String: return "string";
  }
  return "?";
}

void validate_columns(hid_t err_loc, const std::string& name, const std::vector<Column>& cols) {
  if (cols.empty()) fail(err_loc, "a table needs at least one column", name);
  for (std::size_t i = 0; i < cols.size(); ++i) {
    if (cols[i].name.empty()) fail(err_loc, "column " + std::to_string(i) + " has no name", name);
    if (cols[i].name.find('/') != std::string::npos) {
      fail(err_loc, "column '" + cols[i].name + "': a name without '/'", name);
    }
    for (std::size_t j = 0; j < i; ++j) {
      if (cols[j].name == cols[i].name) {
        fail(err_loc, "duplicate column '" + cols[i].name + "'", name);
      }
    }
  }
}

/// File type of a column (a new id the caller owns).
Hid column_file_type(hid_t err_loc, ColumnType t) {
  if (t == ColumnType::String) return vlen_string_type(err_loc);
  return Hid(H5Tcopy(t == ColumnType::Float64 ? H5T_IEEE_F64LE : H5T_STD_I64LE));
}

/// Memory type for a column of type t read/written as `t`.
Hid column_mem_type(hid_t err_loc, ColumnType t) {
  if (t == ColumnType::String) return vlen_string_type(err_loc);
  return Hid(H5Tcopy(t == ColumnType::Float64 ? H5T_NATIVE_DOUBLE : H5T_NATIVE_INT64));
}

/// Writes `count` elements of `buf` (as `mem_type`) to a 1-D extendible dataset at
/// [start, start + count), extending it to exactly start + count.
void write_rows(hid_t ds, hid_t mem_type, hsize_t start, hsize_t count, const void* buf) {
  const hsize_t new_dims[1] = {start + count};
  if (H5Dset_extent(ds, new_dims) < 0) fail(ds, "cannot extend the column");
  if (count == 0) return;
  Hid fspace(H5Dget_space(ds));
  const hsize_t offset[1] = {start};
  const hsize_t n[1] = {count};
  Hid mspace(H5Screate_simple(1, n, nullptr));
  if (!fspace.ok() || !mspace.ok() ||
      H5Sselect_hyperslab(fspace.get(), H5S_SELECT_SET, offset, nullptr, n, nullptr) < 0 ||
      H5Dwrite(ds, mem_type, mspace.get(), fspace.get(), H5P_DEFAULT, buf) < 0) {
    fail(ds, "cannot write " + std::to_string(count) + " rows");
  }
}

/// Reads the first `count` elements of a 1-D dataset into `buf` as `mem_type`.
void read_rows(hid_t ds, hid_t mem_type, hsize_t count, void* buf) {
  if (count == 0) return;
  Hid fspace(H5Dget_space(ds));
  const hsize_t offset[1] = {0};
  const hsize_t n[1] = {count};
  Hid mspace(H5Screate_simple(1, n, nullptr));
  if (!fspace.ok() || !mspace.ok() ||
      H5Sselect_hyperslab(fspace.get(), H5S_SELECT_SET, offset, nullptr, n, nullptr) < 0 ||
      H5Dread(ds, mem_type, mspace.get(), fspace.get(), H5P_DEFAULT, buf) < 0) {
    fail(ds, "cannot read " + std::to_string(count) + " rows");
  }
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

/// Reads every element of a string dataset (variable- or fixed-length).
std::vector<std::string> read_dataset_strings(hid_t ds, std::size_t limit) {
  Hid type(H5Dget_type(ds));
  if (!type.ok() || H5Tget_class(type.get()) != H5T_STRING) fail(ds, "not a string dataset");
  Hid space(H5Dget_space(ds));
  const std::size_t n = std::min(npoints(space.get()), limit);
  std::vector<std::string> out;
  if (n == 0) return out;
  out.reserve(n);
  if (H5Tis_variable_str(type.get()) > 0) {
    Hid mem = vlen_string_type(ds);
    std::vector<char*> buf(n, nullptr);
    read_rows_or_all(ds, mem.get(), n, buf.data());
    for (char* p : buf) out.emplace_back(p != nullptr ? p : "");
    const hsize_t dims[1] = {n};
    Hid mspace(H5Screate_simple(1, dims, nullptr));
    reclaim_vlen(mem.get(), mspace.get(), buf.data());
  } else {
    const std::size_t size = H5Tget_size(type.get());
    Hid mem(H5Tcopy(type.get()));
    std::vector<char> buf(n * size + 1, '\0');
    read_rows_or_all(ds, mem.get(), n, buf.data());
    for (std::size_t i = 0; i < n; ++i) {
      const char* p = buf.data() + i * size;
      std::size_t len = 0;
      while (len < size && p[len] != '\0') ++len;
      out.emplace_back(p, len);
    }
  }
  return out;
}

}  // namespace

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

std::string Object::path() const {
  if (id_ < 0) return "";
  quiet();
  std::string p = object_path_of(id_);
  H5Eclear2(H5E_DEFAULT);
  return p;
}

std::string Object::file_name() const {
  if (id_ < 0) return "";
  quiet();
  std::string p = file_name_of(id_);
  H5Eclear2(H5E_DEFAULT);
  return p;
}

bool Object::has_attribute(const std::string& name) const {
  quiet();
  const htri_t e = H5Aexists(id_, name.c_str());
  if (e < 0) fail(id_, "cannot query attribute '" + name + "'");
  return e > 0;
}

void Object::set_attribute(const std::string& name, const std::string& value) {
  quiet();
  Hid type = vlen_string_type(id_);
  Hid space(H5Screate(H5S_SCALAR));
  if (!space.ok()) fail(id_, "cannot create a dataspace");
  const char* p = value.c_str();
  write_attribute(id_, name, type.get(), type.get(), space.get(), &p);
}

void Object::set_attribute(const std::string& name, const char* value) {
  set_attribute(name, std::string(value != nullptr ? value : ""));
}

void Object::set_attribute(const std::string& name, double value) {
  quiet();
  Hid space(H5Screate(H5S_SCALAR));
  if (!space.ok()) fail(id_, "cannot create a dataspace");
  write_attribute(id_, name, H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, space.get(), &value);
}

void Object::set_attribute_int64(const std::string& name, std::int64_t value) {
  quiet();
  Hid space(H5Screate(H5S_SCALAR));
  if (!space.ok()) fail(id_, "cannot create a dataspace");
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
  std::vector<std::string> v = read_attribute_strings(id_, name);
  if (v.size() != 1) {
    fail(id_, "attribute '" + name + "' holds " + std::to_string(v.size()) +
                  " strings, expected one");
  }
  return std::move(v.front());
}

std::vector<std::string> Object::attribute_strings(const std::string& name) const {
  return read_attribute_strings(id_, name);
}

double Object::attribute_double(const std::string& name) const {
  const std::vector<double> v = read_attribute_numbers<double>(id_, name, H5T_NATIVE_DOUBLE, false);
  if (v.size() != 1) {
    fail(id_, "attribute '" + name + "' holds " + std::to_string(v.size()) +
                  " values, expected one");
  }
  return v.front();
}

std::vector<double> Object::attribute_doubles(const std::string& name) const {
  return read_attribute_numbers<double>(id_, name, H5T_NATIVE_DOUBLE, false);
}

std::int64_t Object::attribute_int64(const std::string& name) const {
  const std::vector<std::int64_t> v =
      read_attribute_numbers<std::int64_t>(id_, name, H5T_NATIVE_INT64, true);
  if (v.size() != 1) {
    fail(id_, "attribute '" + name + "' holds " + std::to_string(v.size()) +
                  " values, expected one");
  }
  return v.front();
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
// Dataset

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
  std::vector<double> out(size());
  if (!out.empty() &&
      H5Dread(id_, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, out.data()) < 0) {
    fail(id_, "cannot read the dataset");
  }
  return out;
}

std::vector<std::int64_t> Dataset::read_int64s() const {
  quiet();
  Hid type(H5Dget_type(id_));
  if (H5Tget_class(type.get()) != H5T_INTEGER) fail(id_, "not an integer dataset");
  std::vector<std::int64_t> out(size());
  if (!out.empty() &&
      H5Dread(id_, H5T_NATIVE_INT64, H5S_ALL, H5S_ALL, H5P_DEFAULT, out.data()) < 0) {
    fail(id_, "cannot read the dataset");
  }
  return out;
}

std::vector<std::string> Dataset::read_strings() const {
  quiet();
  return read_dataset_strings(id_, size());
}

std::string Dataset::units() const {
  return has_attribute("units") ? attribute_string("units") : std::string();
}

void Dataset::make_scale(const std::string& name) {
  quiet();
  if (H5DSset_scale(id_, name.empty() ? nullptr : name.c_str()) < 0) {
    fail(id_, "cannot make a dimension scale");
  }
}

bool Dataset::is_scale() const {
  quiet();
  const htri_t s = H5DSis_scale(id_);
  if (s < 0) fail(id_, "cannot query dimension-scale status");
  return s > 0;
}

void Dataset::attach_scale(Dataset& scale, unsigned dim, const std::string& label) {
  quiet();
  const std::size_t rank = shape().size();
  if (dim >= rank) {
    fail(id_, "dimension " + std::to_string(dim) + " out of range (rank " +
                  std::to_string(rank) + ")");
  }
  if (scale.shape().size() != 1) fail(scale.id(), "a dimension scale must be 1-D");
  if (!scale.is_scale()) scale.make_scale();
  if (H5DSattach_scale(id_, scale.id(), dim) < 0) {
    fail(id_, "cannot attach dimension scale " + scale.path() + " to dimension " +
                  std::to_string(dim));
  }
  if (!label.empty() && H5DSset_label(id_, dim, label.c_str()) < 0) {
    fail(id_, "cannot label dimension " + std::to_string(dim));
  }
}

// =================================================================================
// Table

std::size_t Table::column_index(const std::string& name) const {
  for (std::size_t i = 0; i < columns_.size(); ++i) {
    if (columns_[i].name == name) return i;
  }
  quiet();
  fail(id_, "no column '" + name + "'");
}

bool Table::has_column(const std::string& name) const {
  return std::any_of(columns_.begin(), columns_.end(),
                     [&](const Column& c) { return c.name == name; });
}

Dataset Table::column(const std::string& name) const {
  column_index(name);
  return open_dataset(name);
}

std::size_t Table::rows() const {
  if (columns_.empty()) return 0;
  return open_dataset(columns_.front().name).size();
}

void Table::append(const std::vector<Row>& rows) {
  quiet();
  const std::size_t ncol = columns_.size();
  const std::size_t k = rows.size();
  if (k > 0) {
    // Validate every row first, so a bad row appends nothing.
    for (std::size_t r = 0; r < k; ++r) {
      const Row& row = rows[r];
      if (row.size() != ncol) {
        fail(id_, "row " + std::to_string(r) + " has " + std::to_string(row.size()) +
                      " cells, the table has " + std::to_string(ncol) + " columns");
      }
      for (std::size_t c = 0; c < ncol; ++c) {
        const Cell& cell = row[c];
        const ColumnType t = columns_[c].type;
        const bool fits = (t == ColumnType::Float64 && !std::holds_alternative<std::string>(cell)) ||
                          (t == ColumnType::Int64 && std::holds_alternative<std::int64_t>(cell)) ||
                          (t == ColumnType::String && std::holds_alternative<std::string>(cell));
        if (!fits) {
          static const char* const cell_names[] = {"double", "int64", "string"};
          fail(id_, "row " + std::to_string(r) + ", column '" + columns_[c].name + "' (" +
                        type_name(t) + "): got a " + cell_names[cell.index()] + " cell");
        }
      }
    }
    const hsize_t old_rows = static_cast<hsize_t>(this->rows());
    // The dimension column (0) last: it defines the table's length.
    for (std::size_t step = 1; step <= ncol; ++step) {
      const std::size_t c = step % ncol;
      const Column& col = columns_[c];
      Hid ds(H5Dopen2(id_, col.name.c_str(), H5P_DEFAULT));
      if (!ds.ok()) fail(id_, "cannot open column", col.name);
      Hid mem = column_mem_type(id_, col.type);
      if (col.type == ColumnType::Float64) {
        std::vector<double> v(k);
        for (std::size_t r = 0; r < k; ++r) {
          const Cell& cell = rows[r][c];
          v[r] = std::holds_alternative<double>(cell)
                     ? std::get<double>(cell)
                     : static_cast<double>(std::get<std::int64_t>(cell));
        }
        write_rows(ds.get(), mem.get(), old_rows, k, v.data());
      } else if (col.type == ColumnType::Int64) {
        std::vector<std::int64_t> v(k);
        for (std::size_t r = 0; r < k; ++r) v[r] = std::get<std::int64_t>(rows[r][c]);
        write_rows(ds.get(), mem.get(), old_rows, k, v.data());
      } else {
        std::vector<const char*> v(k);
        for (std::size_t r = 0; r < k; ++r) v[r] = std::get<std::string>(rows[r][c]).c_str();
        write_rows(ds.get(), mem.get(), old_rows, k, v.data());
      }
    }
  }
  if (H5Fflush(id_, H5F_SCOPE_LOCAL) < 0) fail(id_, "cannot flush the file");
}

std::vector<double> Table::read_doubles(const std::string& column) const {
  quiet();
  const std::size_t c = column_index(column);
  if (columns_[c].type == ColumnType::String) {
    fail(id_, "column '" + column + "' holds strings, not numbers");
  }
  std::vector<double> out(rows());
  Hid ds(H5Dopen2(id_, column.c_str(), H5P_DEFAULT));
  if (!ds.ok()) fail(id_, "cannot open column", column);
  read_rows(ds.get(), H5T_NATIVE_DOUBLE, out.size(), out.data());
  return out;
}

std::vector<std::int64_t> Table::read_int64s(const std::string& column) const {
  quiet();
  const std::size_t c = column_index(column);
  if (columns_[c].type != ColumnType::Int64) {
    fail(id_, "column '" + column + "' is " + type_name(columns_[c].type) + ", not int64");
  }
  std::vector<std::int64_t> out(rows());
  Hid ds(H5Dopen2(id_, column.c_str(), H5P_DEFAULT));
  if (!ds.ok()) fail(id_, "cannot open column", column);
  read_rows(ds.get(), H5T_NATIVE_INT64, out.size(), out.data());
  return out;
}

std::vector<std::string> Table::read_strings(const std::string& column) const {
  quiet();
  const std::size_t c = column_index(column);
  if (columns_[c].type != ColumnType::String) {
    fail(id_, "column '" + column + "' is " + type_name(columns_[c].type) + ", not string");
  }
  const std::size_t n = rows();
  Hid ds(H5Dopen2(id_, column.c_str(), H5P_DEFAULT));
  if (!ds.ok()) fail(id_, "cannot open column", column);
  return read_dataset_strings(ds.get(), n);
}

// =================================================================================
// Group

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

  const hsize_t dims[1] = {static_cast<hsize_t>(count)};
  Hid space(H5Screate_simple(1, dims, nullptr));
  Hid dcpl(H5Pcreate(H5P_DATASET_CREATE));
  if (!space.ok() || !dcpl.ok()) fail(id_, "cannot prepare dataset", name);
  if (options.gzip_level > 0 && count > options.compress_min_size &&
      H5Zfilter_avail(H5Z_FILTER_DEFLATE) > 0) {
    const hsize_t chunk[1] = {
        static_cast<hsize_t>(std::min(count, std::max<std::size_t>(options.chunk_size, 1)))};
    if (H5Pset_chunk(dcpl.get(), 1, chunk) < 0 || H5Pset_shuffle(dcpl.get()) < 0 ||
        H5Pset_deflate(dcpl.get(), static_cast<unsigned>(std::min(options.gzip_level, 9))) < 0) {
      fail(id_, "cannot set compression", name);
    }
  }
  Hid lcpl = intermediate_lcpl(id_);
  Hid ds(H5Dcreate2(id_, name.c_str(), H5T_IEEE_F64LE, space.get(), lcpl.get(), dcpl.get(),
                    H5P_DEFAULT));
  if (!ds.ok()) fail(id_, "cannot create dataset", name);
  if (count > 0 &&
      H5Dwrite(ds.get(), H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, values) < 0) {
    fail(id_, "cannot write dataset", name);
  }
  Dataset out(ds.release());
  out.set_attribute("units", units);
  return out;
}

Dataset Group::write_dataset(const std::string& name, const std::vector<double>& values,
                             const std::vector<std::size_t>& shape, const std::string& units,
                             const WriteOptions& options) {
  quiet();
  if (shape.empty()) fail(id_, "a dataset needs at least one dimension", name);
  const std::size_t total =
      std::accumulate(shape.begin(), shape.end(), std::size_t{1}, std::multiplies<>());
  if (total != values.size()) {
    fail(id_, "shape holds " + std::to_string(total) + " values, data has " +
                  std::to_string(values.size()), name);
  }
  if (exists(name)) fail(id_, "already exists", name);

  const std::vector<hsize_t> dims(shape.begin(), shape.end());
  const int rank = static_cast<int>(dims.size());
  Hid space(H5Screate_simple(rank, dims.data(), nullptr));
  Hid dcpl(H5Pcreate(H5P_DATASET_CREATE));
  if (!space.ok() || !dcpl.ok()) fail(id_, "cannot prepare dataset", name);
  if (options.gzip_level > 0 && total > options.compress_min_size &&
      H5Zfilter_avail(H5Z_FILTER_DEFLATE) > 0) {
    // Halve the largest chunk dimension until a chunk holds at most chunk_size values.
    std::vector<hsize_t> chunk = dims;
    const hsize_t target = std::max<std::size_t>(options.chunk_size, 1);
    auto product = [&] {
      return std::accumulate(chunk.begin(), chunk.end(), hsize_t{1}, std::multiplies<>());
    };
    while (product() > target) {
      auto it = std::max_element(chunk.begin(), chunk.end());
      *it = (*it + 1) / 2;
    }
    if (H5Pset_chunk(dcpl.get(), rank, chunk.data()) < 0 || H5Pset_shuffle(dcpl.get()) < 0 ||
        H5Pset_deflate(dcpl.get(), static_cast<unsigned>(std::min(options.gzip_level, 9))) < 0) {
      fail(id_, "cannot set compression", name);
    }
  }
  Hid lcpl = intermediate_lcpl(id_);
  Hid ds(H5Dcreate2(id_, name.c_str(), H5T_IEEE_F64LE, space.get(), lcpl.get(), dcpl.get(),
                    H5P_DEFAULT));
  if (!ds.ok()) fail(id_, "cannot create dataset", name);
  if (total > 0 &&
      H5Dwrite(ds.get(), H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, values.data()) < 0) {
    fail(id_, "cannot write dataset", name);
  }
  Dataset out(ds.release());
  out.set_attribute("units", units);
  return out;
}

Dataset Group::write_dataset(const std::string& name, const std::vector<std::int64_t>& values,
                             const std::string& units) {
  quiet();
  if (exists(name)) fail(id_, "already exists", name);
  Hid space = simple_space(id_, values.size());
  Hid lcpl = intermediate_lcpl(id_);
  Hid ds(H5Dcreate2(id_, name.c_str(), H5T_STD_I64LE, space.get(), lcpl.get(), H5P_DEFAULT,
                    H5P_DEFAULT));
  if (!ds.ok()) fail(id_, "cannot create dataset", name);
  if (!values.empty() &&
      H5Dwrite(ds.get(), H5T_NATIVE_INT64, H5S_ALL, H5S_ALL, H5P_DEFAULT, values.data()) < 0) {
    fail(id_, "cannot write dataset", name);
  }
  Dataset out(ds.release());
  out.set_attribute("units", units);
  return out;
}

Dataset Group::write_dataset(const std::string& name, const std::vector<std::int64_t>& values,
                             const std::vector<std::size_t>& shape, const std::string& units) {
  quiet();
  const std::size_t total =
      std::accumulate(shape.begin(), shape.end(), std::size_t{1}, std::multiplies<>());
  if (total != values.size()) {
    fail(id_, "shape holds " + std::to_string(total) + " values, data has " +
                  std::to_string(values.size()), name);
  }
  if (exists(name)) fail(id_, "already exists", name);
  const std::vector<hsize_t> dims(shape.begin(), shape.end());
  Hid space(H5Screate_simple(static_cast<int>(dims.size()), dims.data(), nullptr));
  if (!space.ok()) fail(id_, "cannot create a dataspace", name);
  Hid lcpl = intermediate_lcpl(id_);
  Hid ds(H5Dcreate2(id_, name.c_str(), H5T_STD_I64LE, space.get(), lcpl.get(), H5P_DEFAULT,
                    H5P_DEFAULT));
  if (!ds.ok()) fail(id_, "cannot create dataset", name);
  if (total > 0 &&
      H5Dwrite(ds.get(), H5T_NATIVE_INT64, H5S_ALL, H5S_ALL, H5P_DEFAULT, values.data()) < 0) {
    fail(id_, "cannot write dataset", name);
  }
  Dataset out(ds.release());
  if (!units.empty()) out.set_attribute("units", units);
  return out;
}

Dataset Group::write_strings(const std::string& name, const std::vector<std::string>& values,
                             const std::vector<std::size_t>& shape_in) {
  quiet();
  const std::vector<std::size_t> shape =
      shape_in.empty() ? std::vector<std::size_t>{values.size()} : shape_in;
  const std::size_t total =
      std::accumulate(shape.begin(), shape.end(), std::size_t{1}, std::multiplies<>());
  if (total != values.size()) {
    fail(id_, "shape holds " + std::to_string(total) + " values, data has " +
                  std::to_string(values.size()), name);
  }
  if (exists(name)) fail(id_, "already exists", name);
  const std::vector<hsize_t> dims(shape.begin(), shape.end());
  Hid space(H5Screate_simple(static_cast<int>(dims.size()), dims.data(), nullptr));
  if (!space.ok()) fail(id_, "cannot create a dataspace", name);
  Hid type = vlen_string_type(id_);
  Hid lcpl = intermediate_lcpl(id_);
  Hid ds(H5Dcreate2(id_, name.c_str(), type.get(), space.get(), lcpl.get(), H5P_DEFAULT,
                    H5P_DEFAULT));
  if (!ds.ok()) fail(id_, "cannot create dataset", name);
  std::vector<const char*> p;
  p.reserve(values.size());
  for (const std::string& v : values) p.push_back(v.c_str());
  if (total > 0 && H5Dwrite(ds.get(), type.get(), H5S_ALL, H5S_ALL, H5P_DEFAULT, p.data()) < 0) {
    fail(id_, "cannot write dataset", name);
  }
  return Dataset(ds.release());
}

Dataset Group::open_dataset(const std::string& path) const {
  quiet();
  const hid_t d = H5Dopen2(id_, path.c_str(), H5P_DEFAULT);
  if (d < 0) fail(id_, "cannot open dataset", path);
  return Dataset(d);
}

Table Group::create_table(const std::string& name, const std::vector<Column>& columns,
                          std::size_t chunk_rows) {
  quiet();
  validate_columns(id_, name, columns);
  if (exists(name)) fail(id_, "already exists", name);
  Group g = require_group(name);
  const hsize_t dims[1] = {0};
  const hsize_t maxdims[1] = {H5S_UNLIMITED};
  const hsize_t chunk[1] = {static_cast<hsize_t>(std::max<std::size_t>(chunk_rows, 1))};
  Hid space(H5Screate_simple(1, dims, maxdims));
  Hid dcpl(H5Pcreate(H5P_DATASET_CREATE));
  if (!space.ok() || !dcpl.ok() || H5Pset_chunk(dcpl.get(), 1, chunk) < 0) {
    fail(id_, "cannot prepare table", name);
  }
  std::vector<Dataset> cols;
  for (const Column& c : columns) {
    Hid ftype = column_file_type(id_, c.type);
    const hid_t d = H5Dcreate2(g.id(), c.name.c_str(), ftype.get(), space.get(), H5P_DEFAULT,
                               dcpl.get(), H5P_DEFAULT);
    if (d < 0) fail(g.id(), "cannot create column", c.name);
    cols.push_back(Dataset(d));
    if (!c.units.empty()) cols.back().set_attribute("units", c.units);
    if (!c.long_name.empty()) cols.back().set_attribute("long_name", c.long_name);
  }
  cols.front().make_scale(columns.front().name);
  for (std::size_t i = 1; i < cols.size(); ++i) cols[i].attach_scale(cols.front(), 0);
  Table t(H5Gopen2(id_, name.c_str(), H5P_DEFAULT), columns);
  if (!t.valid()) fail(id_, "cannot open table", name);
  std::vector<std::string> names, units;
  for (const Column& c : columns) {
    names.push_back(c.name);
    units.push_back(c.units);
  }
  t.set_attribute("columns", names);
  t.set_attribute("units", units);
  return t;
}

Table Group::open_table(const std::string& name) const {
  quiet();
  H5O_info_t info;
  if (!exists(name) || H5Oget_info_by_name(id_, name.c_str(), &info, H5P_DEFAULT) < 0) {
    fail(id_, "cannot open table (absent)", name);
  }
  if (info.type != H5O_TYPE_GROUP) {
    fail(id_, "not a table of columns (a dataset: an older, compound-type table?)", name);
  }
  const hid_t g = H5Gopen2(id_, name.c_str(), H5P_DEFAULT);
  if (g < 0) fail(id_, "cannot open table", name);
  Table t(g, {});
  if (!t.has_attribute("columns")) fail(g, "not a table (no 'columns' attribute)");
  const std::vector<std::string> names = t.attribute_strings("columns");
  if (names.empty()) fail(g, "not a table (no columns)");
  std::vector<Column> cols;
  for (const std::string& n : names) {
    if (!t.exists(n)) fail(g, "column '" + n + "' is missing");
    const Dataset d = t.open_dataset(n);
    if (d.shape().size() != 1) fail(d.id(), "not a table column (not one-dimensional)");
    Hid type(H5Dget_type(d.id()));
    Column c{n, ColumnType::Float64, d.units(),
             d.has_attribute("long_name") ? d.attribute_string("long_name") : std::string()};
    switch (H5Tget_class(type.get())) {
      case H5T_FLOAT: c.type = ColumnType::Float64; break;
      case H5T_INTEGER: c.type = ColumnType::Int64; break;
      case H5T_STRING:
        if (H5Tis_variable_str(type.get()) <= 0) {
          fail(d.id(), "column '" + n + "' is a fixed-length string (unsupported)");
        }
        c.type = ColumnType::String;
        break;
      default: fail(d.id(), "column '" + n + "' has an unsupported type");
    }
    cols.push_back(std::move(c));
  }
  t.columns_ = std::move(cols);
  return t;
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
