# SPDX-License-Identifier: MIT
# The unit-conformance test (test_conformance.c, conformance.c): every check on every
# registered unit, as conformance.<unit>.<check>; gen_kat, the one generator of the
# known-answer tables (<unit>_kat.inc); the toy units registered at run time (test_toy.c, test_toy_span.c).
#
# The case list comes from the registry: after each build, test_conformance prints its
# cases (UNIT.CHECK) and conformance_cases.cmake below turns them into add_test() lines in
# a file that CTest includes, so a unit added to the registry gets its cases with no edit
# here (as gtest_discover_tests does).
if(CMAKE_SCRIPT_MODE_FILE)
  # cmake -DEXE=test_conformance -DOUT=file -DSRC=testbench -P conformance.cmake
  execute_process(COMMAND ${EXE} RESULT_VARIABLE rc OUTPUT_VARIABLE cases)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "${EXE} could not list its cases (${rc})")
  endif()
  string(REPLACE "\n" ";" cases "${cases}")
  set(text "# Written by testbench/conformance.cmake from `test_conformance` (the registry's units).\n")
  foreach(c ${cases})
    string(APPEND text "add_test(conformance.${c} \"${EXE}\" ${c})\n"
      "set_tests_properties(conformance.${c} PROPERTIES SKIP_RETURN_CODE 77 LABELS conformance)\n")
  endforeach()
  file(WRITE ${OUT}.tmp "${text}")
  file(RENAME ${OUT}.tmp ${OUT})
  return()
endif()

add_library(np_conformance STATIC conformance.c conf_toy.c kat.c widths.c span_test.c)
target_link_libraries(np_conformance PUBLIC np_tools)
target_include_directories(np_conformance PUBLIC ${CMAKE_CURRENT_SOURCE_DIR})
np_project_target(np_conformance)
set(np_conf_defs NP_VEC_DIR="${PROJECT_SOURCE_DIR}/vectors" NP_KAT_DIR="${CMAKE_CURRENT_SOURCE_DIR}"
  NP_CONF_WORK="${CMAKE_CURRENT_BINARY_DIR}")

np_test_program(gen_kat gen_kat.c)
target_link_libraries(gen_kat PRIVATE np_conformance)

np_test_program(test_conformance test_conformance.c)
target_link_libraries(test_conformance PRIVATE np_conformance)
target_compile_definitions(test_conformance PRIVATE ${np_conf_defs})
set(np_conf_list ${CMAKE_CURRENT_BINARY_DIR}/conformance_cases.cmake)
add_custom_command(TARGET test_conformance POST_BUILD
  COMMAND ${CMAKE_COMMAND} -DEXE=$<TARGET_FILE:test_conformance> -DOUT=${np_conf_list}
    -P ${CMAKE_CURRENT_LIST_FILE}
  BYPRODUCTS ${np_conf_list} VERBATIM)
# Included by CTest; before the first build there is no list yet, and a case says so.
set(np_conf_include ${CMAKE_CURRENT_BINARY_DIR}/conformance_include.cmake)
file(WRITE ${np_conf_include} "if(EXISTS \"${np_conf_list}\")\n  include(\"${np_conf_list}\")\n"
  "else()\n  add_test(conformance_NOT_BUILT \"${np_conf_list}\")\nendif()\n")
set_property(DIRECTORY APPEND PROPERTY TEST_INCLUDE_FILES ${np_conf_include})

np_test_program(test_toy test_toy.c)
target_link_libraries(test_toy PRIVATE np_conformance)
target_compile_definitions(test_toy PRIVATE ${np_conf_defs})
np_add_cases(test_toy toy register vectors verify conformance gates)

# The toy span unit registered at run time (test_toy_span.c): renders, vectors, verify, conformance, gates.
np_test_program(test_toy_span test_toy_span.c)
target_link_libraries(test_toy_span PRIVATE np_conformance np_render)
target_compile_definitions(test_toy_span PRIVATE ${np_conf_defs})
np_add_cases(test_toy_span toy_span register render_units render vectors verify conformance gates)
