# SPDX-License-Identifier: MIT
# The simplex noise unit: float reference vs Appendix B, derivative, bit-exact model, stability
# cases, cycle-accurate model (testbench/test_simplex.c and the simplex_*.c files it names;
# docs/simplex3.md has the figures).
np_test_program(test_simplex test_simplex.c simplex_common.c simplex_reference.c simplex_model.c
  simplex_pipeline.c simplex_stiff.c pipe_drive.c widths.c)
np_add_cases(test_simplex simplex
  ref_vs_appendix_b deriv_vs_central_diff kat random_1e7 cycle_vs_model_1e6
  faces_uv faces_vw faces_uw faces_uvw kernel_t_zero extremes_0_and_max max_magnitude
  reference_face_jump wrap
  div3_exhaustive deriv_off_same_f error_bound_configs registry datapath_widths rtl_widths)
set_tests_properties(simplex.random_1e7 PROPERTIES TIMEOUT 120)
