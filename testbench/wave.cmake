# SPDX-License-Identifier: MIT
# The Gerstner wave unit (seed 004): ROM, sin/cos bound, model against the double reference over
# long times, the named stiff cases, the host's eq. (1) and dispersion (testbench/test_wave.c,
# docs/wave.md). The unit's vectors and KAT are checked by conformance.wave.*.
np_test_program(test_wave test_wave.c)
np_add_cases(test_wave wave
  rom sincos_bound vs_ref hist_year freq_drift fold nyquist a_gt_A range shallow wind frame_wrap recurrence pipe)
