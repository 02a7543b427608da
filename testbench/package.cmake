# SPDX-License-Identifier: MIT
# package.find_package_consumer: `cmake --install` this build into a prefix in
# the build tree, then build and run testbench/consumer, a separate project that
# does find_package(noisepipe) and links noisepipe::rtl_model and noisepipe::tools
# from C and from C++ (a Verilator or SystemC testbench is C++).
find_program(NP_CXX_COMPILER NAMES c++ g++ clang++)
if(NOT NP_CXX_COMPILER)
  message(FATAL_ERROR "package test: no C++ compiler (Debian: g++, part of build-essential)")
endif()
get_target_property(np_pkg_rtl_headers np_rtl_model PUBLIC_HEADER)
get_target_property(np_pkg_tools_headers np_tools PUBLIC_HEADER)
set(np_pkg_headers)
foreach(h ${np_pkg_rtl_headers} ${np_pkg_tools_headers})
  get_filename_component(h "${h}" NAME)
  list(APPEND np_pkg_headers "${h}")
endforeach()
string(REPLACE ";" "," np_pkg_headers "${np_pkg_headers}")
add_test(NAME package.find_package_consumer
  COMMAND ${CMAKE_COMMAND}
    -DNP_BUILD_DIR=${CMAKE_BINARY_DIR}
    -DNP_CONFIG=$<CONFIG>
    -DNP_WORK_DIR=${CMAKE_CURRENT_BINARY_DIR}/package
    -DNP_SOURCE_DIR=${CMAKE_CURRENT_SOURCE_DIR}/consumer
    -DNP_HEADERS=${np_pkg_headers}
    -DNP_GENERATOR=${CMAKE_GENERATOR}
    -DNP_C_COMPILER=${CMAKE_C_COMPILER}
    -DNP_CXX_COMPILER=${NP_CXX_COMPILER}
    -P ${CMAKE_CURRENT_SOURCE_DIR}/consumer/run.cmake)
set_tests_properties(package.find_package_consumer PROPERTIES TIMEOUT 300)
