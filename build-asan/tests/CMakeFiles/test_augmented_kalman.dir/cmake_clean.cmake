file(REMOVE_RECURSE
  "CMakeFiles/test_augmented_kalman.dir/test_augmented_kalman.cpp.o"
  "CMakeFiles/test_augmented_kalman.dir/test_augmented_kalman.cpp.o.d"
  "test_augmented_kalman"
  "test_augmented_kalman.pdb"
)

# Per-language clean rules from dependency scanning.
foreach(lang CXX)
  include(CMakeFiles/test_augmented_kalman.dir/cmake_clean_${lang}.cmake OPTIONAL)
endforeach()
