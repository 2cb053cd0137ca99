# ctest script: installs the build in BUILD_DIR to a prefix under WORK_DIR, configures and builds the
# examples against it with find_package(palpate), and runs both examples headless.
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
foreach(example existing_app existing_app_deformed)
  run("run ${example} headless" "${WORK_DIR}/build/${example}" --headless "${WORK_DIR}/${example}.png")
  if(NOT EXISTS "${WORK_DIR}/${example}.png")
    message(FATAL_ERROR "${example} wrote no ${WORK_DIR}/${example}.png")
  endif()
endforeach()
file(SHA256 "${WORK_DIR}/existing_app.png" plain)
file(SHA256 "${WORK_DIR}/existing_app_deformed.png" deformed)
if(plain STREQUAL deformed)
  message(FATAL_ERROR "the deformed example drew the same image as the plain one")
endif()
