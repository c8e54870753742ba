# adaptobs_verify_headers(<target> <header>...)
#
# Generates one translation unit per public header that includes only that
# header, and compiles them all into an object library: a header that misses
# one of its own includes fails the build.
function(adaptobs_verify_headers target)
  set(sources)
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
    list(APPEND sources "${source}")
  endforeach()
  add_library(${target} OBJECT ${sources})
  target_link_libraries(${target} PRIVATE adaptobs_developer_options)
endfunction()
