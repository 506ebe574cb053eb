# cmake -P script run by ctest (see CMakeLists.txt beside it).
file(REMOVE_RECURSE ${WORK_DIR})
set(prefix ${WORK_DIR}/prefix)

function(run)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "failed (${rc}): ${ARGN}\n${out}\n${err}")
  endif()
  set(last_output "${out}" PARENT_SCOPE)
endfunction()

run(${CMAKE_COMMAND} --install ${FERRET_BUILD_DIR} --prefix ${prefix})
foreach(required bin/ferret include/ferret/core/error.hpp include/ferret/mapping/occupancy_map_2d.hpp
                 share/ferret/models/miniugv.urdf share/ferret/models/m100.urdf)
  if(NOT EXISTS ${prefix}/${required})
    message(FATAL_ERROR "install is missing ${required}")
  endif()
endforeach()
file(GLOB config_files ${prefix}/lib*/cmake/ferret/ferretConfig.cmake ${prefix}/lib/*/cmake/ferret/ferretConfig.cmake)
if(NOT config_files)
  message(FATAL_ERROR "install is missing ferretConfig.cmake")
endif()

run(${CMAKE_COMMAND} -S ${CONSUMER_SOURCE_DIR} -B ${WORK_DIR}/build -G ${GENERATOR}
    -DCMAKE_PREFIX_PATH=${prefix} -DCMAKE_BUILD_TYPE=Release
    "-DCMAKE_CXX_FLAGS=${CONSUMER_CXX_FLAGS}")  # sanitizer builds: the consumer must be instrumented too
run(${CMAKE_COMMAND} --build ${WORK_DIR}/build)
run(${WORK_DIR}/build/consumer ${WORK_DIR}/roundtrip.yaml)
if(NOT last_output MATCHES "consumer ok: 4x3 cells, 1 occupied")
  message(FATAL_ERROR "consumer printed: ${last_output}")
endif()
# The installed CLI runs from the prefix (RPATH to the installed libraries).
run(${prefix}/bin/ferret --version)
message(STATUS "consumer: ${last_output}")
