# ferret_module(<name> [PUBLIC_DEPS ...] [PRIVATE_DEPS ...])
# One library a module: <name>/src/*.cpp, public headers in <name>/include/ferret/<name>/.
# Target ferret_<name>, alias ferret::<name>, exported as ferret::<name>.
# The folder name may differ from <name> (tether_model/ builds ferret::tether).
function(ferret_module name)
  cmake_parse_arguments(M "" "" "PUBLIC_DEPS;PRIVATE_DEPS" ${ARGN})
  file(GLOB sources CONFIGURE_DEPENDS ${CMAKE_CURRENT_SOURCE_DIR}/src/*.cpp)
  set(target ferret_${name})
  if(NOT sources)
    # A module whose first sources have not landed yet still links as a library.
    set(sources ${CMAKE_CURRENT_BINARY_DIR}/ferret_${name}_empty.cpp)
    file(WRITE ${sources} "// ferret_${name} has no sources yet\n")
  endif()
  add_library(${target} ${sources})
  add_library(ferret::${name} ALIAS ${target})
  set_target_properties(${target} PROPERTIES EXPORT_NAME ${name} OUTPUT_NAME ferret_${name}
                                             VERSION ${PROJECT_VERSION} SOVERSION ${PROJECT_VERSION_MAJOR})
  target_include_directories(${target} PUBLIC
    $<BUILD_INTERFACE:${CMAKE_CURRENT_SOURCE_DIR}/include>
    $<INSTALL_INTERFACE:${CMAKE_INSTALL_INCLUDEDIR}>)
  target_link_libraries(${target} PUBLIC ${M_PUBLIC_DEPS} PRIVATE ${M_PRIVATE_DEPS})
  ferret_warnings(${target})
  install(TARGETS ${target} EXPORT ferretTargets
          LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR}
          ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR}
          RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
  install(DIRECTORY ${CMAKE_CURRENT_SOURCE_DIR}/include/ DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
  set_property(GLOBAL APPEND PROPERTY FERRET_MODULE_TARGETS ${target})
endfunction()

# Project code builds warning-free; third-party headers are SYSTEM includes.
function(ferret_warnings target)
  target_compile_options(${target} PRIVATE -Wall -Wextra -Werror)
endfunction()
