# The layer rule of include/adaptobs: a header includes only from its own layer
# and the layers below it.
#
#   core (core/detail: helpers) -> core
#   models (paper-family models)-> core, and their own layer
#   adaptation, diagnostics     -> core, and their own layer
#   design                      -> core, models, and its own layer
#   observers, baselines        -> core, models, adaptation, design, diagnostics, and their own layer
#   simulation                  -> anything below
#
# It also checks that the headers, and with -DSOURCES=<repository root> the
# examples, tests and benchmarks, cite papers by author and year, as listed in
# docs/references.md, never by a file of extracted text ("000_<hash>.txt") or
# an index ("paper 000", also when a comment breaks the line between the two)
# that only makes sense beside those files.
#
# Run as a script (CTest `layer_rule`):
#   cmake -DROOT=<include/adaptobs> [-DSOURCES=<repository root>] -P AdaptobsCheckLayers.cmake
# It fails naming every include that crosses upward or sideways, and every such citation.
cmake_minimum_required(VERSION 3.20)

set(allowed_core core)
set(allowed_models core models)
set(allowed_adaptation core adaptation)
set(allowed_design core models design)
set(allowed_diagnostics core diagnostics)
set(allowed_observers core models adaptation design diagnostics observers)
set(allowed_baselines core models adaptation design diagnostics baselines)
set(allowed_simulation core models adaptation design diagnostics observers baselines simulation)

if(NOT ROOT)
  message(FATAL_ERROR "AdaptobsCheckLayers: pass -DROOT=<path to include/adaptobs>")
endif()
get_filename_component(ROOT "${ROOT}" ABSOLUTE)
set(violations "")
set(checked 0)

# Appends to `violations` every citation of a paper by file or index in `file`.
# The whole text is searched, so "paper" at the end of a comment line and the
# index at the start of the next are found too.
function(check_citations file name)
  file(READ "${file}" text)
  string(REGEX MATCHALL "[0-9][0-9][0-9]_[0-9a-f]+\\.txt|[Pp]apers?[ \n/#*]+[0-9][0-9][0-9]([^0-9]|$)" found "${text}")
  foreach(citation IN LISTS found)
    string(REGEX REPLACE "[ \n/#*]+" " " citation "${citation}")
    string(STRIP "${citation}" citation)
    string(APPEND violations "\n  ${name}: cites a paper by file or index, not by author and year: '${citation}'")
  endforeach()
  set(violations "${violations}" PARENT_SCOPE)
endfunction()

foreach(layer core models adaptation design diagnostics observers baselines simulation)
  file(GLOB_RECURSE headers "${ROOT}/${layer}/*.hpp")
  foreach(header IN LISTS headers)
    math(EXPR checked "${checked} + 1")
    file(RELATIVE_PATH name "${ROOT}" "${header}")
    check_citations("${header}" "${name}")
    file(STRINGS "${header}" includes REGEX "^#include <adaptobs/")
    foreach(line IN LISTS includes)
      string(REGEX REPLACE "^#include <adaptobs/([a-z_]+)[/.].*" "\\1" target "${line}")
      if(NOT target IN_LIST allowed_${layer})
        file(RELATIVE_PATH name "${ROOT}" "${header}")
        string(APPEND violations "\n  ${name}: ${line} (layer '${layer}' may include only: ${allowed_${layer}})")
      endif()
    endforeach()
  endforeach()
endforeach()
if(checked EQUAL 0)
  message(FATAL_ERROR "AdaptobsCheckLayers: no header found under ${ROOT}")
endif()
set(sources_checked 0)
if(SOURCES)
  get_filename_component(SOURCES "${SOURCES}" ABSOLUTE)
  foreach(folder examples tests benchmarks)
    file(GLOB_RECURSE files "${SOURCES}/${folder}/*.cpp" "${SOURCES}/${folder}/*.hpp")
    foreach(source IN LISTS files)
      math(EXPR sources_checked "${sources_checked} + 1")
      file(RELATIVE_PATH name "${SOURCES}" "${source}")
      check_citations("${source}" "${name}")
    endforeach()
  endforeach()
endif()
if(violations)
  message(FATAL_ERROR "Layer or citation rules broken:${violations}")
endif()
message(STATUS "Layer and citation rules hold for ${checked} headers and ${sources_checked} other sources")
