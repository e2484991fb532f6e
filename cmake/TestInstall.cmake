# Install test (ctest -L install): installs a gridloc build into a private prefix, checks
# what landed there, then configures, builds and runs examples/navigation_stack against that
# prefix only, through find_package(gridloc). Any failing step is a FATAL_ERROR.
#
#   cmake -DBUILD_DIR=<gridloc build> -DSOURCE_DIR=<gridloc source> [-DCONFIG=Release]
#         [-DLIBDIR=lib] [-DINCLUDEDIR=include] [-DDATADIR=share] [-DBINDIR=bin]
#         [-DEXPECT_CLI=1] [-DCXX_COMPILER=...] [-DGENERATOR=...] -P TestInstall.cmake
cmake_minimum_required(VERSION 3.20)

foreach(var BUILD_DIR SOURCE_DIR)
  if(NOT ${var})
    message(FATAL_ERROR "TestInstall: pass -D${var}=...")
  endif()
endforeach()
# GNUInstallDirs' relative defaults, for a call with only the two required variables.
foreach(pair "LIBDIR;lib" "INCLUDEDIR;include" "DATADIR;share" "BINDIR;bin")
  list(GET pair 0 var)
  list(GET pair 1 default)
  if(NOT ${var})
    set(${var} ${default})
  endif()
endforeach()
if(NOT CONFIG)
  set(CONFIG Release)
endif()

set(prefix ${BUILD_DIR}/_install_test)
set(consumer_build ${BUILD_DIR}/_navigation_stack_build)
# Start clean, so files left by an earlier run cannot hide a missing install rule.
file(REMOVE_RECURSE ${prefix} ${consumer_build})

# run(<step> <command...>): runs a command, echoes its output, stops on failure. The output
# is left in step_output for checks.
function(run step)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  message("---- ${step}\n${out}${err}")
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "TestInstall: ${step} failed (${rc}): ${ARGN}")
  endif()
  set(step_output "${out}" PARENT_SCOPE)
endfunction()

# 1. Install.
run("install" ${CMAKE_COMMAND} --install ${BUILD_DIR} --prefix ${prefix} --config ${CONFIG})

# 2. The install tree holds headers, libraries, package files, maps and the CLI.
set(expected
    ${INCLUDEDIR}/gridloc/grids/error.hpp
    ${INCLUDEDIR}/gridloc/grids/map_io.hpp
    ${INCLUDEDIR}/gridloc/sensors/sonar_ring.hpp
    ${INCLUDEDIR}/gridloc/sensors/sonar_sim.hpp
    ${INCLUDEDIR}/gridloc/sensors/rng.hpp
    ${INCLUDEDIR}/gridloc/engine/estimator.hpp
    ${INCLUDEDIR}/gridloc/engine/correlation/estimator.hpp
    ${INCLUDEDIR}/gridloc/engine/icp/estimator.hpp
    ${INCLUDEDIR}/gridloc/engine/sectors/estimator.hpp
    ${INCLUDEDIR}/gridloc/engine/evaluation/sonar_protocol.hpp
    ${LIBDIR}/cmake/gridloc/gridlocConfig.cmake
    ${LIBDIR}/cmake/gridloc/gridlocConfigVersion.cmake
    ${LIBDIR}/cmake/gridloc/gridlocTargets.cmake
    ${LIBDIR}/cmake/gridloc/gridlocOctomapTargets.cmake
    ${DATADIR}/gridloc/maps/room_rect.yaml
    ${DATADIR}/gridloc/maps/room_rect.pgm
    ${DATADIR}/gridloc/maps/sensors/wheelchair_14.yaml)
if(EXPECT_CLI)
  list(APPEND expected ${BINDIR}/gridloc${CMAKE_EXECUTABLE_SUFFIX})
endif()
set(missing "")
foreach(file IN LISTS expected)
  if(NOT EXISTS ${prefix}/${file})
    list(APPEND missing ${file})
  endif()
