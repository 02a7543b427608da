# SPDX-License-Identifier: MIT
# noisepipe report gates --synth (src/report/report_synth.c, docs/cost-model.md):
# Yosys on the reference RTL per stage beside the cost model.
# Without yosys the flag says so and exits 2 (checked with an empty PATH).
add_test(NAME synth.no_yosys
  COMMAND sh -c "PATH=/nonexistent \"$0\" report gates --synth --unit classic3 > /dev/null 2> \"$1\"; s=$?; cat \"$1\";
                 test $s -eq 2 || { echo \"exit $s, want 2\"; exit 1; }; grep -q 'needs yosys' \"$1\""
          $<TARGET_FILE:noisepipe> ${CMAKE_CURRENT_BINARY_DIR}/synth_no_yosys.err)
# A unit without reference RTL, and --tolerance without --synth, are usage errors.
add_test(NAME synth.bad_usage
  COMMAND sh -c "\"$0\" report gates --synth --unit fdiff > /dev/null 2>&1; s=$?; test $s -eq 2 || { echo \"fdiff: exit $s\"; exit 1; }
                 \"$0\" report gates --tolerance 10 > /dev/null 2>&1; s=$?; test $s -eq 2 || { echo \"--tolerance alone: exit $s\"; exit 1; }"
          $<TARGET_FILE:noisepipe>)
# The drift test: the synthesis on a small configuration of classic3 (about 20 s
# of CPU) and every stage of the cost model within 10 % of it (exit 1 otherwise;
# docs/cost-model.md has the table for the default and other configurations).
add_test(NAME synth.classic3_cheap
  COMMAND sh -c "command -v yosys > /dev/null || { echo 'yosys not installed: skipped'; exit 77; }
                 \"$0\" report gates --synth --unit classic3 --config out_bits=8,s_frac=4,lerp_frac=6 --tolerance 10"
          $<TARGET_FILE:noisepipe>)
set_tests_properties(synth.classic3_cheap PROPERTIES SKIP_RETURN_CODE 77 TIMEOUT 900 LABELS "synth"
  PASS_REGULAR_EXPRESSION "\\| O \\|.*\\| \\*\\*total\\*\\* \\|.*largest stage deviation [0-9]\\.[0-9] %")
