file(REMOVE_RECURSE
  "CMakeFiles/dey_bhasin_mimo.dir/dey_bhasin_mimo.cpp.o"
  "CMakeFiles/dey_bhasin_mimo.dir/dey_bhasin_mimo.cpp.o.d"
  "dey_bhasin_mimo"
  "dey_bhasin_mimo.pdb"
)

# Per-language clean rules from dependency scanning.
foreach(lang CXX)
  include(CMakeFiles/dey_bhasin_mimo.dir/cmake_clean_${lang}.cmake OPTIONAL)
endforeach()