endforeach()
foreach(lib grids sensors engine evaluation octomap)
  file(GLOB found ${prefix}/${LIBDIR}/*gridloc_${lib}.*)
  if(NOT found)
    list(APPEND missing "${LIBDIR}/<lib>gridloc_${lib}.<ext>")
  endif()
endforeach()
if(missing)
  message(FATAL_ERROR "TestInstall: missing from ${prefix}:\n  ${missing}")
endif()
# No package file looks for OpenCV or links its libraries: the libraries decode map images
# themselves (issue 18).
file(GLOB package_files ${prefix}/${LIBDIR}/cmake/gridloc/*)
foreach(file IN LISTS package_files)
  file(READ ${file} text)
  if(text MATCHES "opencv_|OpenCVModules|(find_dependency|find_package)\\(OpenCV")
    message(FATAL_ERROR "TestInstall: ${file} needs OpenCV ('${CMAKE_MATCH_0}')")
  endif()
endforeach()

# 3. Configure the consumer against the prefix alone: the package registry and the system
# paths' gridloc (if any) are off, and gridloc_DIR is checked below. It is a sonar-only
# user without OctoMap (find_package(octomap) disabled): gridloc must not need it unless the
# octomap component is asked for. Nor OpenCV (its config package and the OpenCVModules
# finder gridloc's own build uses both disabled): gridloc never needs it (issue 18).
set(consumer_args -S ${SOURCE_DIR}/examples/navigation_stack -B ${consumer_build}
    -DCMAKE_PREFIX_PATH=${prefix} -DCMAKE_BUILD_TYPE=${CONFIG}
    -DCMAKE_FIND_USE_PACKAGE_REGISTRY=OFF -DCMAKE_EXPORT_COMPILE_COMMANDS=ON
    -DCMAKE_DISABLE_FIND_PACKAGE_octomap=ON -DCMAKE_DISABLE_FIND_PACKAGE_OpenCV=ON
    -DCMAKE_DISABLE_FIND_PACKAGE_OpenCVModules=ON)
if(GENERATOR)
  list(APPEND consumer_args -G ${GENERATOR})
endif()
if(CXX_COMPILER)
  list(APPEND consumer_args -DCMAKE_CXX_COMPILER=${CXX_COMPILER})
endif()
run("configure navigation_stack" ${CMAKE_COMMAND} ${consumer_args})

file(STRINGS ${consumer_build}/CMakeCache.txt gridloc_dir REGEX "^gridloc_DIR:")
string(REGEX REPLACE "^gridloc_DIR:[A-Z]+=" "" gridloc_dir "${gridloc_dir}")
file(REAL_PATH "${gridloc_dir}" gridloc_dir)
file(REAL_PATH "${prefix}/${LIBDIR}/cmake/gridloc" expected_dir)
if(NOT gridloc_dir STREQUAL expected_dir)
  message(FATAL_ERROR "TestInstall: found gridloc in '${gridloc_dir}', not in ${expected_dir}")
endif()

# 4. Build, and make sure no source-tree include path leaked into the consumer's compile.
run("build navigation_stack" ${CMAKE_COMMAND} --build ${consumer_build} --config ${CONFIG})
if(EXISTS ${consumer_build}/compile_commands.json)
  file(READ ${consumer_build}/compile_commands.json commands)
  foreach(module grids sensors engine)
    string(FIND "${commands}" "${SOURCE_DIR}/${module}/include" at)
    if(NOT at EQUAL -1)
      message(FATAL_ERROR "TestInstall: the consumer compiles with ${SOURCE_DIR}/${module}/include")
    endif()
  endforeach()
  string(FIND "${commands}" "${prefix}/${INCLUDEDIR}" at)
  if(at EQUAL -1)
    message(FATAL_ERROR "TestInstall: the consumer does not compile with ${prefix}/${INCLUDEDIR}")
  endif()
endif()

# 5. Run it on the installed map and ring: every localization prints one line.
file(GLOB_RECURSE binary ${consumer_build}/navigation_stack${CMAKE_EXECUTABLE_SUFFIX})
if(NOT binary)
  message(FATAL_ERROR "TestInstall: no navigation_stack binary in ${consumer_build}")
endif()
list(GET binary 0 binary)
set(maps ${prefix}/${DATADIR}/gridloc/maps)
run("run navigation_stack" ${binary} ${maps}/room_rect.yaml ${maps}/sensors/wheelchair_14.yaml)
string(REGEX MATCHALL "localization [0-9]+:" lines "${step_output}")
list(LENGTH lines count)
if(count LESS 1)
  message(FATAL_ERROR "TestInstall: navigation_stack printed no localization")
endif()

# Its error path: a bad map is one message and exit code 2, not a crash.
execute_process(COMMAND ${binary} ${maps}/no_such_map.yaml ${maps}/sensors/wheelchair_14.yaml
                RESULT_VARIABLE rc ERROR_VARIABLE err)
if(NOT rc EQUAL 2 OR NOT err MATCHES "no_such_map.yaml")
  message(FATAL_ERROR "TestInstall: bad map gave exit ${rc}, stderr '${err}' (want 2 and the path)")
endif()

# 6. The installed CLI runs on the installed data.
if(EXPECT_CLI)
  run("run installed gridloc demo" ${prefix}/${BINDIR}/gridloc${CMAKE_EXECUTABLE_SUFFIX} demo
      --map ${maps}/room_rect.yaml --ring ${maps}/sensors/wheelchair_14.yaml)
endif()
message("TestInstall: OK (${count} localizations)")
