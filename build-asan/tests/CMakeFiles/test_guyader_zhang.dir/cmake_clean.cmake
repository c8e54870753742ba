file(REMOVE_RECURSE
  "CMakeFiles/test_guyader_zhang.dir/test_guyader_zhang.cpp.o"
  "CMakeFiles/test_guyader_zhang.dir/test_guyader_zhang.cpp.o.d"
  "test_guyader_zhang"
  "test_guyader_zhang.pdb"
)

# Per-language clean rules from dependency scanning.
foreach(lang CXX)
  include(CMakeFiles/test_guyader_zhang.dir/cmake_clean_${lang}.cmake OPTIONAL)
endforeach()
