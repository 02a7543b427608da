/* SPDX-License-Identifier: MIT */
/*
 * The simplex noise unit: float reference against Appendix B, analytic
 * derivative against central differences, bit-exact model (pinned outputs,
 * accuracy, stability cases), cycle-accurate model. The cases live in
 * simplex_*.c by concern (simplex_test.h lists the files); this file names
 * them for CTest (simplex.<name>).
 */
#include "simplex_test.h"

static const np_test_case cases[] = {
    { "ref_vs_appendix_b", simplex_ref_vs_appendix_b },
    { "deriv_vs_central_diff", simplex_deriv_vs_central_diff },
    { "kat", simplex_kat },
    { "random_1e7", simplex_random_1e7 },
    { "cycle_vs_model_1e6", simplex_cycle_vs_model_1e6 },
    { "faces_uv", simplex_faces_uv },
    { "faces_vw", simplex_faces_vw },
    { "faces_uw", simplex_faces_uw },
    { "faces_uvw", simplex_faces_uvw },
    { "kernel_t_zero", simplex_kernel_t_zero },
    { "extremes_0_and_max", simplex_extremes_0_and_max },
    { "max_magnitude", simplex_max_magnitude },
    { "reference_face_jump", simplex_reference_face_jump },
    { "wrap", simplex_wrap },
    { "div3_exhaustive", simplex_div3_exhaustive },
    { "deriv_off_same_f", simplex_deriv_off_same_f },
    { "error_bound_configs", simplex_error_bound_configs },
    { "registry", simplex_registry },
    { "datapath_widths", simplex_datapath_widths },
    { "rtl_widths", simplex_rtl_widths },
    { NULL, NULL },
};

NP_TEST_MAIN(cases)
