# SPDX-License-Identifier: MIT
# Gate and latency reports (src/report/report_gates.c, src/report/report_pareto.c).
np_test_program(test_report test_report.c)
np_add_cases(test_report report cost_model_calibration latency_matches_model unknown_stage_rejected
  dse_axes_from_keys levels_retime)
set_tests_properties(report.cost_model_calibration PROPERTIES
  ENVIRONMENT "NP_COST_CALIB=${CMAKE_CURRENT_SOURCE_DIR}/cost_calib.v" SKIP_RETURN_CODE 77)
# The copies in docs/ are what `noisepipe report all` writes today, byte for byte.
add_test(NAME report.docs_fresh COMMAND ${CMAKE_COMMAND}
  -DNOISEPIPE=$<TARGET_FILE:noisepipe> -DDOCS=${PROJECT_SOURCE_DIR}/docs
  -DOUT=${CMAKE_CURRENT_BINARY_DIR}/report_fresh -P ${CMAKE_CURRENT_SOURCE_DIR}/report_fresh.cmake)
# --scene: wood and marble give different reports, each without what it does not use.
add_test(NAME report.scene_wood_vs_marble COMMAND ${CMAKE_COMMAND}
  -DNOISEPIPE=$<TARGET_FILE:noisepipe> -DSCENES=${PROJECT_SOURCE_DIR}/vectors/scenes
  -P ${CMAKE_CURRENT_SOURCE_DIR}/report_scene.cmake)
# --levels (issue 14): every stage pipelined to the target clock; the one-clock recurrences that cannot
# be cut are named with the reason; a target out of range is refused.
add_test(NAME report.levels_default COMMAND noisepipe report gates)
set_tests_properties(report.levels_default PROPERTIES PASS_REGULAR_EXPRESSION
  "Pipelined to 40 gate levels.*\\| classic3 \\| \\*\\*all\\*\\* \\|.*yes \\|.*fdiff X cannot meet 40 levels:\\*\\* a one-clock recurrence: its 67-bit adder")
add_test(NAME report.levels_wide COMMAND noisepipe report gates --unit fdiff --levels 200)
set_tests_properties(report.levels_wide PROPERTIES PASS_REGULAR_EXPRESSION
  "\\| fdiff \\| X \\| 154 \\| 1 \\| 0 \\| 0 \\| 0 \\| 137 \\| yes \\|")
add_test(NAME report.levels_bad COMMAND ${CMAKE_COMMAND}
  -DCMD=$<TARGET_FILE:noisepipe> -DARGS=report\;gates\;--levels\;2 -DWANT_RC=2
  "-DWANT=--levels 2: expected gate levels per clock, 4..100000" -P ${CMAKE_CURRENT_SOURCE_DIR}/render_expect.cmake)
# report tradeoff (docs/tradeoff.md): fdiff against texel at <= 1 LSB on a scene, with scene-sized registers; a
# scene even the widest registers refuse: exit 2.
add_test(NAME report.tradeoff_wood COMMAND noisepipe report tradeoff --scene ${PROJECT_SOURCE_DIR}/vectors/scenes/wood.json
  -o ${CMAKE_CURRENT_BINARY_DIR}/tradeoff)
set_tests_properties(report.tradeoff_wood PROPERTIES PASS_REGULAR_EXPRESSION "wrote .*tradeoff-wood.md")
add_test(NAME report.tradeoff_refused COMMAND ${CMAKE_COMMAND}
  -DCMD=$<TARGET_FILE:noisepipe> -DARGS=report\;tradeoff\;--scene\;${CMAKE_CURRENT_SOURCE_DIR}/scenes/reg_clamp_j5000.json
  -DWANT_RC=2 "-DWANT=scene reg_clamp_j5000: field texture.quadric.J: the colour index reaches 5000.98"
  -P ${CMAKE_CURRENT_SOURCE_DIR}/render_expect.cmake)
# --scene with an "aa" section: aacount priced from it (parallel and serial), the normal metric left out
# when the scene does not enable it.
file(MAKE_DIRECTORY ${CMAKE_CURRENT_BINARY_DIR}/report_scene_aa)
add_test(NAME report.scene_aacount COMMAND ${CMAKE_COMMAND}
  -DNOISEPIPE=$<TARGET_FILE:noisepipe> -DSCENES=${PROJECT_SOURCE_DIR}/vectors/scenes
  -DOUT=${CMAKE_CURRENT_BINARY_DIR}/report_scene_aa -P ${CMAKE_CURRENT_SOURCE_DIR}/report_scene_aa.cmake)
# --scene --sized: the span units priced with the registers sized by the scene (docs/render.md, "Registers
# sized by the scene"): the configuration, the register formats and the predicted bound of each.
add_test(NAME report.scene_sized_wood COMMAND noisepipe report gates --sized --scene
  ${PROJECT_SOURCE_DIR}/vectors/scenes/wood.json)
set_tests_properties(report.scene_sized_wood PROPERTIES PASS_REGULAR_EXPRESSION
  "Registers \\*\\*sized by the scene\\*\\*.*\\| fdiff \\| `texture=sized:wood idx_int=2 w_frac=12 guard=16 resetup=0 setup_mults=1 [^`]*` \\| s7 Q6\\.0 \\| s4 Q3\\.0 \\| 0\\.788 LSB \\|.*Set-up multipliers of fdiff.*\\| \\*\\*1 \\(chosen\\)\\*\\* \\| 106439 \\| 66086 \\| 30946 \\|.*\\| 4 \\| 290141 \\| 37480 \\| 2340 \\|.*\\| fdiff \\| 1 \\| 106439 \\|")
