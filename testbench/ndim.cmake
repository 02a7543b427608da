# SPDX-License-Identifier: MIT
# Noise in n = 2..5 dimensions (testbench/test_ndim.c; docs/noise-nd.md has the figures).
np_test_program(test_ndim test_ndim.c pipe_drive.c)
np_add_cases(test_ndim ndim
  hash3_is_seed hash_tables hash_distribution grad_sets grad_index_bits sorting_networks
  simplex3_bit_exact classic3_bit_exact classic3_same_datapath
  error_bound_defaults error_simplex error_classic kernel_continuity output_range
  cycle_simplex_1e6 cycle_classic_1e6 registry)
set_tests_properties(ndim.cycle_simplex_1e6 ndim.cycle_classic_1e6 ndim.error_classic PROPERTIES TIMEOUT 300)
# docs/dims.md and docs/dims.svg are `noisepipe report dims -o docs` byte for byte.
add_test(NAME ndim.report_dims_fresh COMMAND ${CMAKE_COMMAND} -DNOISEPIPE=$<TARGET_FILE:noisepipe>
  -DOUT=${CMAKE_CURRENT_BINARY_DIR}/dims-fresh -DDOCS=${PROJECT_SOURCE_DIR}/docs
  -P ${CMAKE_CURRENT_SOURCE_DIR}/ndim_fresh.cmake)
# The time-varying solid texture through 4-D noise: frames written, moving, deterministic.
add_test(NAME ndim.anim4d_frames COMMAND ${CMAKE_COMMAND} -DNOISEPIPE=$<TARGET_FILE:noisepipe>
  -DOUT=${CMAKE_CURRENT_BINARY_DIR}/anim4d-test -P ${CMAKE_CURRENT_SOURCE_DIR}/ndim_anim.cmake)
# The 4-D texture as a scene of the scene pipeline (vectors/scenes/anim4d.json, src/render/np_noisetex.h).
np_test_program(test_ndim_scene test_ndim_scene.c)
target_link_libraries(test_ndim_scene PRIVATE np_render)
target_compile_definitions(test_ndim_scene PRIVATE NP_SOURCE_DIR="${PROJECT_SOURCE_DIR}")
np_add_cases(test_ndim_scene ndim scene_continuity scene_keys scene_classic4)
# `noisepipe render` on it: every frame's image and reference against vectors/images/anim4d_hashes.txt.
add_test(NAME ndim.scene_hashes COMMAND $<TARGET_FILE:noisepipe> render ${PROJECT_SOURCE_DIR}/vectors/scenes/anim4d.json
  -o ${CMAKE_CURRENT_BINARY_DIR}/anim4d-scene --hashes ${PROJECT_SOURCE_DIR}/vectors/images/anim4d_hashes.txt)
# --frames on a scene without a time axis (wood): refused, exit 2, the message naming the scene.
add_test(NAME ndim.scene_frames_refused COMMAND ${CMAKE_COMMAND} -DCHECK=exit
  "-DARGS=render|--frames|2|-o|${CMAKE_CURRENT_BINARY_DIR}/anim4d-refused" -DEXPECT=2
  "-DMATCH=--frames: scene wood has no time axis" ${np_sweep_script})
