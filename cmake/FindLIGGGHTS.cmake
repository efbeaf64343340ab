# FindLIGGGHTS.cmake — locate Debian's libliggghts-dev (LIGGGHTS 3.8), which ships no CMake config
# and no pkg-config file.
#
# Result: imported target LIGGGHTS::liggghts (headers as SYSTEM includes, so their ~26
# unused-parameter warnings do not drown ours; links MPI::MPI_C and defines the MPI C++-binding
# skips). Variables: LIGGGHTS_FOUND, LIGGGHTS_INCLUDE_DIR, LIGGGHTS_LIBRARY.
#
# Nothing else is defined on purpose: SUPERQUADRIC_ACTIVE_FLAG / NONSPHERICAL_ACTIVE_FLAG change
# class layouts and Debian's library was built without them (see ../shared/LIGGGHTS.md).

find_path(LIGGGHTS_INCLUDE_DIR NAMES lammps.h PATH_SUFFIXES liggghts
          DOC "Directory holding LIGGGHTS' lammps.h")
find_library(LIGGGHTS_LIBRARY NAMES liggghts DOC "LIGGGHTS shared library")

include(FindPackageHandleStandardArgs)
find_package_handle_standard_args(LIGGGHTS REQUIRED_VARS LIGGGHTS_LIBRARY LIGGGHTS_INCLUDE_DIR)

if(LIGGGHTS_FOUND AND NOT TARGET LIGGGHTS::liggghts)
  add_library(LIGGGHTS::liggghts UNKNOWN IMPORTED)
  set_target_properties(LIGGGHTS::liggghts PROPERTIES
    IMPORTED_LOCATION "${LIGGGHTS_LIBRARY}")
  target_include_directories(LIGGGHTS::liggghts SYSTEM INTERFACE "${LIGGGHTS_INCLUDE_DIR}")
  target_compile_definitions(LIGGGHTS::liggghts INTERFACE OMPI_SKIP_MPICXX=1 MPICH_SKIP_MPICXX=1)
  target_link_libraries(LIGGGHTS::liggghts INTERFACE MPI::MPI_C)
endif()
mark_as_advanced(LIGGGHTS_INCLUDE_DIR LIGGGHTS_LIBRARY)
