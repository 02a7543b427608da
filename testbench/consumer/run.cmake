# SPDX-License-Identifier: MIT
# Driver of the CTest case package.find_package_consumer (cmake -P):
#   1. cmake --install NP_BUILD_DIR into a fresh prefix under NP_WORK_DIR;
#   2. check that every header named in the NP_*_HEADERS lists was installed and
#      that installed headers include only installed project headers;
#   3. configure testbench/consumer with CMAKE_PREFIX_PATH=<prefix> (so
#      find_package(noisepipe) must find the installed package), build it, run it.
# Inputs (-D): NP_BUILD_DIR NP_CONFIG NP_WORK_DIR NP_SOURCE_DIR NP_HEADERS
# (comma-separated) NP_GENERATOR NP_C_COMPILER NP_CXX_COMPILER.
cmake_minimum_required(VERSION 3.18)
foreach(v NP_BUILD_DIR NP_WORK_DIR NP_SOURCE_DIR NP_HEADERS NP_GENERATOR NP_C_COMPILER NP_CXX_COMPILER)
  if(NOT DEFINED ${v})
    message(FATAL_ERROR "run.cmake: -D${v}=... is required")
  endif()
endforeach()
if(NOT NP_CONFIG)
  set(NP_CONFIG Release)
endif()

set(prefix "${NP_WORK_DIR}/prefix")
set(cbuild "${NP_WORK_DIR}/consumer-build")
file(REMOVE_RECURSE "${prefix}" "${cbuild}")

function(run what)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE rc)
  if(NOT rc EQUAL 0)
    string(JOIN " " cmd ${ARGN})
    message(FATAL_ERROR "package: ${what} failed (exit status ${rc}): ${cmd}")
  endif()
endfunction()

run("install" ${CMAKE_COMMAND} --install "${NP_BUILD_DIR}" --prefix "${prefix}" --config "${NP_CONFIG}")

# The headers: all listed ones present; no installed header needs a missing one.
file(GLOB_RECURSE cfg_files "${prefix}/*/noisepipeConfig.cmake")
if(NOT cfg_files)
  message(FATAL_ERROR "package: no noisepipeConfig.cmake under ${prefix}")
endif()
set(incdir "${prefix}/include/noisepipe")
string(REPLACE "," ";" headers "${NP_HEADERS}")
foreach(h ${headers})
  if(NOT EXISTS "${incdir}/${h}")
    message(FATAL_ERROR "package: header ${h} is listed but not installed in ${incdir}")
  endif()
endforeach()
file(GLOB installed RELATIVE "${incdir}" "${incdir}/*.h")
foreach(h ${installed})
  file(STRINGS "${incdir}/${h}" includes REGEX "^[ \t]*#[ \t]*include[ \t]*\"")
  foreach(line ${includes})
    string(REGEX REPLACE ".*\"([^\"]+)\".*" "\\1" dep "${line}")
    if(NOT EXISTS "${incdir}/${dep}")
      message(FATAL_ERROR "package: installed ${h} includes \"${dep}\", which is not installed")
    endif()
  endforeach()
endforeach()
list(LENGTH installed n_installed)
message(STATUS "package: ${n_installed} headers installed in ${incdir}: ${installed}")

# The consumer, against the installed package only (no package registry).
run("consumer configure" ${CMAKE_COMMAND} -S "${NP_SOURCE_DIR}" -B "${cbuild}"
    -G "${NP_GENERATOR}" "-DCMAKE_C_COMPILER=${NP_C_COMPILER}" "-DCMAKE_CXX_COMPILER=${NP_CXX_COMPILER}" "-DCMAKE_BUILD_TYPE=${NP_CONFIG}"
    "-DCMAKE_PREFIX_PATH=${prefix}" -DCMAKE_FIND_USE_PACKAGE_REGISTRY=OFF
    -DCMAKE_FIND_USE_SYSTEM_PACKAGE_REGISTRY=OFF)
file(STRINGS "${cbuild}/CMakeCache.txt" found REGEX "^noisepipe_DIR:")
string(FIND "${found}" "${prefix}/" at)
if(NOT at GREATER -1)
  message(FATAL_ERROR "package: the consumer found noisepipe outside the test prefix: ${found}")
endif()
run("consumer build" ${CMAKE_COMMAND} --build "${cbuild}" --config "${NP_CONFIG}")
find_program(consumer_exe consumer PATHS "${cbuild}" "${cbuild}/${NP_CONFIG}" NO_DEFAULT_PATH)
if(NOT consumer_exe)
  message(FATAL_ERROR "package: consumer executable not found in ${cbuild}")
endif()
run("consumer run" "${consumer_exe}")
find_program(consumer_cxx_exe consumer_cxx PATHS "${cbuild}" "${cbuild}/${NP_CONFIG}" NO_DEFAULT_PATH)
if(NOT consumer_cxx_exe)
  message(FATAL_ERROR "package: consumer_cxx executable not found in ${cbuild}")
endif()
run("C++ consumer run" "${consumer_cxx_exe}")
