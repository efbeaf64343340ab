# Helpers shared by the tests' CMakeLists (included from tests/CMakeLists.txt).
#
# WHEELSIM_MPI_TEST_ENV: environment for any test that calls mpirun. CI and the developer machines
#   run as root on 2 cores; OpenMPI refuses root and more ranks than free cores without these.
#   hwloc_base_binding_policy=none: Open MPI binds every np-1 and np-2 job to the first cores, so
#   two MPI tests side by side (ctest -j 2) would share core 0 (docs/coupled-runs.md "MPI launch").
# wheelsim_mpirun(<out-var> <np>): the launcher prefix as a list, e.g.
#   /usr/bin/mpiexec -n 2 — append the executable and its arguments.
# WHEELSIM_LIGGGHTS_WHEEL: path of the liggghts-wheel executable (generator expression).
# Tests that start N MPI ranks set the property PROCESSORS N, so `ctest -j` counts their cores.

set(WHEELSIM_MPI_TEST_ENV
    "OMPI_ALLOW_RUN_AS_ROOT=1;OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1;OMPI_MCA_rmaps_base_oversubscribe=1;OMPI_MCA_btl_vader_single_copy_mechanism=none;OMPI_MCA_hwloc_base_binding_policy=none")

function(wheelsim_mpirun out np)
  set(${out} ${MPIEXEC_EXECUTABLE} ${MPIEXEC_NUMPROC_FLAG} ${np} ${MPIEXEC_PREFLAGS} PARENT_SCOPE)
endfunction()

if(WHEELSIM_WITH_LIGGGHTS)
  set(WHEELSIM_LIGGGHTS_WHEEL "$<TARGET_FILE:liggghts-wheel>")
endif()
