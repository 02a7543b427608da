# SPDX-License-Identifier: MIT
# The adaptive supersampling pipeline on the G-buffer (src/render/np_render_aa.h,
# docs/aacount.md): issue 15's acceptance checks on the seed scenes.
np_test_program(test_aa_render test_aa_render.c)
target_link_libraries(test_aa_render PRIVATE np_render)
target_compile_definitions(test_aa_render PRIVATE NP_SOURCE_DIR="${PROJECT_SOURCE_DIR}")
np_add_cases(test_aa_render aa_render
  matches_gbuf thresholds_zero_full c_zero_one_sample cycle_model mse_budget beats_full_3x3 host_conversion)
