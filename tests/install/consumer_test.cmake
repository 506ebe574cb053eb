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
                 include/ferret/planning/uav_approach.hpp include/ferret/planning/ugv_path.hpp
                 share/ferret/models/miniugv.urdf share/ferret/models/m100.urdf
                 share/ferret/worlds/default.yaml share/ferret/plans/detour_ugv.json
                 share/ferret/maps/sparse.yaml share/ferret/maps/sparse.pgm
                 share/ferret/config/mission.yaml share/ferret/plot_experiment.py
                 share/ferret/examples/library/main.cpp share/ferret/examples/library/CMakeLists.txt)
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
# The library example (examples/library), built from its installed copy against the
# installed package, run from a directory of its own: everything it reads must come
# from the prefix (data_path() beside the installed libferret_core), none from the
# source tree, whose build-tree library is the only one that reads it.
set(example_build ${WORK_DIR}/example)
run(${CMAKE_COMMAND} -S ${prefix}/share/ferret/examples/library -B ${example_build} -G ${GENERATOR}
    -DCMAKE_PREFIX_PATH=${prefix} -DCMAKE_BUILD_TYPE=Release "-DCMAKE_CXX_FLAGS=${CONSUMER_CXX_FLAGS}")
run(${CMAKE_COMMAND} --build ${example_build})
set(run_dir ${WORK_DIR}/run)
file(MAKE_DIRECTORY ${run_dir}/plans)
execute_process(COMMAND ${example_build}/ferret_library_example ${run_dir}/plans WORKING_DIRECTORY ${run_dir}
                RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "library example failed (${rc}):\n${out}\n${err}")
endif()
foreach(expected "approach: solved, [0-9]+ states" "ugv: solved, [0-9]+ states" "approach check: valid"
                 "ugv check: valid" "search: cdos found the object in")
  if(NOT out MATCHES "${expected}")
    message(FATAL_ERROR "library example did not print '${expected}':\n${out}")
  endif()
endforeach()
file(REAL_PATH ${prefix} real_prefix)
foreach(line world model)
  string(REGEX MATCH "${line}: ([^\n]*)" _ "${out}")
  file(REAL_PATH "${CMAKE_MATCH_1}" found)
  string(FIND "${found}" "${real_prefix}/share/ferret/" at)
  if(NOT at EQUAL 0)
    message(FATAL_ERROR "library example read its ${line} from ${found}, not from the prefix ${real_prefix}")
  endif()
endforeach()
foreach(plan approach.json ugv.json)
  if(NOT EXISTS ${run_dir}/plans/${plan})
    message(FATAL_ERROR "library example wrote no ${plan}")
  endif()
endforeach()
# The installed CLI validates the example's miniUGV plan (its robot_model the installed URDF).
run(${prefix}/bin/ferret validate --world ${prefix}/share/ferret/worlds/default.yaml --plan ${run_dir}/plans/ugv.json)
if(NOT last_output MATCHES "^valid:")
  message(FATAL_ERROR "ferret validate of the example's plan printed: ${last_output}")
endif()
message(STATUS "library example: ${out}")

# The installed CLI runs from the prefix (RPATH to the installed libraries).
run(${prefix}/bin/ferret --version)
message(STATUS "consumer: ${last_output}")
