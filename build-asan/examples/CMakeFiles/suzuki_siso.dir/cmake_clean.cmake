file(REMOVE_RECURSE
  "CMakeFiles/suzuki_siso.dir/suzuki_siso.cpp.o"
  "CMakeFiles/suzuki_siso.dir/suzuki_siso.cpp.o.d"
  "suzuki_siso"
  "suzuki_siso.pdb"
)

# Per-language clean rules from dependency scanning.
foreach(lang CXX)
  include(CMakeFiles/suzuki_siso.dir/cmake_clean_${lang}.cmake OPTIONAL)
endforeach()
