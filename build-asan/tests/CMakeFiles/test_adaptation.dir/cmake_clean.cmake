file(REMOVE_RECURSE
  "CMakeFiles/test_adaptation.dir/test_adaptation.cpp.o"
  "CMakeFiles/test_adaptation.dir/test_adaptation.cpp.o.d"
  "test_adaptation"
  "test_adaptation.pdb"
)

# Per-language clean rules from dependency scanning.
foreach(lang CXX)
  include(CMakeFiles/test_adaptation.dir/cmake_clean_${lang}.cmake OPTIONAL)
endforeach()
