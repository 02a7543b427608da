# SPDX-License-Identifier: MIT
# Shared primitives: fixed-point helpers, hash, gradient, generator; the unit registry's
# configuration keys (every unit of np_units[]).
np_test_program(test_core test_core.c)
np_add_cases(test_core core
  fixed_asr fixed_round fixed_sat_sext hash_kat hash_exhaustive grad_all64 grad_fixed_range rng_kat
  unit_keys_roundtrip unit_keys_ranges unit_keys_decimal unit_keys_twice_missing unit_keys_derived
  unit_keys_model_defaults)
