# CMake generated Testfile for 
# Source directory: /work/wt/issue-5/examples
# Build directory: /work/wt/issue-5/build-asan/examples
# 
# This file includes the relevant testing commands required for 
# testing this directory and lists subdirectories to be tested as well.
add_test([=[example_satellite]=] "/work/wt/issue-5/build-asan/examples/satellite" "--out" "/work/wt/issue-5/build-asan/examples/example_output")
set_tests_properties([=[example_satellite]=] PROPERTIES  _BACKTRACE_TRIPLES "/work/wt/issue-5/examples/CMakeLists.txt;9;add_test;/work/wt/issue-5/examples/CMakeLists.txt;14;adaptobs_add_example;/work/wt/issue-5/examples/CMakeLists.txt;0;")
add_test([=[example_dey_bhasin_mimo]=] "/work/wt/issue-5/build-asan/examples/dey_bhasin_mimo" "--out" "/work/wt/issue-5/build-asan/examples/example_output")
set_tests_properties([=[example_dey_bhasin_mimo]=] PROPERTIES  _BACKTRACE_TRIPLES "/work/wt/issue-5/examples/CMakeLists.txt;9;add_test;/work/wt/issue-5/examples/CMakeLists.txt;15;adaptobs_add_example;/work/wt/issue-5/examples/CMakeLists.txt;0;")
add_test([=[example_suzuki_siso]=] "/work/wt/issue-5/build-asan/examples/suzuki_siso" "--out" "/work/wt/issue-5/build-asan/examples/example_output")
set_tests_properties([=[example_suzuki_siso]=] PROPERTIES  _BACKTRACE_TRIPLES "/work/wt/issue-5/examples/CMakeLists.txt;9;add_test;/work/wt/issue-5/examples/CMakeLists.txt;16;adaptobs_add_example;/work/wt/issue-5/examples/CMakeLists.txt;0;")
