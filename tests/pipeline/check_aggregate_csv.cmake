# cmake -DDIR=FOLDER -P check_aggregate_csv.cmake
# Checks the aggregates of data/generate_sweep_aggregate.json against its triangles.csv:
# triangles_by_status.csv has one group (status ok) with count 2, min/max the two made
# counts, mean and median their average, n_mean 75 and n_sd 35.35533906 (sample sd of 50
# and 100); triangles_large.csv keeps the n = 100 row only: count 1, mean its count, sd empty.
function(read_rows file expected_header out_cells)
  file(STRINGS "${file}" lines)
  list(LENGTH lines count)
  if(NOT count EQUAL 2)
    message(FATAL_ERROR "${file}: expected a header and 1 row, found ${count} lines: ${lines}")
  endif()
  list(GET lines 0 header)
  if(NOT header STREQUAL expected_header)
    message(FATAL_ERROR "${file}: expected header '${expected_header}', found '${header}'")
  endif()
  list(GET lines 1 row)
  # Keep empty cells: a trailing "," would otherwise vanish from the list.
  string(REPLACE "," ";" cells "${row};")
  set(${out_cells} "${cells}" PARENT_SCOPE)
endfunction()

file(STRINGS "${DIR}/triangles.csv" gathered)
list(GET gathered 1 row50)
list(GET gathered 2 row100)
string(REPLACE "," ";" row50 "${row50}")
string(REPLACE "," ";" row100 "${row100}")
list(GET row50 1 made50)
list(GET row100 1 made100)
math(EXPR sum "${made50} + ${made100}")
math(EXPR half "${sum} / 2")
math(EXPR odd "${sum} % 2")
if(odd)
  set(mean "${half}.5")
else()
  set(mean "${half}")
endif()

read_rows("${DIR}/triangles_by_status.csv"
          "status,triangles_count,triangles_min,triangles_max,triangles_mean,triangles_median,n_mean,n_sd" by_status)
set(expected "ok;2;${made50};${made100};${mean};${mean};75;35.35533906;")
if(NOT by_status STREQUAL expected)
  message(FATAL_ERROR "triangles_by_status.csv: expected cells '${expected}', found '${by_status}'")
endif()

read_rows("${DIR}/triangles_large.csv" "triangles_count,triangles_mean,triangles_sd" large)
set(expected "1;${made100};;")
if(NOT large STREQUAL expected)
  message(FATAL_ERROR "triangles_large.csv: expected cells '${expected}', found '${large}'")
endif()

file(READ "${DIR}/triangles_by_status.csv" text)
string(TOLOWER "${text}" lower)
if(lower MATCHES "nan")
  message(FATAL_ERROR "triangles_by_status.csv: contains nan")
endif()
if(REQUIRE_PNG AND NOT EXISTS "${DIR}/triangles_by_status.png")
  message(FATAL_ERROR "${DIR}/triangles_by_status.png: expected the plot (gnuplot is installed)")
endif()
message(STATUS "ok: ${DIR}/triangles_by_status.csv, ${DIR}/triangles_large.csv")
