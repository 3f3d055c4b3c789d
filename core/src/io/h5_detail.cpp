// The shared layer under the HDF5 wrappers (io/h5_detail.hpp): error reporting with
// HDF5's error stack, closing ids, string types, dataspaces and row transfers. The RAII
// classes are in h5.cpp (files, groups, datasets) and h5_attribute.cpp (attributes).
#include <hdf5.h>

#include <algorithm>
#include <stdexcept>
#include <utility>

#include "io/h5_detail.hpp"

namespace lub::h5::detail {

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

}  // namespace

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

namespace {

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

namespace {

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

// ---------------------------------------------------------------------------------
// Dataspaces

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

}  // namespace lub::h5::detail
