# SPDX-License-Identifier: MIT
# `noisepipe report gates --scene` on the two seed scenes: each report holds
# only what its scene uses, and they differ where the scenes differ.
foreach(s wood marble)
  execute_process(COMMAND ${NOISEPIPE} report gates --scene ${SCENES}/${s}.json
    RESULT_VARIABLE rc OUTPUT_VARIABLE out_${s} ERROR_VARIABLE err)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "report gates --scene ${s}.json failed (${rc}): ${err}")
  endif()
  # Neither scene reads a noise unit or a derivative: no noise unit's or derivative's datapath.
  foreach(bad "## classic3" "## simplex3" "deriv=1" "dout_bits")
    string(FIND "${out_${s}}" "${bad}" at)
    if(NOT at EQUAL -1)
      message(FATAL_ERROR "${s}: the report contains '${bad}', which the scene does not use")
    endif()
  endforeach()
  foreach(want "## fdiff" "## texel" "left out.*`classic3`, `simplex3`" "no derivative datapath")
    if(NOT out_${s} MATCHES "${want}")
      message(FATAL_ERROR "${s}: the report lacks '${want}'")
    endif()
  endforeach()
endforeach()
# Wood: one octave, a 4-entry table; marble: four octaves, an 8-entry table: four times the
# octave lanes (e.g. 12 DDA adders of u40 in fdiff's core against 3) and more cycles per frame.
set(expect_wood "1 octave \\(" "3 x add 40 → u" "2 x mux 4:1 of 24")
set(expect_marble "4 octaves \\(" "12 x add 40 → u" "2 x mux 8:1 of 24")
foreach(s wood marble)
  foreach(want ${expect_${s}})
    if(NOT out_${s} MATCHES "${want}")
      message(FATAL_ERROR "${s}: expected '${want}' in its report")
    endif()
  endforeach()
endforeach()
string(REGEX MATCH "\\| fdiff \\| [0-9]+ \\| ([0-9]+) \\|" m "${out_wood}")
set(g_wood ${CMAKE_MATCH_1})
string(REGEX MATCH "\\| fdiff \\| [0-9]+ \\| ([0-9]+) \\|" m "${out_marble}")
set(g_marble ${CMAKE_MATCH_1})
if(NOT g_wood OR NOT g_marble OR NOT g_marble GREATER g_wood)
  message(FATAL_ERROR "fdiff gates: wood ${g_wood}, marble ${g_marble}: marble (4 octaves) should cost more")
endif()
message(STATUS "wood: fdiff ${g_wood} gates (1 octave); marble: fdiff ${g_marble} gates (4 octaves); "
  "neither has a noise unit or a derivative datapath")
