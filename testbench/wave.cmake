# SPDX-License-Identifier: MIT
# The Gerstner wave unit (seed 004): ROM, sin/cos bound, model against the double reference over
# long times, the named stiff cases, the host's eq. (1) and dispersion, boxes and rays, culling,
# the cycle model and the time budget (testbench/test_wave.c, docs/wave.md). The unit's vectors
# and KAT are checked by conformance.wave.*.
np_test_program(test_wave test_wave.c)
target_link_libraries(test_wave PRIVATE np_render)
target_compile_definitions(test_wave PRIVATE NP_WAVE_SCENES="${PROJECT_SOURCE_DIR}/vectors/scenes"
  NP_WAVE_VECTORS="${PROJECT_SOURCE_DIR}/vectors/wave")
np_add_cases(test_wave wave
  rom sincos_bound vs_ref hist_year freq_drift fold nyquist a_gt_A range shallow wind frame_wrap recurrence pipe
  ray_partition culling scaling budget overlap land scene_refusals vector_regs jac_vs_ref fold_flag jac_pipe jac_regs recur_unit)
# The command: a folding scene is refused with exit 2 and a message naming allow_fold.
add_test(NAME wave.cli_fold_refused COMMAND sh -c
  "\"$0\" wave \"$1\" 2>&1; test $? -eq 2" $<TARGET_FILE:noisepipe> ${PROJECT_SOURCE_DIR}/vectors/scenes/wave_fold.json)
set_tests_properties(wave.cli_fold_refused PROPERTIES PASS_REGULAR_EXPRESSION "allow_fold")
# Lit through the G-buffer renderer (issue 15's np_gbuf): two frames of scenario 1 at 64^2, each
# a height PNG and a lit PNG.
add_test(NAME wave.cli_render_lit COMMAND sh -c
  "rm -rf \"$3\" && \"$0\" wave \"$1\" --grid 64 --frames 2 -o \"$3\" --render \"$2\" && test -s \"$3/wave_scenario1-lit-f0000000000.png\" && test -s \"$3/wave_scenario1-lit-f0000000015.png\""
  $<TARGET_FILE:noisepipe> ${PROJECT_SOURCE_DIR}/vectors/scenes/wave_scenario1.json
  ${PROJECT_SOURCE_DIR}/vectors/scenes/wave_render.json ${CMAKE_CURRENT_BINARY_DIR}/wave_render_lit)
set_tests_properties(wave.cli_render_lit PROPERTIES PASS_REGULAR_EXPRESSION "lit: .*lit: ")
# The lit renders pinned: every lit image's SHA-256 against vectors/images/wave_hashes.txt.
add_test(NAME wave.lit_hashes COMMAND sh ${CMAKE_CURRENT_SOURCE_DIR}/wave_lit_hashes.sh $<TARGET_FILE:noisepipe>
  ${PROJECT_SOURCE_DIR}/vectors/scenes ${PROJECT_SOURCE_DIR}/vectors/images/wave_hashes.txt
  ${CMAKE_CURRENT_BINARY_DIR}/wave_lit_hashes)
