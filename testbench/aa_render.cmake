# SPDX-License-Identifier: MIT
# The adaptive supersampling pipeline on the G-buffer (src/render/np_render_aa.h,
# docs/aacount.md): issue 15's acceptance checks on the seed scenes.
np_test_program(test_aa_render test_aa_render.c np_golden.c)
target_link_libraries(test_aa_render PRIVATE np_render)
target_compile_definitions(test_aa_render PRIVATE NP_SOURCE_DIR="${PROJECT_SOURCE_DIR}")
np_add_cases(test_aa_render aa_render
  borders thresholds_zero_full c_zero_one_sample cycle_model mse_budget beats_full_3x3 host_conversion boxes_knobs)
# The command's bad usage: exit 2 and a message naming what is wrong.
set(np_aa_scene ${PROJECT_SOURCE_DIR}/vectors/scenes/marble.json)
foreach(case "m5|m=5|--aa m=5: expected 2, 3 or 4" "key|m=3,c_x=1|--aa c_x=1: unknown key or not a number"
              "neg|m=3,c_d=-1|--aa c_d=-1: unknown key or not a number" "nom|c_d=5|--aa c_d=5: no m given")
  string(REPLACE "|" ";" parts "${case}")
  list(GET parts 0 nm)
  list(GET parts 1 spec)
  list(GET parts 2 want)
  add_test(NAME aa_render.cli_bad_${nm} COMMAND ${CMAKE_COMMAND}
    -DCMD=$<TARGET_FILE:noisepipe> -DARGS=render\;--aa\;${spec}\;--gt\;0\;${np_aa_scene}
    -DWANT_RC=2 "-DWANT=${want}" -P ${CMAKE_CURRENT_SOURCE_DIR}/render_expect.cmake)
endforeach()
add_test(NAME aa_render.cli_no_scene COMMAND ${CMAKE_COMMAND}
  -DCMD=$<TARGET_FILE:noisepipe> -DARGS=render\;--aa\;m=3 -DWANT_RC=2 "-DWANT=no scene"
  -P ${CMAKE_CURRENT_SOURCE_DIR}/render_expect.cmake)
# The command's normal output, byte for byte: stdout and every PNG, SVG and Markdown file against
# vectors/images/aa_hashes.txt (aa_golden.cmake, which also proves a flipped byte is caught).
add_test(NAME aa_render.golden COMMAND ${CMAKE_COMMAND} -DNOISEPIPE=$<TARGET_FILE:noisepipe>
  -DOUT=${CMAKE_CURRENT_BINARY_DIR}/aa-golden -DLIST=${PROJECT_SOURCE_DIR}/vectors/images/aa_hashes.txt
  -P ${CMAKE_CURRENT_SOURCE_DIR}/aa_golden.cmake)
