# SPDX-License-Identifier: MIT
# noisepipe report fpga (src/report/report_fpga.c, docs/fpga.md): the reference RTL through
# the open iCE40 flow (yosys synth_ice40, nextpnr-ice40, icepack, icetime). The flow runs in
# CI on the smallest unit that has RTL: classic3 at its cheap configuration with the serial
# lerp engine (about 15 s); the other units' figures are in docs/fpga.md, run by hand.
# Skipped (exit 77) when nextpnr-ice40 is not installed.
set(np_fpga_skip "command -v nextpnr-ice40 > /dev/null && command -v icepack > /dev/null || { echo 'nextpnr-ice40 / icepack not installed: skipped'; exit 77; }")
set(np_fpga_cheap --unit classic3 --config out_bits=8,s_frac=4,lerp_frac=6 --rtl-param LERP_SERIAL=1)

# The flow end to end: every figure printed, the seed named, the critical path between two
# of the unit's banks, and a bitstream of an HX8K's size (135,100 bytes, the same for every
# design) that icepack's reverse, iceunpack, reads back. The target, 400 MHz, is above what
# the design reaches: it is reported as missed (nextpnr's --timing-allow-fail: the figure is
# the result, not an error) and the bitstream is still made. One run, to keep CI short.
add_test(NAME fpga.classic3_serial
  COMMAND sh -c "${np_fpga_skip}
                 d=\"$1\"; shift; rm -rf \"$d\"; \"$0\" report fpga \"$@\" -o \"$d\" > \"$d.md\"; s=$?; cat \"$d.md\"
                 test $s -eq 0 || { echo \"exit $s\"; exit 1; }
                 for f in bin asc json report.json nextpnr.log; do test -s \"$d/fpga-classic3.$f\" || { echo \"no fpga-classic3.$f\"; exit 1; }; done
                 cmp -s \"$d.md\" \"$d/fpga.md\" || { echo 'fpga.md differs from stdout'; exit 1; }
                 test $(wc -c < \"$d/fpga-classic3.bin\") -eq 135100 || { echo 'bitstream size'; exit 1; }
                 iceunpack \"$d/fpga-classic3.bin\" \"$d/unpacked.asc\" 2> /dev/null && grep -q '^.device 8k' \"$d/unpacked.asc\" || { echo 'iceunpack cannot read the bitstream'; exit 1; }"
          $<TARGET_FILE:noisepipe> ${CMAKE_CURRENT_BINARY_DIR}/fpga_classic3 ${np_fpga_cheap} --freq 400 --seed 7)
set_tests_properties(fpga.classic3_serial PROPERTIES SKIP_RETURN_CODE 77 TIMEOUT 600 LABELS "fpga;nosan"
  PASS_REGULAR_EXPRESSION "\\| LUT4 \\| [1-9][0-9]+ \\|.*\\| flip-flops \\| [1-9][0-9]+ \\|.*logic cells.*\\| [1-9][0-9]+ of 7680 .*Fmax after routing \\(nextpnr, seed 7\\) \\| \\| [1-9][0-9]*\\.[0-9][0-9] MHz \\(target 400\\.00 MHz: \\*\\*missed\\*\\*\\).*icetime.*\\| [1-9][0-9]*\\.[0-9][0-9] MHz \\|.*results per second at Fmax \\| [0-9.]+ M .*Critical path \\(nextpnr\\): from `r[0-9]_[a-z0-9]+`.* to `r[0-9]_[a-z0-9]+`")
# Without the tools: exit 2 and the packages to install.
add_test(NAME fpga.no_tools
  COMMAND sh -c "PATH=/nonexistent \"$0\" report fpga --unit classic3 > /dev/null 2> \"$1\"; s=$?; cat \"$1\";
                 test $s -eq 2 || { echo \"exit $s, want 2\"; exit 1; }; grep -q 'apt-get install yosys nextpnr-ice40 fpga-icestorm' \"$1\""
          $<TARGET_FILE:noisepipe> ${CMAKE_CURRENT_BINARY_DIR}/fpga_no_tools.err)
# Bad input, each exit 2 with its message: a unit without RTL, an unknown device, a clock out
# of range, a seed nextpnr does not take, FPGA options on another report, --synth with fpga.
add_test(NAME fpga.bad_usage
  COMMAND sh -c "chk() { want=\"$1\"; shift; \"$0\" report \"$@\" > /dev/null 2> err.txt; s=$?;
                   test $s -eq 2 || { echo \"$*: exit $s\"; exit 1; }; grep -q \"$want\" err.txt || { echo \"$*:\"; cat err.txt; exit 1; }; }
                 chk 'no reference RTL' fpga --unit fdiff
                 chk 'expected hx8k or up5k' fpga --unit classic3 --device xc7
                 chk 'expected a clock in MHz' fpga --unit classic3 --freq 0
                 chk 'up to 999999999' fpga --unit classic3 --seed 1000000000
                 chk 'go with fpga' gates --retime
                 chk 'go with fpga' gates --device up5k
                 chk 'fpga takes' fpga --synth
                 chk 'is not an RTL parameter' fpga --unit classic3 --rtl-param FOO=1"
          $<TARGET_FILE:noisepipe>)
set_tests_properties(fpga.bad_usage PROPERTIES WORKING_DIRECTORY ${CMAKE_CURRENT_BINARY_DIR})
