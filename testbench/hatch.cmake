# SPDX-License-Identifier: MIT
# The hatching unit (seed 003, docs/hatch.md): seed sets, the bit-exact model
# against the float reference, nesting, coverage lists, zoom, stiff cases.
np_test_program(test_hatch test_hatch.c)
np_add_cases(test_hatch hatch
  seeds_fkm16 seeds_fkm64 seeds_all16 seeds_shipped seeds_random
  tone_exact alpha_error model_vs_ref guard_bits nesting kat
  cover_identical16 cover_identical64 cover_rotations cover_table1
  zoom_identical zoom_sequence stiff_deep_zoom stiff_level_seam stiff_256_blends stiff_tile_corner
  stiff_frac_half stiff_tone_0_1)
# The command prints the figures of the design (worst / median / best over all B(4,2)).
add_test(NAME hatch.cli_seeds_all COMMAND noisepipe seeds --order 2 --all)
set_tests_properties(hatch.cli_seeds_all PROPERTIES
  PASS_REGULAR_EXPRESSION "20736 cyclic sequences enumerated.*equal, every one de Bruijn.*worst 0\\.0138, median 0\\.0810, best 0\\.1668 \\(8 sequences at the best\\)")
add_test(NAME hatch.cli_seeds_bad COMMAND noisepipe seeds --order 2 --digits 0000111122223333)
set_tests_properties(hatch.cli_seeds_bad PROPERTIES
  PASS_REGULAR_EXPRESSION "de Bruijn: NO; one seed per cell of the 4x4 grid: NO")
add_test(NAME hatch.cli_seeds_usage COMMAND noisepipe seeds --order 4)
set_tests_properties(hatch.cli_seeds_usage PROPERTIES
  PASS_REGULAR_EXPRESSION "noisepipe seeds: --order '4': expected a decimal number in 1\\.\\.3")
# Scenes hatched through the G-buffer renderer (docs/hatch.md, "Scenes"): coverage against brute
# force on the hatched cube (4 x 16 and 4 x 64 seeds), the host's level of detail, the scene keys.
np_test_program(test_hatch_scene test_hatch_scene.c np_golden.c)
target_link_libraries(test_hatch_scene PRIVATE np_render)
target_compile_definitions(test_hatch_scene PRIVATE NP_SOURCE_DIR="${PROJECT_SOURCE_DIR}")
np_add_cases(test_hatch_scene hatch scene_cover_identical scene_lod scene_keys scene_gates)
# The command on the hatched cubes: every image against its golden hash, the hatched image's cycle
# model and float reference checked by the command.
add_test(NAME hatch.scene_golden COMMAND noisepipe render -o ${CMAKE_CURRENT_BINARY_DIR}/hatch-scenes
  --hashes ${PROJECT_SOURCE_DIR}/vectors/images/hatch_hashes.txt
  ${PROJECT_SOURCE_DIR}/vectors/scenes/hatch_wood.json ${PROJECT_SOURCE_DIR}/vectors/scenes/hatch_marble.json)
set_tests_properties(hatch.scene_golden PROPERTIES
  PASS_REGULAR_EXPRESSION "hash: hatch_wood hatch: matches.*hash: hatch_marble hatch: matches.*render: ok")
# A rendered zoom sequence over 8 levels: every tracked stroke centre stays on its UV point, no alpha drops,
# and in the rendered pixels each tracked stroke's centroid stays within a pixel of its UV centre.
add_test(NAME hatch.scene_zoom COMMAND noisepipe render --no-cycles --zoom-frames 16 --zoom-levels 8
  -o ${CMAKE_CURRENT_BINARY_DIR}/hatch-zoom ${PROJECT_SOURCE_DIR}/vectors/scenes/hatch_wood.json)
set_tests_properties(hatch.scene_zoom PROPERTIES
  PASS_REGULAR_EXPRESSION "levels -1 \\.\\. -9 on polygon.*16 stroke centres of layer 0 tracked: 0 frame-centres off their UV point, 0 alpha drops \\(0 frames without the polygon\\).*in the rendered frames, [1-9][0-9]* stroke-frames wholly on the face: the stroke's alpha-weighted centroid over its pixels at most 0\\.[0-9]+ px from its UV centre, 0 over 1 px, 0 without ink.*render: ok")
# The gate report of a hatched scene: the unit configured from the scene, with its coverage logic.
add_test(NAME hatch.scene_report_gates COMMAND noisepipe report gates --scene ${PROJECT_SOURCE_DIR}/vectors/scenes/hatch_wood.json)
set_tests_properties(hatch.scene_report_gates PROPERTIES
  PASS_REGULAR_EXPRESSION "also used:\\*\\* `hatch` `set=best16 layers=4 fade=smooth guard=9 lanes=1 rot=pin inv_len=1024 inv_wid=8533 mode=coverage slots=4`")
# B16 / C16 / B64 / C64 on the hatched cube beside the paper's Table 1 (the command compares the images).
add_test(NAME hatch.scene_table1 COMMAND noisepipe render --no-cycles --hatch-table
  -o ${CMAKE_CURRENT_BINARY_DIR}/hatch-table ${PROJECT_SOURCE_DIR}/vectors/scenes/hatch_wood.json)
set_tests_properties(hatch.scene_table1 PROPERTIES
  PASS_REGULAR_EXPRESSION "\\| C16 \\| 4\\.903 \\| 1\\.226 \\(4\\) \\| 0 of 35136 \\|.*\\| C64 \\| 4\\.842 \\| 1\\.210 \\(4\\) \\| 0 of 35136 \\|.*units at 1 GHz.*coverage against brute force: bit-identical.*render: ok")
# The hatch options on a scene without a "hatch" section: refused (exit 2), naming the scene.
add_test(NAME hatch.scene_needs_hatch COMMAND noisepipe render --zoom-frames 2 -o ${CMAKE_CURRENT_BINARY_DIR}/hatch-none embedded:wood)
set_tests_properties(hatch.scene_needs_hatch PROPERTIES
  PASS_REGULAR_EXPRESSION "noisepipe render: wood: --hatch-table and --zoom-frames need a scene with a \"hatch\" section")
