// A small RAII layer over the HDF5 C API, for the run files (lubsim run.h5) and the
// sweep's study file. HDF5 itself stays out of this header: handles are opaque
// `std::int64_t` ids (hid_t in HDF5 ≥ 1.10), and lubcore links HDF5 privately.
//
// ## Conventions
//
//  - Every failure throws `std::runtime_error`; the message names the file and the
//    object path and carries HDF5's own error stack. HDF5's automatic error printing
//    is switched off (per thread, on first use of this module).
//  - Files, groups, datasets and tables are move-only; the destructor closes the
//    handle. A file stays open until the last object opened from it is closed.
//  - Strings (attributes, string datasets, table cells) are variable-length UTF-8:
//    h5py returns attributes as `str`, dataset elements as `bytes` (`.asstr()[:]`),
//    xarray (h5netcdf) as `str`, and h5dump prints them as text. Fixed-length strings
//    written by others read fine.
//  - Dataset names may be paths ("series/case_0007/t"); missing groups are created.
//
// Tables of columns and dimension scales (the netCDF-4 convention of the study file's
// `/cases` and a run file's `/cycles`) are declared in lub/io/h5_table.hpp, which this
// header includes.
#pragma once

#include <cstddef>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <utility>
#include <variant>
#include <vector>

namespace lub::h5 {

/// An HDF5 identifier (hid_t); < 0 means "none".
using Id = std::int64_t;

/// Base of every open object: owns one id, closes it on destruction, carries the
/// attribute interface (attributes live on the file's root group, groups, datasets).
class Object {
 public:
  Object(const Object&) = delete;
  Object& operator=(const Object&) = delete;
  Object(Object&& other) noexcept;
  Object& operator=(Object&& other) noexcept;
  virtual ~Object();

  Id id() const { return id_; }
  bool valid() const { return id_ >= 0; }
  /// Path of the object inside its file ("/" for a file), and the file's name.
  std::string path() const;
  std::string file_name() const;

  // --- Attributes. Setters overwrite an existing attribute of that name. ---
  bool has_attribute(const std::string& name) const;
  void set_attribute(const std::string& name, const std::string& value);
  void set_attribute(const std::string& name, const char* value);
  void set_attribute(const std::string& name, double value);
  void set_attribute(const std::string& name, const std::vector<double>& values);
  void set_attribute(const std::string& name, const std::vector<std::string>& values);
  /// Any integer type is stored as int64 (bool is rejected at compile time).
  template <class T, std::enable_if_t<std::is_integral_v<T> && !std::is_same_v<T, bool>, int> = 0>
  void set_attribute(const std::string& name, T value) {
    set_attribute_int64(name, static_cast<std::int64_t>(value));
  }
  void set_attribute(const std::string& name, bool value) = delete;
  void set_attribute_int64(const std::string& name, std::int64_t value);
  void remove_attribute(const std::string& name);

  // Readers throw if the attribute is missing or of another class. attribute_double(s)
  // read integer attributes too (converted); attribute_int64 needs an integer one.
  // The scalar readers also accept a one-element array.
  std::string attribute_string(const std::string& name) const;
  double attribute_double(const std::string& name) const;
  std::int64_t attribute_int64(const std::string& name) const;
  std::vector<double> attribute_doubles(const std::string& name) const;
  std::vector<std::string> attribute_strings(const std::string& name) const;
  std::vector<std::string> attribute_names() const;

 protected:
  Object() = default;
  explicit Object(Id id) : id_(id) {}
  void close_handle() noexcept;
  Id id_ = -1;
};

/// Chunking/compression of a written dataset.
struct WriteOptions {
  int gzip_level = 4;                  ///< 0..9; 0 = never compress
  std::size_t compress_min_size = 4096;  ///< compress (shuffle + gzip) only above this many values
  std::size_t chunk_size = 16384;        ///< target values per chunk when compressed
};

/// A dataset (numeric arrays; tables are datasets too).
class Dataset : public Object {
 public:
  Dataset() = default;

  std::vector<std::size_t> shape() const;
  /// Total number of elements (rows, for a table).
  std::size_t size() const;
  /// All elements, row-major, converted to double / int64.
  std::vector<double> read_doubles() const;
  std::vector<std::int64_t> read_int64s() const;
  /// All elements of a string dataset, row-major.
  std::vector<std::string> read_strings() const;
  /// The `units` attribute ("" if absent).
  std::string units() const;

