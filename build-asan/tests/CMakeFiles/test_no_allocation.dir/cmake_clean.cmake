file(REMOVE_RECURSE
  "CMakeFiles/test_no_allocation.dir/no_allocation_dey_bhasin.cpp.o"
  "CMakeFiles/test_no_allocation.dir/no_allocation_dey_bhasin.cpp.o.d"
  "CMakeFiles/test_no_allocation.dir/no_allocation_guyader_zhang.cpp.o"
  "CMakeFiles/test_no_allocation.dir/no_allocation_guyader_zhang.cpp.o.d"
  "CMakeFiles/test_no_allocation.dir/support/allocation_counter.cpp.o"
  "CMakeFiles/test_no_allocation.dir/support/allocation_counter.cpp.o.d"
  "test_no_allocation"
  "test_no_allocation.pdb"
)

# Per-language clean rules from dependency scanning.
foreach(lang CXX)
  include(CMakeFiles/test_no_allocation.dir/cmake_clean_${lang}.cmake OPTIONAL)
endforeach()
