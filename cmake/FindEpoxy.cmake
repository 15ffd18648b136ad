# Finds libepoxy (Debian: libepoxy-dev), which ships only a pkg-config file.
# Defines the imported target epoxy::epoxy.
find_package(PkgConfig QUIET)
if(PkgConfig_FOUND)
  pkg_check_modules(PC_EPOXY QUIET epoxy)
endif()
find_path(Epoxy_INCLUDE_DIR epoxy/gl.h HINTS ${PC_EPOXY_INCLUDE_DIRS})
find_library(Epoxy_LIBRARY NAMES epoxy HINTS ${PC_EPOXY_LIBRARY_DIRS})
include(FindPackageHandleStandardArgs)
find_package_handle_standard_args(Epoxy REQUIRED_VARS Epoxy_LIBRARY Epoxy_INCLUDE_DIR)
if(Epoxy_FOUND AND NOT TARGET epoxy::epoxy)
  add_library(epoxy::epoxy UNKNOWN IMPORTED)
  set_target_properties(epoxy::epoxy PROPERTIES IMPORTED_LOCATION "${Epoxy_LIBRARY}"
                                                INTERFACE_INCLUDE_DIRECTORIES "${Epoxy_INCLUDE_DIR}")
endif()
mark_as_advanced(Epoxy_INCLUDE_DIR Epoxy_LIBRARY)
