if(EXISTS "/work/wt/issue-5/build-asan/tests/test_dey_bhasin")
  if(NOT EXISTS "/work/wt/issue-5/build-asan/tests/test_dey_bhasin[1]_tests.cmake" OR
     NOT "/work/wt/issue-5/build-asan/tests/test_dey_bhasin[1]_tests.cmake" IS_NEWER_THAN "/work/wt/issue-5/build-asan/tests/test_dey_bhasin" OR
     NOT "/work/wt/issue-5/build-asan/tests/test_dey_bhasin[1]_tests.cmake" IS_NEWER_THAN "${CMAKE_CURRENT_LIST_FILE}")
    include("/usr/share/cmake-3.25/Modules/GoogleTestAddTests.cmake")
    gtest_discover_tests_impl(
      TEST_EXECUTABLE [==[/work/wt/issue-5/build-asan/tests/test_dey_bhasin]==]
      TEST_EXECUTOR [==[]==]
      TEST_WORKING_DIR [==[/work/wt/issue-5/build-asan/tests]==]
      TEST_EXTRA_ARGS [==[]==]
      TEST_PROPERTIES [==[]==]
      TEST_PREFIX [==[]==]
      TEST_SUFFIX [==[]==]
      TEST_FILTER [==[]==]
      NO_PRETTY_TYPES [==[FALSE]==]
      NO_PRETTY_VALUES [==[FALSE]==]
      TEST_LIST [==[test_dey_bhasin_TESTS]==]
      CTEST_FILE [==[/work/wt/issue-5/build-asan/tests/test_dey_bhasin[1]_tests.cmake]==]
      TEST_DISCOVERY_TIMEOUT [==[60]==]
      TEST_XML_OUTPUT_DIR [==[]==]
    )
  endif()
  include("/work/wt/issue-5/build-asan/tests/test_dey_bhasin[1]_tests.cmake")
else()
  add_test(test_dey_bhasin_NOT_BUILT test_dey_bhasin_NOT_BUILT)
endif()
