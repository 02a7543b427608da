# SPDX-License-Identifier: MIT
# The classic noise unit: bit-exact model, float reference, cycle model.
np_test_program(test_classic test_classic.c pipe_drive.c widths.c)
np_add_cases(test_classic classic
  kat lattice_points_zero ref_properties in_cell_matches_eval cycle_vs_model cycle_throughput
  cycle_reset signal_widths error_bound_configs cfg_validation datapath_widths)
