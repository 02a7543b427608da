# SPDX-License-Identifier: MIT
# Shared primitives: fixed-point helpers, hash, gradient, generator.
np_test_program(test_core test_core.c)
np_add_cases(test_core core
  fixed_asr fixed_round fixed_sat_sext hash_kat hash_exhaustive grad_all64 grad_fixed_range rng_kat)
