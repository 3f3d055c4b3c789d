// The table and dimension-scale convention of the HDF5 layer: see lub/io/h5_table.hpp.
#include "lub/io/h5_table.hpp"

#include <hdf5.h>
#include <hdf5_hl.h>

#include <algorithm>
#include <utility>

#include "io/h5_detail.hpp"

namespace lub::h5 {
namespace {

using detail::fail;
using detail::Hid;
using detail::quiet;

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
  if (t == ColumnType::String) return detail::vlen_string_type(err_loc);
  return Hid(H5Tcopy(t == ColumnType::Float64 ? H5T_IEEE_F64LE : H5T_STD_I64LE));
}

/// Memory type for a column of type t read/written as `t`.
Hid column_mem_type(hid_t err_loc, ColumnType t) {
  if (t == ColumnType::String) return detail::vlen_string_type(err_loc);
  return Hid(H5Tcopy(t == ColumnType::Float64 ? H5T_NATIVE_DOUBLE : H5T_NATIVE_INT64));
}

/// The dataset of column `column` of the table group `table`.
Hid open_column(hid_t table, const std::string& column) {
  Hid ds(H5Dopen2(table, column.c_str(), H5P_DEFAULT));
  if (!ds.ok()) fail(table, "cannot open column", column);
  return ds;
}

/// Writes `count` elements of `buf` (as `mem_type`) to a 1-D extendible dataset at
/// [start, start + count), extending it to exactly start + count.
void write_rows(hid_t ds, hid_t mem_type, hsize_t start, hsize_t count, const void* buf) {
  const hsize_t new_dims[1] = {start + count};
  if (H5Dset_extent(ds, new_dims) < 0) fail(ds, "cannot extend the column");
  if (count == 0) return;
  Hid fspace, mspace;
  if (!detail::select_rows(ds, start, count, fspace, mspace) ||
      H5Dwrite(ds, mem_type, mspace.get(), fspace.get(), H5P_DEFAULT, buf) < 0) {
    fail(ds, "cannot write " + std::to_string(count) + " rows");
  }
}

/// Throws unless every row has one cell per column, each of the column's type (so a bad
/// row appends nothing).
void check_rows(hid_t table, const std::vector<Column>& columns, const std::vector<Row>& rows) {
  const std::size_t ncol = columns.size();
  for (std::size_t r = 0; r < rows.size(); ++r) {
    const Row& row = rows[r];
    if (row.size() != ncol) {
      fail(table, "row " + std::to_string(r) + " has " + std::to_string(row.size()) +
                      " cells, the table has " + std::to_string(ncol) + " columns");
    }
    for (std::size_t c = 0; c < ncol; ++c) {
      const Cell& cell = row[c];
      const ColumnType t = columns[c].type;
      const bool fits = (t == ColumnType::Float64 && !std::holds_alternative<std::string>(cell)) ||
                        (t == ColumnType::Int64 && std::holds_alternative<std::int64_t>(cell)) ||
                        (t == ColumnType::String && std::holds_alternative<std::string>(cell));
      if (!fits) {
        static const char* const cell_names[] = {"double", "int64", "string"};
        fail(table, "row " + std::to_string(r) + ", column '" + columns[c].name + "' (" +
                        type_name(t) + "): got a " + cell_names[cell.index()] + " cell");
      }
    }
  }
}

/// Writes cell `c` of every row (checked) to column `col` from row `old_rows` on.
void append_column(hid_t table, const Column& col, std::size_t c, const std::vector<Row>& rows,
                   hsize_t old_rows) {
  const std::size_t k = rows.size();
  Hid ds = open_column(table, col.name);
  Hid mem = column_mem_type(table, col.type);
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

/// The first `rows` elements of column `column`, read as `mem_type`.
template <class T>
std::vector<T> read_column(hid_t table, const std::string& column, std::size_t rows,
                           hid_t mem_type) {
  std::vector<T> out(rows);
  Hid ds = open_column(table, column);
  detail::read_rows(ds.get(), mem_type, out.size(), out.data());
  return out;
}

/// The description of an existing column `name` (its dataset `d`) of a table.
Column column_of(const Dataset& d, const std::string& name) {
  if (d.shape().size() != 1) fail(d.id(), "not a table column (not one-dimensional)");
  Hid type(H5Dget_type(d.id()));
  Column c{name, ColumnType::Float64, d.units(),
           d.has_attribute("long_name") ? d.attribute_string("long_name") : std::string()};
  switch (H5Tget_class(type.get())) {
    case H5T_FLOAT: c.type = ColumnType::Float64; break;
    case H5T_INTEGER: c.type = ColumnType::Int64; break;
    case H5T_STRING:
      if (H5Tis_variable_str(type.get()) <= 0) {
        fail(d.id(), "column '" + name + "' is a fixed-length string (unsupported)");
      }
      c.type = ColumnType::String;
      break;
    default: fail(d.id(), "column '" + name + "' has an unsupported type");
  }
  return c;
}

}  // namespace

// =================================================================================
// Dimension scales

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
  if (!rows.empty()) {
    check_rows(id_, columns_, rows);
    const hsize_t old_rows = static_cast<hsize_t>(this->rows());
    // The dimension column (0) last: it defines the table's length.
    for (std::size_t step = 1; step <= ncol; ++step) {
      const std::size_t c = step % ncol;
      append_column(id_, columns_[c], c, rows, old_rows);
    }
  }
  if (H5Fflush(id_, H5F_SCOPE_LOCAL) < 0) fail(id_, "cannot flush the file");
}

std::vector<double> Table::read_doubles(const std::string& column) const {
  quiet();
  if (columns_[column_index(column)].type == ColumnType::String) {
    fail(id_, "column '" + column + "' holds strings, not numbers");
  }
  return read_column<double>(id_, column, rows(), H5T_NATIVE_DOUBLE);
}

std::vector<std::int64_t> Table::read_int64s(const std::string& column) const {
  quiet();
  const ColumnType type = columns_[column_index(column)].type;
  if (type != ColumnType::Int64) {
    fail(id_, "column '" + column + "' is " + type_name(type) + ", not int64");
  }
  return read_column<std::int64_t>(id_, column, rows(), H5T_NATIVE_INT64);
}

std::vector<std::string> Table::read_strings(const std::string& column) const {
  quiet();
  const ColumnType type = columns_[column_index(column)].type;
  if (type != ColumnType::String) {
    fail(id_, "column '" + column + "' is " + type_name(type) + ", not string");
  }
  const std::size_t n = rows();
  Hid ds = open_column(id_, column);
  return detail::read_dataset_strings(ds.get(), n);
}

// =================================================================================
// Group: creating and opening tables

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
    cols.push_back(column_of(t.open_dataset(n), n));
  }
  t.columns_ = std::move(cols);
  return t;
}

}  // namespace lub::h5
