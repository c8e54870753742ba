# Flags for the project's own targets (tests, examples, benchmarks, header
# checks). They travel through INTERFACE targets, never through global
# variables, so that consumers of adaptobs inherit none of them.
#   adaptobs_warnings            the warning flags;
#   adaptobs_developer_options   the warning flags and, with ADAPTOBS_SANITIZE,
#                                the sanitizers.
add_library(adaptobs_warnings INTERFACE)
add_library(adaptobs_developer_options INTERFACE)

if(CMAKE_CXX_COMPILER_ID MATCHES "GNU|Clang")
  target_compile_options(adaptobs_warnings INTERFACE -Wall -Wextra -Wpedantic)
  if(ADAPTOBS_WARNINGS_AS_ERRORS)
    target_compile_options(adaptobs_warnings INTERFACE -Werror)
  endif()
  if(ADAPTOBS_SANITIZE)
    # Without UBSan's object-size check, which only acts in optimized units
    # (test_long_runs): there it keeps clang from inlining Eigen's coefficient
    # accessors, so that those tests run a fifth slower and compile 15% slower,
    # and AddressSanitizer checks the same accesses against the real allocation.
    set(_adaptobs_sanitizers -fsanitize=address,undefined -fno-sanitize=object-size -fno-sanitize-recover=all
                             -fno-omit-frame-pointer)
    target_compile_options(adaptobs_developer_options INTERFACE ${_adaptobs_sanitizers})
    target_link_options(adaptobs_developer_options INTERFACE ${_adaptobs_sanitizers})
  endif()
elseif(MSVC)
  target_compile_options(adaptobs_warnings INTERFACE /W4 $<$<BOOL:${ADAPTOBS_WARNINGS_AS_ERRORS}>:/WX>)
endif()

target_link_libraries(adaptobs_warnings INTERFACE adaptobs::adaptobs)
target_link_libraries(adaptobs_developer_options INTERFACE adaptobs_warnings)

# adaptobs::precompiled: the double-precision design routines compiled once
# (include/adaptobs/core/precompiled.hpp). The tests and examples link it; the
# README example, the header checks, the installed-package consumer and the
# benchmarks (built for x86-64-v3) stay header-only. adaptobs::precompiled_base, which
# it links, holds the part that running an observer with given gains calls (the
# matrix exponential and the dense eigenvalues): the satellite example of
# scripts/demo.sh links that alone, and the demo compiles none of the design routines.
add_library(adaptobs_precompiled_base STATIC ${ADAPTOBS_PRECOMPILED_BASE_SOURCES})
add_library(adaptobs::precompiled_base ALIAS adaptobs_precompiled_base)
target_compile_definitions(adaptobs_precompiled_base PUBLIC ADAPTOBS_PRECOMPILED)
target_link_libraries(adaptobs_precompiled_base PRIVATE adaptobs_developer_options PUBLIC adaptobs::adaptobs)
add_library(adaptobs_precompiled STATIC ${ADAPTOBS_PRECOMPILED_DESIGN_SOURCES} ${ADAPTOBS_PRECOMPILED_FLOAT_SOURCES})
add_library(adaptobs::precompiled ALIAS adaptobs_precompiled)
target_link_libraries(adaptobs_precompiled PRIVATE adaptobs_developer_options PUBLIC adaptobs::precompiled_base)
