# adaptobs_verify_headers(<target> <header>...)
#
# Generates one translation unit per public header that includes only that
# header, and compiles them all into an object library: a header that misses
# one of its own includes fails the build.
#
# Parsing <Eigen/Core> is about 1 s of the 1.2 s each of these units costs, so
# the units of headers that reach Eigen through their own includes share a
# precompiled <Eigen/Core>. For them the check is unchanged: Eigen/Core, which
# every Eigen module includes first, reads no macro of this library, and its
# include guard makes the header's own inclusion of it a no-op. A header whose
# includes never reach Eigen is compiled without the prefix, so that nothing
# Eigen declares (or the standard headers it pulls in) can hide a missing include.
# The sorting reads the headers' includes, so editing a header re-runs CMake.
function(adaptobs_verify_headers target)
  set(with_eigen)
  set(without_eigen)
  foreach(header IN LISTS ARGN)
    string(MAKE_C_IDENTIFIER "${header}" stem)
    set(source "${CMAKE_CURRENT_BINARY_DIR}/header_check/${stem}.cpp")
    set(content "#include <${header}>\n#include <${header}>  // and is idempotent\n")
    if(EXISTS "${source}")
      file(READ "${source}" existing)
    else()
      set(existing "")
    endif()
    if(NOT existing STREQUAL content)
      file(WRITE "${source}" "${content}")
    endif()
    _adaptobs_reaches_eigen("${header}" reaches)
    if(reaches)
      list(APPEND with_eigen "${source}")
    else()
      list(APPEND without_eigen "${source}")
    endif()
  endforeach()
  add_library(${target} OBJECT ${with_eigen} ${without_eigen})
  target_link_libraries(${target} PRIVATE adaptobs_developer_options)
  if(with_eigen)
    target_precompile_headers(${target} PRIVATE <Eigen/Core>)
    set_source_files_properties(${without_eigen} TARGET_DIRECTORY ${target} PROPERTIES SKIP_PRECOMPILE_HEADERS ON)
  endif()
endfunction()

# _adaptobs_reaches_eigen(<header> <out>): whether <header> (a path under
# include/) includes an Eigen header, directly or through the library's own
# headers. Read from the text; conditional includes count as includes.
function(_adaptobs_reaches_eigen header out)
  set(pending "${header}")
  set(seen)
  set(result FALSE)
  while(pending AND NOT result)
    list(POP_FRONT pending current)
    if(current IN_LIST seen)
      continue()
    endif()
    list(APPEND seen "${current}")
    set(path "${PROJECT_SOURCE_DIR}/include/${current}")
    if(NOT EXISTS "${path}")
      continue()
    endif()
    set_property(DIRECTORY "${PROJECT_SOURCE_DIR}" APPEND PROPERTY CMAKE_CONFIGURE_DEPENDS "${path}")
    file(STRINGS "${path}" includes REGEX "^#include <(Eigen|adaptobs)/")
    foreach(line IN LISTS includes)
      if(line MATCHES "^#include <Eigen/")
        set(result TRUE)
        break()
      endif()
      string(REGEX REPLACE "^#include <([^>]+)>.*" "\\1" included "${line}")
      list(APPEND pending "${included}")
    endforeach()
  endwhile()
  set(${out} ${result} PARENT_SCOPE)
endfunction()
