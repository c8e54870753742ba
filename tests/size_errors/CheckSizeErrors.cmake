# Compiles wrong_sizes.cpp once correctly, then once per WRONG_* macro, and
# requires each wrong one to fail with exactly one error: the static_assert
# that names the argument.
# Usage: cmake -DCXX=... -DINCLUDES="dir;dir" -DSOURCE=wrong_sizes.cpp -P CheckSizeErrors.cmake
set(flags -std=c++20 -fsyntax-only)
foreach(dir IN LISTS INCLUDES)
  list(APPEND flags "-I${dir}")
endforeach()
execute_process(COMMAND "${CXX}" ${flags} "${SOURCE}" RESULT_VARIABLE rc ERROR_VARIABLE err)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "the correct sizes do not compile:\n${err}")
endif()
foreach(case "WRONG_B;DiscreteLtiModel: B must be nx x nu"
             "WRONG_K;GuyaderZhangObserver: K must be nx x ny"
             "WRONG_THETA0;GuyaderZhangObserver: theta0 must be an np-vector")
  list(GET case 0 macro)
  list(GET case 1 expected)
  execute_process(COMMAND "${CXX}" ${flags} "-D${macro}" "${SOURCE}" RESULT_VARIABLE rc ERROR_VARIABLE err)
  string(REGEX MATCHALL "error:" errors "${err}")
  list(LENGTH errors count)
  if(rc EQUAL 0 OR NOT err MATCHES "${expected}" OR NOT count EQUAL 1)
    message(FATAL_ERROR "${macro}: expected one error, '${expected}'; got ${count}:\n${err}")
  endif()
  message(STATUS "${macro}: ${expected}")
endforeach()
