# `cmake --install build --prefix P` (docs/building.md, "Install"): every tool, runnable from P.
#
#   P/bin/                 the executables (wheel-rig, wong-reece, wheel-mesh, scm-soil,
#                          liggghts-wheel) and links to the Python and shell tools (wheel-cosim,
#                          wheel-sweep, park-running, wheelsim-post, soil-lab) in share/wheelsim
#   P/share/wheelsim/      the parts of the source tree the tools and the shipped configs use, at
#                          the same relative places as in a checkout, so that the tools' own
#                          lookups (<root>/inputs, <root>/build/bin, <root>/build/meshes) and the
#                          configs' relative paths (../../build/meshes/wheel2.obj) work unchanged:
#                            inputs/, wheel_dynamics/examples/, meshes/catalog.toml,
#                            scripts/ (wheel-cosim, wheel-sweep, park-running, wheelsim_sweep/),
#                            postprocess/ (wheelsim-post, wheelsim_post/),
#                            soil_lab/ (soil-lab, soil_lab_py/, decks/),
#                            build/meshes/ (the generated wheels), build/bin -> ../../../bin,
#                            VERSION ("<version> <git revision>", for the Python tools' --version)
#   P/share/doc/wheelsim/  README.md, LICENSE, docs/
# The Python tools find share/wheelsim from their own (link-resolved) location; without a
# CMakeLists.txt there they write their default run directories under the working directory.

set(_share share/wheelsim)
set(_src "${PROJECT_SOURCE_DIR}")
set(_no_cache PATTERN "__pycache__" EXCLUDE PATTERN "*.pyc" EXCLUDE)

# --- executables (wong-reece, wheel-rig, liggghts-wheel and scm-soil install themselves) ---
install(TARGETS wheel-mesh RUNTIME DESTINATION bin)

# --- the Python and shell tools, at their source-tree places under share/wheelsim ---
install(PROGRAMS "${_src}/scripts/wheel-cosim" "${_src}/scripts/wheel-sweep"
                 "${_src}/scripts/park-running" DESTINATION ${_share}/scripts)
install(DIRECTORY "${_src}/scripts/wheelsim_sweep" DESTINATION ${_share}/scripts ${_no_cache})
install(PROGRAMS "${_src}/postprocess/wheelsim-post" DESTINATION ${_share}/postprocess)
install(DIRECTORY "${_src}/postprocess/wheelsim_post" DESTINATION ${_share}/postprocess
        ${_no_cache})
install(PROGRAMS "${_src}/soil_lab/soil-lab" DESTINATION ${_share}/soil_lab)
install(DIRECTORY "${_src}/soil_lab/soil_lab_py" "${_src}/soil_lab/decks"
        DESTINATION ${_share}/soil_lab ${_no_cache})

# --- data: decks, soils, sweeps, rig configs, the wheel catalogue and the generated wheels ---
install(DIRECTORY "${_src}/inputs" DESTINATION ${_share} PATTERN "CMakeLists.txt" EXCLUDE)
install(DIRECTORY "${_src}/wheel_dynamics/examples" DESTINATION ${_share}/wheel_dynamics)
install(FILES "${_src}/meshes/catalog.toml" DESTINATION ${_share}/meshes)
install(DIRECTORY "${WHEELSIM_MESH_DIR}/" DESTINATION ${_share}/build/meshes
        FILES_MATCHING PATTERN "*.obj" PATTERN "*.stl" PATTERN "*.props.toml"
        PATTERN "CMakeFiles" EXCLUDE)
# generated/VERSION: written with wheelsim_version.h at every build (cmake/WheelsimGitRevision.cmake)
install(FILES "${CMAKE_BINARY_DIR}/generated/VERSION" DESTINATION ${_share})

# --- documentation and licence ---
install(FILES "${_src}/README.md" "${_src}/LICENSE" DESTINATION share/doc/wheelsim)
install(DIRECTORY "${_src}/docs" DESTINATION share/doc/wheelsim)

# --- links: P/bin/<tool> -> ../share/wheelsim/<dir>/<tool>; share/wheelsim/build/bin -> P/bin ---
install(CODE [[
  set(_p "$ENV{DESTDIR}${CMAKE_INSTALL_PREFIX}")
  file(MAKE_DIRECTORY "${_p}/bin" "${_p}/share/wheelsim/build")
  foreach(_tool scripts/wheel-cosim scripts/wheel-sweep scripts/park-running
                postprocess/wheelsim-post soil_lab/soil-lab)
    get_filename_component(_name "${_tool}" NAME)
    file(REMOVE "${_p}/bin/${_name}")
    file(CREATE_LINK "../share/wheelsim/${_tool}" "${_p}/bin/${_name}" SYMBOLIC)
    message(STATUS "Installing: ${_p}/bin/${_name} -> ../share/wheelsim/${_tool}")
  endforeach()
  file(REMOVE "${_p}/share/wheelsim/build/bin")
  file(CREATE_LINK "../../../bin" "${_p}/share/wheelsim/build/bin" SYMBOLIC)
  message(STATUS "Installing: ${_p}/share/wheelsim/build/bin -> ../../../bin")
]])
