# SPDX-License-Identifier: MIT
# `noisepipe report gates --scene` prices the unit aacount from the scene's "aa" section:
# boxes.json with the three metrics against the same scene without the normal metric (no
# "c_n"): both variants (parallel, serial) are priced, and each costs fewer gates without it.
file(READ ${SCENES}/boxes.json base)
set(aa_with "\"aa\": { \"m\": 3, \"c_d\": 1000, \"c_n\": 8, \"c_s\": 8 }")
set(aa_without "\"aa\": { \"m\": 3, \"c_d\": 1000, \"c_s\": 8 }")
foreach(v with without)
  string(REPLACE "\"aa\": { \"m\": 3 }" "${aa_${v}}" txt "${base}")
  if(txt STREQUAL base)
    message(FATAL_ERROR "boxes.json has no '\"aa\": { \"m\": 3 }' to replace")
  endif()
  file(WRITE ${OUT}/boxes_aa_${v}.json "${txt}")
  execute_process(COMMAND ${NOISEPIPE} report gates --scene ${OUT}/boxes_aa_${v}.json
    RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "report gates --scene (${v} normals) failed (${rc}): ${err}")
  endif()
  foreach(variant 0 1)
    string(REGEX MATCH "\\| aacount \\| `[^`]*serial=${variant}[^`]*` \\| ([0-9]+) \\|" m "${out}")
    if(NOT CMAKE_MATCH_1)
      message(FATAL_ERROR "${v} normals: no aacount serial=${variant} row in\n${out}")
    endif()
    set(g_${v}_${variant} ${CMAKE_MATCH_1})
  endforeach()
  string(FIND "${out}" "normal=1" n1)
  if(v STREQUAL "without" AND NOT n1 EQUAL -1)
    message(FATAL_ERROR "without normals: the report builds the normal metric")
  endif()
endforeach()
foreach(variant 0 1)
  if(NOT g_without_${variant} LESS g_with_${variant})
    message(FATAL_ERROR "serial=${variant}: ${g_without_${variant}} gates without the normal metric, "
      "${g_with_${variant}} with it: should be fewer")
  endif()
endforeach()
message(STATUS "aacount on boxes (m=3): parallel ${g_with_0} gates with normals, ${g_without_0} without; "
  "serial ${g_with_1} with, ${g_without_1} without")
