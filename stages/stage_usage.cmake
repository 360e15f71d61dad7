# cmake -DSOURCE=stage/main.cpp -DOUTPUT=stage_usage.hpp [-DPAGE=docs/stages/NAME.md -DNAME=NAME] -P stage_usage.cmake
# A stage's --help text is its main.cpp's leading comment block (usage, what it reads and
# writes, exit codes), so the documentation and the help cannot drift apart. PAGE gets the
# same text as the stage's markdown page (docs/stages/NAME.md is a copy, checked by a test).
file(READ "${SOURCE}" content)
string(REGEX MATCH "^(//[^\n]*\n)+" header "${content}")
if(header STREQUAL "")
  message(FATAL_ERROR "${SOURCE}: expected a leading // comment block with the stage's usage, found none")
endif()
string(REGEX REPLACE "(^|\n)// ?" "\\1" text "${header}")
# The options every stage takes (core/cli.hpp, core/progress.hpp), said once here.
string(APPEND text "\nEvery stage also takes:\n"
  "  --progress text|slicer|none  progress as text lines on stderr (the default), as 3D Slicer's\n"
  "      <filter-progress> lines on stdout, or not at all\n"
  "  --xml   prints the stage's 3D Slicer CLI module description (XML) and exits\n"
  "  --help  prints this text and exits\n")
# Writes only when the content changed, so that dependants do not rebuild for nothing.
function(write_if_changed path content)
  if(EXISTS "${path}")
    file(READ "${path}" previous)
    if(previous STREQUAL content)
      return()
    endif()
  endif()
  file(WRITE "${path}" "${content}")
endfunction()
if(DEFINED PAGE)
  string(CONCAT page "# ${NAME}\n\nWhat `${NAME} --help` prints: the leading comment of\n"
           "[`stages/${NAME}/main.cpp`](../../stages/${NAME}/main.cpp), made into this page when the stage is built.\n\n"
           "```text\n${text}```\n")
  write_if_changed("${PAGE}" "${page}")
endif()
set(generated "// Generated from ${SOURCE} by stages/stage_usage.cmake.\n#pragma once\ninline constexpr const char* kStageUsage = R\"usage(${text})usage\";\n")
write_if_changed("${OUTPUT}" "${generated}")