set_tests_properties(wave.lit_hashes PROPERTIES PASS_REGULAR_EXPRESSION "5 lit images identical")
# The gate report of a wave scene: the effects it does not use and its culled boxes left out. Scenario 2
# as it is (no irregular height, no noise: irr=0 cap=0; 7 boxes visible), with its camera turned away
# (every box culled: the frame is the 42 plane tests), and with both effects on (nothing left out).
add_test(NAME wave.report_scene COMMAND sh -c "
  set -e; np=\"$0\"; sc=\"$1\"; d=\"$2\"; mkdir -p \"$d\"
  \"$np\" report gates --scene \"$sc\" >\"$d/r.md\"
  grep -q 'wave. trains=1 irr=0 cap=0 ' \"$d/r.md\"; grep -q '7 visible, 0 culled' \"$d/r.md\"
  grep -q 'Frame:\\*\\* 36306 cycles' \"$d/r.md\"
  sed 's/\"target\": \\[512, 0, 520\\]/\"target\": [512, 1800, -1500]/' \"$sc\" >\"$d/away.json\"
  \"$np\" report gates --scene \"$d/away.json\" >\"$d/a.md\"
  grep -q '0 visible, 7 culled' \"$d/a.md\"; grep -q 'Frame:\\*\\* 42 cycles' \"$d/a.md\"
  sed 's/\"irregular\": false, \"noise\": false/\"irregular\": true, \"noise\": true/; s/\"fps\": 60,/\"fps\": 60, \"normals\": true, \"fold\": true,/' \"$sc\" >\"$d/fx.json\"
  \"$np\" report gates --scene \"$d/fx.json\" >\"$d/f.md\"
  grep -q 'wave. trains=1 irr=1 cap=1 rom_log2=8 normals=1 fold=1 ' \"$d/f.md\"; grep -q ': 0 left out' \"$d/f.md\"
  grep -q 'normals nx, ny, nz [*]*left out' \"$d/r.md\"; grep -q 'fold flag [*]*left out' \"$d/r.md\"
  grep -h 'boxes:\\|gates:\\|Frame:\\|outputs read' \"$d/r.md\" \"$d/a.md\" \"$d/f.md\""
  $<TARGET_FILE:noisepipe> ${PROJECT_SOURCE_DIR}/vectors/scenes/wave_scenario2.json ${CMAKE_CURRENT_BINARY_DIR}/wave_report_scene)
# --scene leaves out what the scene does not read: scenario 2 reading the fold flag alone has fold=1 and
# normals=0 (the normals' datapath left out, fewer gates than with both), and reading neither has neither.
add_test(NAME wave.report_scene_outputs COMMAND sh -c "
  set -e; np=\"$0\"; sc=\"$1\"; d=\"$2\"; mkdir -p \"$d\"
  sed 's/\"fps\": 60,/\"fps\": 60, \"fold\": true,/' \"$sc\" >\"$d/fold.json\"
  sed 's/\"fps\": 60,/\"fps\": 60, \"normals\": true, \"fold\": true,/' \"$sc\" >\"$d/both.json\"
  \"$np\" report gates --scene \"$sc\" >\"$d/none.md\"
  \"$np\" report gates --scene \"$d/fold.json\" >\"$d/fold.md\"
  \"$np\" report gates --scene \"$d/both.json\" >\"$d/both.md\"
  grep -q 'wave. trains=1 irr=0 cap=0 rom_log2=8 regs=1 ' \"$d/none.md\"
  grep -q 'wave. trains=1 irr=0 cap=0 rom_log2=8 fold=1 regs=1 ' \"$d/fold.md\"; grep -q 'normals nx, ny, nz [*]*left out' \"$d/fold.md\"
  grep -q 'fold flag read' \"$d/fold.md\"
  grep -q 'wave. trains=1 irr=0 cap=0 rom_log2=8 normals=1 fold=1 regs=1 ' \"$d/both.md\"
  g() { sed -n 's/.*gates:.. \\([0-9]*\\) for what.*/\\1/p' \"$1\"; }
  n=$(g \"$d/none.md\"); f=$(g \"$d/fold.md\"); b=$(g \"$d/both.md\")
  echo \"gates: reads neither $n, the fold flag $f, both $b\"
  test \"$n\" -lt \"$f\"; test \"$f\" -lt \"$b\""
  $<TARGET_FILE:noisepipe> ${PROJECT_SOURCE_DIR}/vectors/scenes/wave_scenario2.json ${CMAKE_CURRENT_BINARY_DIR}/wave_report_scene_outputs)
set_tests_properties(wave.report_scene_outputs PROPERTIES PASS_REGULAR_EXPRESSION "gates: reads neither [0-9]+, the fold flag [0-9]+, both [0-9]+")
