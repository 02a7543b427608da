# SPDX-License-Identifier: MIT
# Gate and latency reports (src/report/report_gates.c, src/report/report_pareto.c).
np_test_program(test_report test_report.c)
np_add_cases(test_report report cost_model_calibration latency_matches_model unknown_stage_rejected
  dse_axes_from_keys)
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
# --scene with an "aa" section: aacount priced from it (parallel and serial), the normal metric left out
# when the scene does not enable it.
file(MAKE_DIRECTORY ${CMAKE_CURRENT_BINARY_DIR}/report_scene_aa)
add_test(NAME report.scene_aacount COMMAND ${CMAKE_COMMAND}
  -DNOISEPIPE=$<TARGET_FILE:noisepipe> -DSCENES=${PROJECT_SOURCE_DIR}/vectors/scenes
  -DOUT=${CMAKE_CURRENT_BINARY_DIR}/report_scene_aa -P ${CMAKE_CURRENT_SOURCE_DIR}/report_scene_aa.cmake)
