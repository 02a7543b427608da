# SPDX-License-Identifier: MIT
# The scanline texturing units (forward differences and per pixel), scenes,
# the reference renderer, golden images and image files (docs/fdiff.md,
# docs/render.md).
# One program per concern (the CTest names are the same as before the split):
# the forward-difference unit, the per-pixel unit, and what they share; the
# fixtures and the cycle-model driver in span_test.c.
np_test_program(test_fdiff test_fdiff.c span_test.c)
np_add_cases(test_fdiff fdiff
  stiff_span65536 stiff_deriv_tiny stiff_deriv_huge stiff_cell_edge_on_pixel stiff_span_one_zero
  stiff_wrap stiff_quadric_long guard_search guard_min_both_ways setup_exact appendix_coefficients drift_identity
  cycle_vs_model cycle_count setup_overlap)
# The carried (multiplier-free) cell set-up of fdiff against the multiplier set-up (issue 26).
np_test_program(test_fdiff_carry test_fdiff_carry.c span_test.c np_golden.c)
target_link_libraries(test_fdiff_carry PRIVATE np_render)
target_compile_definitions(test_fdiff_carry PRIVATE NP_SOURCE_DIR="${PROJECT_SOURCE_DIR}")
np_add_cases(test_fdiff_carry fdiff carry_seed_scenes carry_adversarial carry_unit_spans carry_price carry_span_relations)
np_test_program(test_texel test_texel.c span_test.c)
np_add_cases(test_texel fdiff texel_exact_weights texel_cycle_vs_model)
np_test_program(test_texture test_texture.c span_test.c)
np_add_cases(test_texture fdiff colour_stage front_end_rounding lattice_distribution cfg_validation
  register_bound sized_fewest)

np_test_program(test_render test_render.c np_golden.c)
target_link_libraries(test_render PRIVATE np_render)
target_compile_definitions(test_render PRIVATE NP_SOURCE_DIR="${PROJECT_SOURCE_DIR}")
np_add_cases(test_render render
  sha256_kat exr_roundtrip png_roundtrip scene_errors scene_seed seed_scenes_1lsb golden_hashes sized_registers
  scanline perspective_polygon builtin_textures stream_vectors
  error_colour_bar error_rounded shading_view exr_colour_attributes)
foreach(c exr_roundtrip png_roundtrip stream_vectors error_colour_bar error_rounded shading_view exr_colour_attributes)
  set_tests_properties(render.${c} PROPERTIES WORKING_DIRECTORY ${CMAKE_CURRENT_BINARY_DIR})
endforeach()

# The command on both seed scenes: images written, errors within 1 LSB, golden
# hashes checked; then exrheader (package openexr) must read the EXR files.
set(np_render_out ${CMAKE_CURRENT_BINARY_DIR}/render-cli)
add_test(NAME render.cli COMMAND noisepipe render -o ${np_render_out}
  --hashes ${PROJECT_SOURCE_DIR}/vectors/images/hashes.txt
  ${PROJECT_SOURCE_DIR}/vectors/scenes/wood.json ${PROJECT_SOURCE_DIR}/vectors/scenes/marble.json)
set_tests_properties(render.cli PROPERTIES FIXTURES_SETUP np_render_images)
find_program(NP_EXRHEADER exrheader)
if(NP_EXRHEADER)
  foreach(f wood_ref wood_fdiff marble_texel marble_fdiff_err)
    add_test(NAME render.exrheader_${f} COMMAND ${NP_EXRHEADER} ${np_render_out}/${f}.exr)
    set_tests_properties(render.exrheader_${f} PROPERTIES FIXTURES_REQUIRED np_render_images
      PASS_REGULAR_EXPRESSION "R, 32-bit floating-point")
  endforeach()
endif()
# The colour EXRs carry the chromaticities (Rec. 709, D65) and say what their values are.
if(NP_EXRHEADER)
  add_test(NAME render.exrheader_chromaticities COMMAND ${NP_EXRHEADER} ${np_render_out}/wood_fdiff.exr)
  set_tests_properties(render.exrheader_chromaticities PROPERTIES FIXTURES_REQUIRED np_render_images
    PASS_REGULAR_EXPRESSION "red +\\(0\\.64 0\\.33\\)")
