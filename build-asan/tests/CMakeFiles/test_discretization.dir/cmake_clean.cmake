file(REMOVE_RECURSE
  "CMakeFiles/test_discretization.dir/test_discretization.cpp.o"
  "CMakeFiles/test_discretization.dir/test_discretization.cpp.o.d"
  "test_discretization"
  "test_discretization.pdb"
)

# Per-language clean rules from dependency scanning.
foreach(lang CXX)
  include(CMakeFiles/test_discretization.dir/cmake_clean_${lang}.cmake OPTIONAL)
endforeach()
