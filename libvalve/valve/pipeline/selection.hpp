#pragma once
// Per group, the row of a study table that meets every threshold and comes first by the
// minimized columns: the "select" entries of a pipeline (format and rules in
// pipeline_spec.hpp). Like aggregates, selections work on the cell texts as written.
#include <filesystem>
#include <string>

#include "valve/pipeline/gather.hpp"
#include "valve/pipeline/pipeline_spec.hpp"

namespace valve {

struct Selection {
  CsvTable table;    ///< one row per group (see pipeline_spec.hpp)
  std::string line;  ///< the choices in words, one line without a trailing newline
};

/// The selection of `from` (whose header must hold every column the spec names, which
/// parse_pipeline has checked; an Error otherwise).
Selection select_table(const SelectSpec& select, const CsvTable& from);

struct SelectResult {
  std::filesystem::path path;  ///< DIR/<csv>
  std::filesystem::path text;  ///< DIR/<csv stem>.txt
  std::string from;            ///< the source csv, relative to DIR
  std::string line;
  size_t rows = 0;
};

/// select_table, written atomically to DIR/<csv> and the line to DIR/<csv stem>.txt.
SelectResult write_select(const SelectSpec& select, const CsvTable& from, const std::filesystem::path& out_dir);

}  // namespace valve
