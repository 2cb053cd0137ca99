# ctest script: installs the build in BUILD_DIR to a prefix under WORK_DIR, then builds the examples
# against it as their kinds of host would: gl45_* and core33_* with CMake's find_package(palpate),
# legacy_* with the plain Makefile through pkg-config. The test then runs them.
# Inputs: BUILD_DIR, EXAMPLES_DIR, WORK_DIR, GENERATOR, BUILD_TYPE, CXX_FLAGS, LINKER_FLAGS.
file(REMOVE_RECURSE "${WORK_DIR}")
set(prefix "${WORK_DIR}/prefix")

function(run what)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE status OUTPUT_VARIABLE out ERROR_VARIABLE out)
  if(NOT status EQUAL 0)
    message(FATAL_ERROR "${what} failed (${status}):\n${out}")
  endif()
  message(STATUS "${what}: ok")
endfunction()

run("install palpate to ${prefix}" ${CMAKE_COMMAND} --install "${BUILD_DIR}" --prefix "${prefix}")
run("configure the examples" ${CMAKE_COMMAND} -S "${EXAMPLES_DIR}" -B "${WORK_DIR}/build" -G "${GENERATOR}"
    "-DCMAKE_PREFIX_PATH=${prefix}" "-DCMAKE_BUILD_TYPE=${BUILD_TYPE}" "-DCMAKE_CXX_FLAGS=${CXX_FLAGS}"
    "-DCMAKE_EXE_LINKER_FLAGS=${LINKER_FLAGS}")
run("build the examples" ${CMAKE_COMMAND} --build "${WORK_DIR}/build" -j 2)
file(MAKE_DIRECTORY "${WORK_DIR}/build/legacy")
run("make the legacy examples" ${CMAKE_COMMAND} -E env "PKG_CONFIG_PATH=${prefix}/lib/pkgconfig"
    make -C "${WORK_DIR}/build/legacy" -f "${EXAMPLES_DIR}/Makefile" "VPATH=${EXAMPLES_DIR}"
    "CXXFLAGS=${CXX_FLAGS}" "LDFLAGS=${LINKER_FLAGS}" -j 2)