endif()
# -o naming a regular file: exit 2, and the first line is the project's message, not the EXR library's.
file(WRITE ${CMAKE_CURRENT_BINARY_DIR}/render_out_file "a file, not a folder\n")
add_test(NAME render.cli_out_file COMMAND ${CMAKE_COMMAND}
  -DCMD=$<TARGET_FILE:noisepipe> -DARGS=render\;-o\;${CMAKE_CURRENT_BINARY_DIR}/render_out_file -DWANT_RC=2 -DFIRST=1
  "-DWANT=noisepipe render: -o ${CMAKE_CURRENT_BINARY_DIR}/render_out_file: not a folder: render writes several images into a folder"
  -P ${CMAKE_CURRENT_SOURCE_DIR}/render_expect.cmake)
# report -o a folder that does not exist (two levels): created, as render creates its folder.
add_test(NAME render.report_out_newdir COMMAND ${CMAKE_COMMAND}
  -DCMD=$<TARGET_FILE:noisepipe> -DARGS=report\;gates\;-o\;${CMAKE_CURRENT_BINARY_DIR}/report-newdir/sub -DWANT_RC=0
  -DWANT= -DREMOVE=${CMAKE_CURRENT_BINARY_DIR}/report-newdir
  -DWANT_FILE=${CMAKE_CURRENT_BINARY_DIR}/report-newdir/sub/gates.md
  -P ${CMAKE_CURRENT_SOURCE_DIR}/render_expect.cmake)
# A malformed scene: exit status 2 and a message naming the file and the field.
file(WRITE ${CMAKE_CURRENT_BINARY_DIR}/render_bad_scene.json
  "{ \"noisepipe_scene\": 1, \"name\": \"bad\", \"image\": { \"width\": 0, \"height\": 8 } }\n")
add_test(NAME render.cli_bad_scene COMMAND ${CMAKE_COMMAND}
  -DCMD=$<TARGET_FILE:noisepipe> -DARGS=render\;${CMAKE_CURRENT_BINARY_DIR}/render_bad_scene.json
  -DWANT_RC=2 "-DWANT=render_bad_scene.json: field 'image.width': expected an integer in 1..4096"
  -P ${CMAKE_CURRENT_SOURCE_DIR}/render_expect.cmake)
# The report (error against run time, plots; docs/plots is its output for the seed
# scenes; `noisepipe render --report DIR` is its alias) and the benchmark run end to end.
add_test(NAME render.report COMMAND noisepipe report runtime -o ${CMAKE_CURRENT_BINARY_DIR}/render-report --repeat 1)
set_tests_properties(render.report PROPERTIES PASS_REGULAR_EXPRESSION "report: 94 configurations")
add_test(NAME render.report_alias COMMAND noisepipe render --report ${CMAKE_CURRENT_BINARY_DIR}/render-report-alias
  --repeat 1 embedded:wood)
set_tests_properties(render.report_alias PROPERTIES PASS_REGULAR_EXPRESSION "report: 47 configurations")
add_test(NAME render.bench COMMAND noisepipe render --bench --repeat 1
  ${PROJECT_SOURCE_DIR}/vectors/scenes/wood.json ${PROJECT_SOURCE_DIR}/vectors/scenes/marble.json)
set_tests_properties(render.bench PROPERTIES PASS_REGULAR_EXPRESSION "bench marble.*hardware cycles per frame")
# --unit-config U:K=V,... configures through the unit registry: the default guard gives the golden
# images; another guard reaches the render (its hash line names it); an unknown unit or key, a key
# given twice and a key the scene sets are exit 2 naming it.
add_test(NAME render.cli_unit_config COMMAND noisepipe render -o ${CMAKE_CURRENT_BINARY_DIR}/render-unit-config
  --no-cycles --hashes ${PROJECT_SOURCE_DIR}/vectors/images/hashes.txt --unit-config fdiff:guard=44)
add_test(NAME render.cli_unit_config_applied COMMAND noisepipe render
  -o ${CMAKE_CURRENT_BINARY_DIR}/render-unit-config-applied --no-cycles
  --hashes ${PROJECT_SOURCE_DIR}/vectors/images/hashes.txt --unit-config fdiff:guard=40
  --unit-config texel:weight_frac=15)
set_tests_properties(render.cli_unit_config_applied PROPERTIES PASS_REGULAR_EXPRESSION
  "wood fdiff: configuration idx_int=10,w_frac=12,guard=40,resetup=0,setup_mults=2,mult_lat=2 differs.*wood texel: configuration [^ ]*weight_frac=15")
