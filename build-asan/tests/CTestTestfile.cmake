# CMake generated Testfile for 
# Source directory: /work/wt/issue-5/tests
# Build directory: /work/wt/issue-5/build-asan/tests
# 
# This file includes the relevant testing commands required for 
# testing this directory and lists subdirectories to be tested as well.
include("/work/wt/issue-5/build-asan/tests/test_discretization[1]_include.cmake")
include("/work/wt/issue-5/build-asan/tests/test_design[1]_include.cmake")
include("/work/wt/issue-5/build-asan/tests/test_guyader_zhang[1]_include.cmake")
include("/work/wt/issue-5/build-asan/tests/test_augmented_kalman[1]_include.cmake")
include("/work/wt/issue-5/build-asan/tests/test_simulation[1]_include.cmake")
include("/work/wt/issue-5/build-asan/tests/test_adaptation[1]_include.cmake")
include("/work/wt/issue-5/build-asan/tests/test_dey_bhasin[1]_include.cmake")
include("/work/wt/issue-5/build-asan/tests/test_no_allocation[1]_include.cmake")
add_test([=[package_install_and_consume]=] "/usr/bin/cmake" "-DADAPTOBS_SOURCE_DIR=/work/wt/issue-5" "-DADAPTOBS_BINARY_DIR=/work/wt/issue-5/build-asan" "-DWORK_DIR=/work/wt/issue-5/build-asan/tests/package_test" "-DCXX_COMPILER=/usr/bin/c++" "-DEIGEN_DIR=/usr/share/eigen3/cmake" "-P" "/work/wt/issue-5/tests/package/TestInstalledPackage.cmake")
set_tests_properties([=[package_install_and_consume]=] PROPERTIES  TIMEOUT "300" _BACKTRACE_TRIPLES "/work/wt/issue-5/tests/CMakeLists.txt;29;add_test;/work/wt/issue-5/tests/CMakeLists.txt;0;")
