
# Consider dependencies only in project.
set(CMAKE_DEPENDS_IN_PROJECT_ONLY OFF)

# The set of languages for which implicit dependencies are needed:
set(CMAKE_DEPENDS_LANGUAGES
  )

# The set of dependency files which are needed:
set(CMAKE_DEPENDS_DEPENDENCY_FILES
  "/work/wt/issue-5/tests/no_allocation_dey_bhasin.cpp" "tests/CMakeFiles/test_no_allocation.dir/no_allocation_dey_bhasin.cpp.o" "gcc" "tests/CMakeFiles/test_no_allocation.dir/no_allocation_dey_bhasin.cpp.o.d"
  "/work/wt/issue-5/tests/no_allocation_guyader_zhang.cpp" "tests/CMakeFiles/test_no_allocation.dir/no_allocation_guyader_zhang.cpp.o" "gcc" "tests/CMakeFiles/test_no_allocation.dir/no_allocation_guyader_zhang.cpp.o.d"
  "/work/wt/issue-5/tests/support/allocation_counter.cpp" "tests/CMakeFiles/test_no_allocation.dir/support/allocation_counter.cpp.o" "gcc" "tests/CMakeFiles/test_no_allocation.dir/support/allocation_counter.cpp.o.d"
  )

# Targets to which this target links.
set(CMAKE_TARGET_LINKED_INFO_FILES
  )

# Fortran module output directory.
set(CMAKE_Fortran_TARGET_MODULE_DIR "")
