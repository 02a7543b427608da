# SPDX-License-Identifier: MIT
# package.find_package_consumer: `cmake --install` this build into a prefix in
# the build tree, then build and run testbench/consumer, a separate project that
# does find_package(noisepipe) and links noisepipe::rtl_model and noisepipe::tools.
get_target_property(np_pkg_rtl_headers np_rtl_model PUBLIC_HEADER)
get_target_property(np_pkg_tools_headers np_tools PUBLIC_HEADER)
string(REPLACE ";" "," np_pkg_headers "${np_pkg_rtl_headers};${np_pkg_tools_headers}")
add_test(NAME package.find_package_consumer
  COMMAND ${CMAKE_COMMAND}
    -DNP_BUILD_DIR=${CMAKE_BINARY_DIR}
    -DNP_CONFIG=$<CONFIG>
    -DNP_WORK_DIR=${CMAKE_CURRENT_BINARY_DIR}/package
    -DNP_SOURCE_DIR=${CMAKE_CURRENT_SOURCE_DIR}/consumer
    -DNP_HEADERS=${np_pkg_headers}
    -DNP_GENERATOR=${CMAKE_GENERATOR}
    -DNP_C_COMPILER=${CMAKE_C_COMPILER}
    -P ${CMAKE_CURRENT_SOURCE_DIR}/consumer/run.cmake)
set_tests_properties(package.find_package_consumer PROPERTIES TIMEOUT 300)
