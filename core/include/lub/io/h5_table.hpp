// The table convention of the HDF5 layer (lub/io/h5.hpp, which includes this header):
// tables of columns with a dimension scale, for the study file's `/cases` and a run file's
// `/cycles`. Defined in core/src/io/h5_table.cpp, with the dimension-scale methods of
// `Dataset`.
//
// A table is a group holding one extendible 1-D dataset per column (double → f8,
// int64 → i8, string → variable-length UTF-8), netCDF-4 style: the first column is the
// table's dimension scale (its name is the dimension's: `case`, `cycle`) and every other
// column has it attached, so `xarray.open_dataset(file, group="cases",
// engine="h5netcdf")` gives one Dataset indexed by the first column (and
// `.to_dataframe()` a pandas table). Each column carries `units` (numbers) and
// `long_name` attributes when given; the group carries `columns` (names, in order) and
// `units`. `Table::append` writes a batch of rows (every other column first, the
// dimension column last) and flushes the file, so a process killed after `append`
// returns leaves a file that opens with every row appended so far; the table's length is
// the dimension column's, and readers ignore a longer column's tail (a kill *during* an
// append), which the next append overwrites. Files use the default (1.8-compatible)
// format, which has no "file open for write" flag, so a killed writer never leaves a
// file that needs `h5clear`.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <utility>
#include <variant>
#include <vector>

#include "lub/io/h5.hpp"

namespace lub::h5 {

/// Column type of a table.
enum class ColumnType { Float64, Int64, String };

struct Column {
  Column() = default;
  Column(std::string name_, ColumnType type_, std::string units_ = "", std::string long_name_ = "")
      : name(std::move(name_)), type(type_), units(std::move(units_)), long_name(std::move(long_name_)) {}
  std::string name;
  ColumnType type = ColumnType::Float64;
  std::string units;      ///< CF-style ("m", "Pa s", "m s-2", "1"); "" for strings
  std::string long_name;  ///< a description ("" : none)
};

/// One cell; an int64 cell is accepted by a Float64 column (converted).
using Cell = std::variant<double, std::int64_t, std::string>;
/// One row: one cell per column, in column order.
using Row = std::vector<Cell>;

/// An appendable table of columns: see the header comment.
class Table : public Group {
 public:
  Table() = default;

  const std::vector<Column>& columns() const { return columns_; }
  /// Index of a column; throws if absent.
  std::size_t column_index(const std::string& name) const;
  bool has_column(const std::string& name) const;
  /// Rows: the length of the first (dimension) column.
  std::size_t rows() const;
  /// The dataset of one column (to add attributes).
  Dataset column(const std::string& name) const;

  /// Append rows (each with one cell per column, matching types), then flush the
  /// file. An empty batch is a no-op (but still flushes).
  void append(const std::vector<Row>& rows);
  void append(const Row& row) { append(std::vector<Row>{row}); }

  /// One column, all rows. The column must have the matching type (a Float64 read of
  /// an Int64 column converts).
  std::vector<double> read_doubles(const std::string& column) const;
  std::vector<std::int64_t> read_int64s(const std::string& column) const;
  std::vector<std::string> read_strings(const std::string& column) const;

 private:
  friend class Group;
  Table(Id id, std::vector<Column> columns) : Group(id), columns_(std::move(columns)) {}
  std::vector<Column> columns_;
};

}  // namespace lub::h5
