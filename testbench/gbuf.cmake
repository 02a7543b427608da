# SPDX-License-Identifier: MIT
# The G-buffer renderer (src/render/np_gbuf.h, docs/render.md "The G-buffer"):
# sample positions and index matrices, the resolve's ROM, the 1x1 image from
# the centre sample, full supersampling, the references, light, meshes.
np_test_program(test_gbuf test_gbuf.c)
target_link_libraries(test_gbuf PRIVATE np_render)
target_compile_definitions(test_gbuf PRIVATE NP_SOURCE_DIR="${PROJECT_SOURCE_DIR}")
np_add_cases(test_gbuf gbuf
  index_matrices resolve_exhaustive centre_golden full_ssaa borders shared_edges depth_far shade_cycles)
