# SPDX-License-Identifier: MIT
# The sample-count unit aacount (issue 15): model against the exact rational
# reference, host registers, stiff cases, resolve, serial cycle model.
np_test_program(test_aacount test_aacount.c)
target_include_directories(test_aacount PRIVATE ${CMAKE_CURRENT_SOURCE_DIR})
np_add_cases(test_aacount aacount
  kat ref_random ref_thresholds host_registers depth_near_max_1lsb slanted_cube_faces nbar_zero
  identical_normals luma_at_threshold k_over_n thresholds_zero_and_c_zero bayer_matrices
  resolve_exhaustive tile_max bus_roundtrip serial_model)
