# Debian's OpenSubdivConfig.cmake names static libraries the package does not ship, so
# find_package(OpenSubdiv) is a hard error (TOOLCHAIN.md). Define the target by hand.
find_path(OSD_INCLUDE_DIR opensubdiv/far/topologyRefiner.h)
find_library(OSD_CPU_LIBRARY NAMES osdCPU)
if(OSD_INCLUDE_DIR AND OSD_CPU_LIBRARY)
  add_library(OpenSubdiv::osdCPU SHARED IMPORTED)
  set_target_properties(OpenSubdiv::osdCPU PROPERTIES
    IMPORTED_LOCATION "${OSD_CPU_LIBRARY}"
    INTERFACE_INCLUDE_DIRECTORIES "${OSD_INCLUDE_DIR}")
  set(SUBLIFT_HAVE_OSD ON)
else()
  message(FATAL_ERROR "OpenSubdiv (libosd-dev) not found: scripts/test installs it")
endif()
