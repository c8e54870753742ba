# Flags for the project's own targets (tests, examples, benchmarks, header
# checks). They travel through an INTERFACE target, never through global
# variables, so that consumers of adaptobs inherit none of them.
add_library(adaptobs_developer_options INTERFACE)

if(CMAKE_CXX_COMPILER_ID MATCHES "GNU|Clang")
  target_compile_options(adaptobs_developer_options INTERFACE -Wall -Wextra -Wpedantic)
  if(ADAPTOBS_WARNINGS_AS_ERRORS)
    target_compile_options(adaptobs_developer_options INTERFACE -Werror)
  endif()
  if(ADAPTOBS_SANITIZE)
    set(_adaptobs_sanitizers -fsanitize=address,undefined -fno-sanitize-recover=all -fno-omit-frame-pointer)
    target_compile_options(adaptobs_developer_options INTERFACE ${_adaptobs_sanitizers})
    target_link_options(adaptobs_developer_options INTERFACE ${_adaptobs_sanitizers})
  endif()
elseif(MSVC)
  target_compile_options(adaptobs_developer_options INTERFACE /W4 $<$<BOOL:${ADAPTOBS_WARNINGS_AS_ERRORS}>:/WX>)
endif()

target_link_libraries(adaptobs_developer_options INTERFACE adaptobs::adaptobs)
