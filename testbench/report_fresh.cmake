# SPDX-License-Identifier: MIT
# Regenerate the reports into OUT and compare each with its copy in DOCS.
# Fails naming every stale file and the command that refreshes them.
file(REMOVE_RECURSE ${OUT})
file(MAKE_DIRECTORY ${OUT})
execute_process(COMMAND ${NOISEPIPE} report all -o ${OUT} --repeat 1 RESULT_VARIABLE rc)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "noisepipe report all failed (${rc})")
endif()
# Every file that does not hold a time: gates, pareto sweeps, and of the
# error-against-run-time report (plots/) the images, the cycle plots and the
# scanline plots; its table is compared without the model-time column below.
file(GLOB generated RELATIVE ${OUT} ${OUT}/gates.* ${OUT}/pareto-* ${OUT}/plots/*.png ${OUT}/plots/*_cycles.svg
  ${OUT}/plots/*_scanline*.svg)
set(stale "")
foreach(f ${generated})
  if(NOT EXISTS ${DOCS}/${f})
    list(APPEND stale "${f} (missing in docs/)")
  else()
    file(SHA256 ${OUT}/${f} a)
    file(SHA256 ${DOCS}/${f} b)
    if(NOT a STREQUAL b)
      list(APPEND stale ${f})
    endif()
  endif()
endforeach()
# plots/error_runtime.csv: every column but the last (model_s, a time).
foreach(side OUT DOCS)
  file(STRINGS ${${side}}/plots/error_runtime.csv lines_${side})
  list(TRANSFORM lines_${side} REPLACE ",[^,]*$" "")
endforeach()
if(NOT lines_OUT STREQUAL lines_DOCS)
  list(APPEND stale "plots/error_runtime.csv (besides model_s)")
endif()
list(LENGTH generated n)
if(n EQUAL 0)
  message(FATAL_ERROR "noisepipe report all wrote nothing")
endif()
if(stale)
  message(FATAL_ERROR "stale in docs/: ${stale}\nrefresh with: build/noisepipe report all -o docs")
endif()
message(STATUS "${n} report files in docs/ are fresh")
