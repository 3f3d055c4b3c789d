// Attributes of any HDF5 object (lub::h5::Object's attribute members, lub/io/h5.hpp):
// numbers, 64-bit integers and strings (variable- or fixed-length), single or as lists.
#include "lub/io/h5.hpp"

#include <hdf5.h>

#include <utility>

#include "io/h5_detail.hpp"

namespace lub::h5 {
namespace detail {
namespace {

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

}  // namespace
}  // namespace detail

using namespace detail;

// =================================================================================
// Object: attributes

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

}  // namespace lub::h5
