file(REMOVE_RECURSE
  "CMakeFiles/test_dey_bhasin.dir/test_dey_bhasin_mimo.cpp.o"
  "CMakeFiles/test_dey_bhasin.dir/test_dey_bhasin_mimo.cpp.o.d"
  "CMakeFiles/test_dey_bhasin.dir/test_dey_bhasin_siso.cpp.o"
  "CMakeFiles/test_dey_bhasin.dir/test_dey_bhasin_siso.cpp.o.d"
  "test_dey_bhasin"
  "test_dey_bhasin.pdb"
)

# Per-language clean rules from dependency scanning.
foreach(lang CXX)
  include(CMakeFiles/test_dey_bhasin.dir/cmake_clean_${lang}.cmake OPTIONAL)
endforeach()
