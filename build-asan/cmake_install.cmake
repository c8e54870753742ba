# Install script for directory: /work/wt/issue-5

# Set the install prefix
if(NOT DEFINED CMAKE_INSTALL_PREFIX)
  set(CMAKE_INSTALL_PREFIX "/usr/local")
endif()
string(REGEX REPLACE "/$" "" CMAKE_INSTALL_PREFIX "${CMAKE_INSTALL_PREFIX}")

# Set the install configuration name.
if(NOT DEFINED CMAKE_INSTALL_CONFIG_NAME)
  if(BUILD_TYPE)
    string(REGEX REPLACE "^[^A-Za-z0-9_]+" ""
           CMAKE_INSTALL_CONFIG_NAME "${BUILD_TYPE}")
  else()
    set(CMAKE_INSTALL_CONFIG_NAME "Debug")
  endif()
  message(STATUS "Install configuration: \"${CMAKE_INSTALL_CONFIG_NAME}\"")
endif()

# Set the component getting installed.
if(NOT CMAKE_INSTALL_COMPONENT)
  if(COMPONENT)
    message(STATUS "Install component: \"${COMPONENT}\"")
    set(CMAKE_INSTALL_COMPONENT "${COMPONENT}")
  else()
    set(CMAKE_INSTALL_COMPONENT)
  endif()
endif()

# Install shared libraries without execute permission?
if(NOT DEFINED CMAKE_INSTALL_SO_NO_EXE)
  set(CMAKE_INSTALL_SO_NO_EXE "1")
endif()

# Is this installation the result of a crosscompile?
if(NOT DEFINED CMAKE_CROSSCOMPILING)
  set(CMAKE_CROSSCOMPILING "FALSE")
endif()

# Set default install directory permissions.
if(NOT DEFINED CMAKE_OBJDUMP)
  set(CMAKE_OBJDUMP "/usr/bin/objdump")
endif()

if(CMAKE_INSTALL_COMPONENT STREQUAL "Unspecified" OR NOT CMAKE_INSTALL_COMPONENT)
  file(INSTALL DESTINATION "${CMAKE_INSTALL_PREFIX}/include/adaptobs" TYPE FILE FILES "/work/wt/issue-5/include/adaptobs/adaptobs.hpp")
  file(INSTALL DESTINATION "${CMAKE_INSTALL_PREFIX}/include/adaptobs/adaptation" TYPE FILE FILES
    "/work/wt/issue-5/include/adaptobs/adaptation/adaptation_law.hpp"
    "/work/wt/issue-5/include/adaptobs/adaptation/covariance_resetting.hpp"
    "/work/wt/issue-5/include/adaptobs/adaptation/exponential_forgetting.hpp"
    "/work/wt/issue-5/include/adaptobs/adaptation/normalized_gradient.hpp"
    "/work/wt/issue-5/include/adaptobs/adaptation/recursive_least_squares.hpp"
    "/work/wt/issue-5/include/adaptobs/adaptation/rls_correction.hpp"
    )
  file(INSTALL DESTINATION "${CMAKE_INSTALL_PREFIX}/include/adaptobs/baselines" TYPE FILE FILES "/work/wt/issue-5/include/adaptobs/baselines/augmented_kalman.hpp")
  file(INSTALL DESTINATION "${CMAKE_INSTALL_PREFIX}/include/adaptobs/core" TYPE FILE FILES
    "/work/wt/issue-5/include/adaptobs/core/commit.hpp"
    "/work/wt/issue-5/include/adaptobs/core/dimensions.hpp"
    "/work/wt/issue-5/include/adaptobs/core/discrete_model.hpp"
    "/work/wt/issue-5/include/adaptobs/core/discretization.hpp"
    "/work/wt/issue-5/include/adaptobs/core/matrix_exponential.hpp"
    "/work/wt/issue-5/include/adaptobs/core/observer.hpp"
    "/work/wt/issue-5/include/adaptobs/core/products.hpp"
    "/work/wt/issue-5/include/adaptobs/core/spectral_norm.hpp"
    "/work/wt/issue-5/include/adaptobs/core/status.hpp"
    "/work/wt/issue-5/include/adaptobs/core/validation.hpp"
    )
  file(INSTALL DESTINATION "${CMAKE_INSTALL_PREFIX}/include/adaptobs/design" TYPE FILE FILES
    "/work/wt/issue-5/include/adaptobs/design/dare.hpp"
    "/work/wt/issue-5/include/adaptobs/design/excitation_monitor.hpp"
    "/work/wt/issue-5/include/adaptobs/design/riccati_recursion.hpp"
    "/work/wt/issue-5/include/adaptobs/design/stability.hpp"
    )
  file(INSTALL DESTINATION "${CMAKE_INSTALL_PREFIX}/include/adaptobs/observers" TYPE FILE FILES
    "/work/wt/issue-5/include/adaptobs/observers/canonical_form_filters.hpp"
    "/work/wt/issue-5/include/adaptobs/observers/dey_bhasin.hpp"
    "/work/wt/issue-5/include/adaptobs/observers/guyader_zhang.hpp"
    )
  file(INSTALL DESTINATION "${CMAKE_INSTALL_PREFIX}/include/adaptobs/simulation" TYPE FILE FILES
    "/work/wt/issue-5/include/adaptobs/simulation/discrete_plant.hpp"
    "/work/wt/issue-5/include/adaptobs/simulation/runner.hpp"
    "/work/wt/issue-5/include/adaptobs/simulation/series_table.hpp"
    )
