# SPDX-License-Identifier: MIT
# Output files, write errors and interruption (src/common/np_outfile.h, docs/bad-input.md).
np_test_program(test_cli test_cli.c)
np_add_cases(test_cli cli
  outfile_regular_atomic outfile_fifo outfile_chardev outfile_symlink outfile_refuse
  interrupt_sigint interrupt_sigterm interrupt_note_race numbers)

# End to end through the command: lost standard output is exit 2, never 0.
add_test(NAME cli.stdout_write_error
  COMMAND sh -c "test -w /dev/full || exit 77; \"$0\" units > /dev/full; s=$?; test $s -eq 2 || { echo \"exit $s, want 2\"; exit 1; }"
          $<TARGET_FILE:noisepipe>)
set_tests_properties(cli.stdout_write_error PROPERTIES SKIP_RETURN_CODE 77)

# Numbers are decimal unless documented as hex: "010" is ten, "0x10" is refused,
# "# count 0x5" in a vector file is refused naming the field (issue 11, item 2).
add_test(NAME cli.numbers_decimal
  COMMAND sh -c "\"$0\" vectors --unit classic3 --seed 010 -n 3 | grep -qx '# seed 10' || { echo 'seed 010 is not ten'; exit 1; }
                 \"$0\" vectors --unit classic3 --seed 0x10 -n 3 > /dev/null 2>&1; s=$?; test $s -eq 2 || { echo \"--seed 0x10: exit $s, want 2\"; exit 1; }
                 \"$0\" vectors --unit classic3 -n 3 | sed 's/^# count .*/# count 0x5/' > \"$1\" &&
                 \"$0\" verify \"$1\" > /dev/null 2> \"$1.err\"; s=$?; cat \"$1.err\"; test $s -eq 2 && grep -q count \"$1.err\""
          $<TARGET_FILE:noisepipe> ${CMAKE_CURRENT_BINARY_DIR}/cli_count_hex.vec)

# Progress: --progress forces it into a log (stderr not a terminal), --quiet stops it.
add_test(NAME cli.progress_forced
  COMMAND sh -c "\"$0\" sweep --unit classic3 --z 0 --x-cells 0:1 --progress 2>&1 >/dev/null | grep -q '^sweep: 100.0%' || { echo 'no progress line'; exit 1; }
                 test -z \"$(\"$0\" sweep --unit classic3 --z 0 --x-cells 0:1 --quiet 2>&1 >/dev/null)\" || { echo '--quiet printed progress'; exit 1; }"
          $<TARGET_FILE:noisepipe>)

# -o through np_outfile end to end (issue 11 item 1): a FIFO is streamed to and
# stays a FIFO, /dev/full is exit 2, a directory is exit 2 naming it, a
# symbolic link is written through and stays a link.
add_test(NAME cli.vectors_output_kinds
  COMMAND sh -c "d=\"$1\"; rm -rf \"$d\"; mkdir -p \"$d\" && mkfifo \"$d/p\" || exit 1
                 ( wc -l < \"$d/p\" > \"$d/n\" ) & r=$!
                 \"$0\" vectors --unit classic3 -n 5 -o \"$d/p\" || { echo 'fifo: exit'; exit 1; }
                 wait $r; test -p \"$d/p\" || { echo 'the FIFO was replaced'; exit 1; }
                 test \"$(cat \"$d/n\")\" -gt 100 || { echo 'the reader got too little'; exit 1; }
                 if test -w /dev/full; then \"$0\" vectors --unit classic3 -n 5 -o /dev/full 2>/dev/null; s=$?; test $s -eq 2 || { echo \"/dev/full: exit $s\"; exit 1; }; test -c /dev/full || exit 1; fi
                 \"$0\" vectors --unit classic3 -n 5 -o \"$d\" 2> \"$d.err\"; s=$?; test $s -eq 2 && grep -q 'is a directory' \"$d.err\" || { echo \"dir: exit $s\"; exit 1; }
                 : > \"$d/t\"; ln -s t \"$d/l\"
                 \"$0\" vectors --unit classic3 -n 5 -o \"$d/l\" && test -L \"$d/l\" && test -s \"$d/t\" || { echo 'symlink'; exit 1; }
                 ls \"$d\" | grep -q tmp && { echo 'a temporary file was left'; exit 1; }; exit 0"
          $<TARGET_FILE:noisepipe> ${CMAKE_CURRENT_BINARY_DIR}/cli_outkinds)
# render shows progress too (4096 x 4096 used to take minutes in silence).
add_test(NAME cli.render_progress
  COMMAND sh -c "\"$0\" render embedded:wood -o \"$1\" --progress 2>&1 >/dev/null | grep -q '^render: float reference, spans: 100.0%' &&
                 \"$0\" render embedded:wood -o \"$1\" --progress 2>&1 >/dev/null | grep -q '^render: fdiff cycle model, spans: 100.0%'"
          $<TARGET_FILE:noisepipe> ${CMAKE_CURRENT_BINARY_DIR}/cli_render_progress)
# SIGINT during a journalled sweep: exit 130, one line saying what the journal
# keeps and how to go on, and --resume finishes from there (issue 11 item 6).
add_test(NAME cli.sweep_interrupt
  COMMAND sh -c "j=\"$1\"; rm -f \"$j\" \"$j.err\"
                 \"$0\" sweep --unit classic3 --z 0 --x-cells 0:256 --journal \"$j\" > /dev/null 2> \"$j.err\" & p=$!
                 i=0; while [ $i -lt 600 ] && ! grep -q '^block' \"$j\" 2>/dev/null; do sleep 0.1; i=$((i+1)); done
                 kill -INT $p; wait $p; s=$?; cat \"$j.err\"
                 test $s -eq 130 || { echo \"exit $s, want 130\"; exit 1; }
                 grep -q 'interrupted by SIGINT' \"$j.err\" && grep -q 'keeps [0-9]* finished block' \"$j.err\" &&
                   grep -q -- '--resume' \"$j.err\" || { echo 'no note'; exit 1; }
                 k=$(sed -n 's/.*keeps \\([0-9]*\\) finished.*/\\1/p' \"$j.err\")
                 \"$0\" sweep --unit classic3 --z 0 --x-cells 0:256 --journal \"$j\" --resume --threads 1 > \"$j.out\" 2>&1 & p=$!
                 sleep 0.5; kill -TERM $p; wait $p; s=$?; cat \"$j.out\"
                 test $s -eq 143 || { echo \"resumed run, SIGTERM: exit $s, want 143\"; exit 1; }
                 grep -q \"[0-9]* finished block\" \"$j.out\" || { echo 'no note after resume'; exit 1; }
                 k2=$(sed -n 's/.*keeps \\([0-9]*\\) finished.*/\\1/p' \"$j.out\")
                 test \"$k2\" -ge \"$k\" || { echo \"the resumed journal keeps $k2 blocks, fewer than $k\"; exit 1; }; exit 0"
          $<TARGET_FILE:noisepipe> ${CMAKE_CURRENT_BINARY_DIR}/cli_sweep_interrupt.jnl)
set_tests_properties(cli.sweep_interrupt PROPERTIES TIMEOUT 120)