  /// Make this (1-D) dataset a dimension scale (H5DSset_scale); `name` may be "".
  void make_scale(const std::string& name = "");
  /// Attach `scale` to dimension `dim` of this dataset (H5DSattach_scale); makes it a
  /// scale first if it is not one yet. `label` (optional) names the dimension.
  void attach_scale(Dataset& scale, unsigned dim, const std::string& label = "");
  bool is_scale() const;

 protected:
  friend class Group;
  explicit Dataset(Id id) : Object(id) {}
};

struct Column;  // lub/io/h5_table.hpp
class Table;

/// A group (also the base of File, whose id stands for its root group).
class Group : public Object {
 public:
  Group() = default;

  /// Whether a link exists at `path` (relative to this group, or absolute).
  bool exists(const std::string& path) const;
  /// Create-or-open a group, creating intermediate groups ("a/b/c", "/series/x").
  Group require_group(const std::string& path);
  /// Open an existing group; throws if absent.
  Group open_group(const std::string& path) const;
  /// Names of the links directly in this group, in name order.
  std::vector<std::string> list() const;
  /// Copy the object at `path` (a group with all it holds, or a dataset, with attributes)
  /// to `to` under the same path (H5Ocopy); throws if it is absent or `to` has that path.
  void copy_to(const std::string& path, Group& to) const;

  /// Write a 1-D double dataset with a `units` attribute (shuffle + gzip, chunked, if
  /// longer than options.compress_min_size). Throws if `name` exists.
  Dataset write_dataset(const std::string& name, const std::vector<double>& values,
                        const std::string& units, const WriteOptions& options = {});
  Dataset write_dataset(const std::string& name, const double* values, std::size_t count,
                        const std::string& units, const WriteOptions& options = {});
  /// N-D double dataset, `values` in row-major (C) order, size = product of shape.
  Dataset write_dataset(const std::string& name, const std::vector<double>& values,
                        const std::vector<std::size_t>& shape, const std::string& units,
                        const WriteOptions& options = {});
  /// 1-D int64 dataset (no compression).
  Dataset write_dataset(const std::string& name, const std::vector<std::int64_t>& values,
                        const std::string& units);
  /// N-D int64 dataset, row-major (no compression); `units` "" writes no attribute.
  Dataset write_dataset(const std::string& name, const std::vector<std::int64_t>& values,
                        const std::vector<std::size_t>& shape, const std::string& units);
  /// Variable-length UTF-8 string dataset, row-major; `shape` {} means 1-D.
  Dataset write_strings(const std::string& name, const std::vector<std::string>& values,
                        const std::vector<std::size_t>& shape = {});
  Dataset open_dataset(const std::string& path) const;

  /// Create an empty table (a group of columns, see the header comment); throws if
  /// `name` exists or the columns are invalid (empty or duplicate names). `chunk_rows`
  /// rows per chunk.
  Table create_table(const std::string& name, const std::vector<Column>& columns,
                     std::size_t chunk_rows = 64);
  /// Open an existing table (columns from its `columns` attribute and their datasets).
  /// Throws if `name` is not such a group (e.g. an older, compound-type table).
  Table open_table(const std::string& name) const;

 protected:
  explicit Group(Id id) : Object(id) {}
};

/// An HDF5 file. `File` is a `Group`: its methods act on the root group.
class File : public Group {
 public:
  enum class Mode { ReadOnly, ReadWrite };

  File() = default;
  /// Create (truncating any existing file).
  static File create(const std::string& path);
  /// Open an existing file.
  static File open(const std::string& path, Mode mode = Mode::ReadOnly);

  /// Write everything buffered to the file (H5Fflush); the file then opens intact
  /// even if the process is killed before closing it.
  void flush();
  /// Close now, reporting errors (the destructor closes silently).
  void close();
  const std::string& filename() const { return filename_; }

 private:
  File(Id id, std::string filename) : Group(id), filename_(std::move(filename)) {}
  std::string filename_;
};

}  // namespace lub::h5

#include "lub/io/h5_table.hpp"  // IWYU pragma: export
