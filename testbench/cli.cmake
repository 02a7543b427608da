# SPDX-License-Identifier: MIT
# Output files, write errors and interruption (src/cli/np_outfile.h, docs/bad-input.md).
np_test_program(test_cli test_cli.c)
np_add_cases(test_cli cli
  outfile_regular_atomic outfile_fifo outfile_chardev outfile_symlink outfile_refuse
  interrupt_sigint interrupt_sigterm)

# End to end through the command: lost standard output is exit 2, never 0.
add_test(NAME cli.stdout_write_error
  COMMAND sh -c "test -w /dev/full || exit 77; \"$0\" units > /dev/full; s=$?; test $s -eq 2 || { echo \"exit $s, want 2\"; exit 1; }"
          $<TARGET_FILE:noisepipe>)
set_tests_properties(cli.stdout_write_error PROPERTIES SKIP_RETURN_CODE 77)
