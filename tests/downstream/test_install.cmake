# The test install_downstream: `cmake --install` this build into a prefix in the build tree,
# then configure, build and run the project beside this file (patch_test.cpp) against that
# prefix alone, as a project of someone else's would.
#   cmake -DBINARY_DIR=... -DSOURCE_DIR=... -DWORK=... -DGENERATOR=... [-DMAKE_PROGRAM=...]
#         -DCXX_COMPILER=... [-DBUILD_TYPE=...] [-DCXX_FLAGS=...] [-DLINKER_FLAGS=...] -P test_install.cmake
function(run what)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE status OUTPUT_VARIABLE out ERROR_VARIABLE out)
  if(NOT status EQUAL 0)
    message(FATAL_ERROR "${what} failed (exit status ${status}):\n${out}")
  endif()
  set(output "${out}" PARENT_SCOPE)
endfunction()

set(prefix ${WORK}/prefix)
set(build ${WORK}/build)
file(REMOVE_RECURSE ${WORK})

# 1. Install the library, its headers and its CMake package (not the chapter programs).
if(NOT EXISTS ${BINARY_DIR}/cmake_install.cmake)
  message(FATAL_ERROR "${BINARY_DIR} is not a configured build tree")
endif()
set(config_args "")
if(BUILD_TYPE)
  set(config_args --config ${BUILD_TYPE})
endif()
run("cmake --install (is the library built? the test runs after the build)"
    ${CMAKE_COMMAND} --install ${BINARY_DIR} --prefix ${prefix} --component development ${config_args})
foreach(file include/kerf/mesh/box_mesh.hpp lib/cmake/kerf/kerfConfig.cmake
             lib/cmake/kerf/kerfConfigVersion.cmake lib/cmake/kerf/kerfTargets.cmake)
  if(NOT EXISTS ${prefix}/${file})
    message(FATAL_ERROR "cmake --install did not write ${prefix}/${file}")
  endif()
endforeach()
file(GLOB_RECURSE private_headers ${prefix}/include/*vtk_error_catcher*)
if(private_headers)
  message(FATAL_ERROR "a private header was installed: ${private_headers}")
endif()

# 2. The package must not point back at the sources or the build tree: a prefix moved to
#    another machine would break, and this test would pass for the wrong reason.
file(GLOB_RECURSE package_files ${prefix}/lib/cmake/*)
foreach(file ${package_files})
  file(READ ${file} text)
  foreach(tree ${SOURCE_DIR} ${BINARY_DIR})
    string(FIND "${text}" "${tree}" at)
    if(NOT at EQUAL -1)
      message(FATAL_ERROR "${file} names ${tree}, so it depends on more than the prefix")
    endif()
  endforeach()
endforeach()

# 3. Configure the downstream project with the prefix as the only place to find kerf in.
set(configure_args -S ${SOURCE_DIR}/tests/downstream -B ${build} -G ${GENERATOR}
    -DCMAKE_CXX_COMPILER=${CXX_COMPILER} -DCMAKE_PREFIX_PATH=${prefix}
    -DCMAKE_FIND_USE_PACKAGE_REGISTRY=OFF -DCMAKE_EXPORT_COMPILE_COMMANDS=ON)
if(MAKE_PROGRAM)
  list(APPEND configure_args -DCMAKE_MAKE_PROGRAM=${MAKE_PROGRAM})
endif()
if(BUILD_TYPE)
  list(APPEND configure_args -DCMAKE_BUILD_TYPE=${BUILD_TYPE})
endif()
if(CXX_FLAGS)
  list(APPEND configure_args "-DCMAKE_CXX_FLAGS=${CXX_FLAGS}")
endif()
if(LINKER_FLAGS)
  list(APPEND configure_args "-DCMAKE_EXE_LINKER_FLAGS=${LINKER_FLAGS}")
endif()
# An environment that names another Kerf must not leak in either.
run("configuring the downstream project"
    ${CMAKE_COMMAND} -E env --unset=kerf_DIR --unset=CMAKE_PREFIX_PATH ${CMAKE_COMMAND} ${configure_args})
file(STRINGS ${build}/CMakeCache.txt kerf_dir REGEX "^kerf_DIR:")
string(REGEX REPLACE "^kerf_DIR:[A-Z]+=" "" kerf_dir "${kerf_dir}")
file(REAL_PATH ${prefix}/lib/cmake/kerf expected_dir)
file(REAL_PATH "${kerf_dir}" found_dir)
if(NOT found_dir STREQUAL expected_dir)
  message(FATAL_ERROR "find_package(kerf) found ${kerf_dir}, not the installed ${expected_dir}")
endif()
file(READ ${build}/compile_commands.json commands)
string(FIND "${commands}" "${SOURCE_DIR}/common/" at)
if(NOT at EQUAL -1)
  message(FATAL_ERROR "the downstream project compiles against the source tree's headers:\n${commands}")
endif()

# 4. Build it and run it: it checks its own answer against the closed form.
run("building the downstream project" ${CMAKE_COMMAND} --build ${build} ${config_args})
find_program(program patch_test PATHS ${build} ${build}/${BUILD_TYPE} NO_DEFAULT_PATH REQUIRED)
run("running the downstream program ${program}" ${program} WORKING_DIRECTORY ${build})
message(STATUS "${output}")
if(NOT output MATCHES "patch test: 12 interior nodes" OR NOT EXISTS ${build}/patch_test.vtu)
  message(FATAL_ERROR "the downstream program did not do what it says")
endif()