foreach(bad "unknown_unit|nosuch:x=1|unknown unit 'nosuch'"
            "unknown_key|fdiff:nosuch=1|unknown configuration key 'nosuch' for unit fdiff"
            "key_twice|fdiff:guard=4,guard=5|key guard given twice"
            "scene_key|fdiff:texture=ramp|the scene sets texture")
  string(REPLACE "|" ";" bad "${bad}")
  list(GET bad 0 name)
  list(GET bad 1 arg)
  list(GET bad 2 want)
  add_test(NAME render.cli_unit_config_${name} COMMAND ${CMAKE_COMMAND}
    -DCMD=$<TARGET_FILE:noisepipe> -DARGS=render\;--unit-config\;${arg} -DWANT_RC=2 "-DWANT=${want}"
    -P ${CMAKE_CURRENT_SOURCE_DIR}/render_expect.cmake)
endforeach()
# Register quantisation inside the bound (issue 10, docs/fdiff.md "Registers over a scene"): each scene
# below either fits the units' bound or is refused at load, exit 2, the message naming scene and field.
foreach(c
    "reg_scale01_near1000|field texture.octaves[0] transform entry [0][0] = 0.1 rounds in its register (24 bits, 16 fraction)"
    "reg_scale1e6|field texture.octaves[0] transform entry [0][0] = 1e-06 rounds in its register (24 bits, 16 fraction)"
    "reg_quadric_a1e6|field texture.quadric.A = 2e-06 rounds in its register (48 bits, 24 fraction)"
    "reg_clamp_j1023|field texture.quadric.J: the colour index reaches 1024.48 on a clamped colour map")
  string(REPLACE "|" ";" c "${c}")
  list(GET c 0 name)
  list(GET c 1 want)
  foreach(cmd render report)
    if(cmd STREQUAL render)
      set(args "render\;-o\;${CMAKE_CURRENT_BINARY_DIR}/render-reg\;${CMAKE_CURRENT_SOURCE_DIR}/scenes/${name}.json")
    else()
      set(args "report\;gates\;--scene\;${CMAKE_CURRENT_SOURCE_DIR}/scenes/${name}.json")
    endif()
    add_test(NAME render.${cmd}_refuses_${name} COMMAND ${CMAKE_COMMAND}
      -DCMD=$<TARGET_FILE:noisepipe> -DARGS=${args} -DWANT_RC=2 "-DWANT=scene ${name}: ${want}"
      -P ${CMAKE_CURRENT_SOURCE_DIR}/render_expect.cmake)
  endforeach()
endforeach()
# Registers sized by the scene (render --sized, report gates --scene): the issue's four scenes render
# within 1 LSB (render.sized_registers measures them against the predicted bound); a scene the widest
# registers cannot hold is still refused, exit 2, naming the field, its value and the width it needs.
add_test(NAME render.sized_cli_scale1e6 COMMAND noisepipe render --sized --no-cycles
  -o ${CMAKE_CURRENT_BINARY_DIR}/render-sized ${CMAKE_CURRENT_SOURCE_DIR}/scenes/reg_scale1e6.json)
set_tests_properties(render.sized_cli_scale1e6 PROPERTIES PASS_REGULAR_EXPRESSION
  "fdiff .*bound: predicted 0\\.[0-9]+ LSB \\(unit [0-9.]+ \\+ registers [0-9.e-]+\\), measured max 0\\.[0-9]+ LSB; registers: quadric s[0-9]+ Q\\.[0-9]+, transform s[0-9]+ Q\\.2[0-9].*render: ok")
foreach(cmd render report)
  if(cmd STREQUAL render)
    set(args "render\;--sized\;-o\;${CMAKE_CURRENT_BINARY_DIR}/render-sized\;${CMAKE_CURRENT_SOURCE_DIR}/scenes/reg_clamp_j5000.json")
  else()
    set(args "report\;gates\;--sized\;--scene\;${CMAKE_CURRENT_SOURCE_DIR}/scenes/reg_clamp_j5000.json")
  endif()
  add_test(NAME render.sized_${cmd}_refuses_clamp_j5000 COMMAND ${CMAKE_COMMAND}
    -DCMD=$<TARGET_FILE:noisepipe> -DARGS=${args} -DWANT_RC=2
    "-DWANT=scene reg_clamp_j5000: field texture.quadric.J: the colour index reaches 5000.98 on a clamped colour map over the scene's coordinates: it needs 13 index integer bits, the unit has at most 11"
    -P ${CMAKE_CURRENT_SOURCE_DIR}/render_expect.cmake)
endforeach()