endif()

if(CMAKE_INSTALL_COMPONENT STREQUAL "Unspecified" OR NOT CMAKE_INSTALL_COMPONENT)
  if(EXISTS "$ENV{DESTDIR}${CMAKE_INSTALL_PREFIX}/share/cmake/adaptobs/adaptobsTargets.cmake")
    file(DIFFERENT _cmake_export_file_changed FILES
         "$ENV{DESTDIR}${CMAKE_INSTALL_PREFIX}/share/cmake/adaptobs/adaptobsTargets.cmake"
         "/work/wt/issue-5/build-asan/CMakeFiles/Export/04c3fa81a895244884ab260890800fc4/adaptobsTargets.cmake")
    if(_cmake_export_file_changed)
      file(GLOB _cmake_old_config_files "$ENV{DESTDIR}${CMAKE_INSTALL_PREFIX}/share/cmake/adaptobs/adaptobsTargets-*.cmake")
      if(_cmake_old_config_files)
        string(REPLACE ";" ", " _cmake_old_config_files_text "${_cmake_old_config_files}")
        message(STATUS "Old export file \"$ENV{DESTDIR}${CMAKE_INSTALL_PREFIX}/share/cmake/adaptobs/adaptobsTargets.cmake\" will be replaced.  Removing files [${_cmake_old_config_files_text}].")
        unset(_cmake_old_config_files_text)
        file(REMOVE ${_cmake_old_config_files})
      endif()
      unset(_cmake_old_config_files)
    endif()
    unset(_cmake_export_file_changed)
  endif()
  file(INSTALL DESTINATION "${CMAKE_INSTALL_PREFIX}/share/cmake/adaptobs" TYPE FILE FILES "/work/wt/issue-5/build-asan/CMakeFiles/Export/04c3fa81a895244884ab260890800fc4/adaptobsTargets.cmake")
endif()

if(CMAKE_INSTALL_COMPONENT STREQUAL "Unspecified" OR NOT CMAKE_INSTALL_COMPONENT)
  file(INSTALL DESTINATION "${CMAKE_INSTALL_PREFIX}/share/cmake/adaptobs" TYPE FILE FILES
    "/work/wt/issue-5/build-asan/adaptobsConfig.cmake"
    "/work/wt/issue-5/build-asan/adaptobsConfigVersion.cmake"
    )
endif()

if(CMAKE_INSTALL_COMPONENT STREQUAL "Unspecified" OR NOT CMAKE_INSTALL_COMPONENT)
  file(INSTALL DESTINATION "${CMAKE_INSTALL_PREFIX}/share/doc/adaptobs" TYPE FILE FILES
    "/work/wt/issue-5/LICENSE"
    "/work/wt/issue-5/README.md"
    )
endif()

if(NOT CMAKE_INSTALL_LOCAL_ONLY)
  # Include the install script for the subdirectory.
  include("/work/wt/issue-5/build-asan/tests/cmake_install.cmake")
endif()

if(NOT CMAKE_INSTALL_LOCAL_ONLY)
  # Include the install script for the subdirectory.
  include("/work/wt/issue-5/build-asan/examples/cmake_install.cmake")
endif()

if(CMAKE_INSTALL_COMPONENT)
  set(CMAKE_INSTALL_MANIFEST "install_manifest_${CMAKE_INSTALL_COMPONENT}.txt")
else()
  set(CMAKE_INSTALL_MANIFEST "install_manifest.txt")
endif()

string(REPLACE ";" "\n" CMAKE_INSTALL_MANIFEST_CONTENT
       "${CMAKE_INSTALL_MANIFEST_FILES}")
file(WRITE "/work/wt/issue-5/build-asan/${CMAKE_INSTALL_MANIFEST}"
     "${CMAKE_INSTALL_MANIFEST_CONTENT}")
