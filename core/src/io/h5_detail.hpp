// What the parts of the HDF5 layer share (internal to lub_io): error reporting, the owner
// of a temporary HDF5 id, string types, dataspaces and 1-D row transfers (h5_detail.cpp).
// h5.cpp holds the RAII layer's files, groups and datasets, h5_attribute.cpp their
// attributes, h5_table.cpp the table and dimension-scale convention (lub/io/h5_table.hpp).
#pragma once

#include <hdf5.h>

#include <cstddef>
#include <string>
#include <utility>
#include <vector>

#include "lub/io/h5.hpp"

static_assert(std::is_same_v<hid_t, lub::h5::Id>, "lub::h5::Id must be hid_t (HDF5 >= 1.10)");

namespace lub::h5::detail {

/// Switch off HDF5's automatic error printing (per thread in thread-safe builds).
void quiet();

/// Throw for a failure at object `loc` (optionally naming a child `name`), with HDF5's
/// error stack in the message.
[[noreturn]] void fail(hid_t loc, const std::string& what, const std::string& name = "");
/// Throw for a failure on a file path (no open id).
[[noreturn]] void fail_file(const std::string& path, const std::string& what);

/// Close any HDF5 id (< 0: nothing), clearing the error stack.
void close_id(hid_t id) noexcept;

/// The file name and the object path of an open id ("?" if HDF5 gives none).
std::string file_name_of(hid_t id);
std::string object_path_of(hid_t id);
/// `get(id)` for an open id ("" for a closed one), leaving no HDF5 error behind.
std::string name_or_empty(hid_t id, std::string (*get)(hid_t));

/// Owner of a temporary id.
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

/// Variable-length UTF-8 string type.
Hid vlen_string_type(hid_t err_loc);
/// Variable-length string type of character set `cset`.
Hid vlen_string_type(hid_t err_loc, H5T_cset_t cset);
/// Frees the strings HDF5 allocated into `buf` (a read of `mem_type` over `space`).
void reclaim_vlen(hid_t mem_type, hid_t space, void* buf);
/// The number of elements of dataspace `space` (0 on error).
std::size_t npoints(hid_t space);
/// `n` fixed-length strings of `size` bytes each, NUL-terminated or padded (trailing
/// spaces dropped too if `space_padded`).
std::vector<std::string> split_fixed_strings(const char* buf, std::size_t n, std::size_t size, bool space_padded);

/// A 1-D dataspace of `n` elements, and a scalar one.
Hid simple_space(hid_t err_loc, std::size_t n);
Hid scalar_space(hid_t err_loc);

/// Selects rows [start, start + count) of the 1-D dataset `ds` in `file_space` and makes
/// `mem_space` a 1-D space of `count` elements; false if any step failed.
bool select_rows(hid_t ds, hsize_t start, hsize_t count, Hid& file_space, Hid& mem_space);

/// Reads the first `count` elements of a 1-D dataset into `buf` as `mem_type`.
void read_rows(hid_t ds, hid_t mem_type, hsize_t count, void* buf);

/// Reads the elements of a string dataset (variable- or fixed-length), at most `limit`.
std::vector<std::string> read_dataset_strings(hid_t ds, std::size_t limit);

}  // namespace lub::h5::detail
