# FindDSDP
# --------
#
# Finds DSDP 5 (semidefinite programming solver; Debian package libdsdp-dev).
#
# Imported target:
#   DSDP::DSDP   the library, with the directory of dsdp5.h as a usage requirement
#
# Result variables:
#   DSDP_FOUND, DSDP_INCLUDE_DIR, DSDP_LIBRARY
#
# Debian installs the header as /usr/include/dsdp/dsdp5.h, a build from source
# as <prefix>/include/dsdp5.h; both are found, and sources include <dsdp5.h>.
# A static libdsdp.a needs LAPACK and BLAS, which are then linked as well.

find_path(DSDP_INCLUDE_DIR NAMES dsdp5.h PATH_SUFFIXES dsdp)
find_library(DSDP_LIBRARY NAMES dsdp)
mark_as_advanced(DSDP_INCLUDE_DIR DSDP_LIBRARY)

include(FindPackageHandleStandardArgs)
find_package_handle_standard_args(DSDP REQUIRED_VARS DSDP_LIBRARY DSDP_INCLUDE_DIR)

if(DSDP_FOUND AND NOT TARGET DSDP::DSDP)
  add_library(DSDP::DSDP UNKNOWN IMPORTED)
  set_target_properties(DSDP::DSDP PROPERTIES
    IMPORTED_LOCATION "${DSDP_LIBRARY}"
    INTERFACE_INCLUDE_DIRECTORIES "${DSDP_INCLUDE_DIR}")
  if(DSDP_LIBRARY MATCHES "\\.a$")
    find_package(LAPACK QUIET)
    if(LAPACK_FOUND)
      set_property(TARGET DSDP::DSDP APPEND PROPERTY INTERFACE_LINK_LIBRARIES ${LAPACK_LIBRARIES} m)
    endif()
  endif()
endif()
