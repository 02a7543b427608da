# SPDX-License-Identifier: MIT
# The G-buffer renderer (src/render/np_gbuf.h, docs/render.md "The G-buffer"):
# sample positions and index matrices, the resolve's ROM, the 1x1 image from
# the centre sample, full supersampling, the references, light, meshes.
np_test_program(test_gbuf test_gbuf.c np_golden.c)
target_link_libraries(test_gbuf PRIVATE np_render)
target_compile_definitions(test_gbuf PRIVATE NP_SOURCE_DIR="${PROJECT_SOURCE_DIR}")
np_add_cases(test_gbuf gbuf
  resolve_exhaustive centre_golden full_ssaa borders shared_edges depth_far shade_cycles
  ground_truth light mesh_sphere perspective_depth scene_keys)
# The command on the new scenes: boxes.json (depth edges, light.image) and sphere.json (998,000
# triangles): rendered, every unit within 1 LSB of the reference, the cycle models agreeing.
foreach(sc boxes sphere)
  add_test(NAME gbuf.cli_${sc} COMMAND noisepipe render -o ${CMAKE_CURRENT_BINARY_DIR}/gbuf-cli
    ${PROJECT_SOURCE_DIR}/vectors/scenes/${sc}.json)
  set_tests_properties(gbuf.cli_${sc} PROPERTIES PASS_REGULAR_EXPRESSION "render: ok")
endforeach()
