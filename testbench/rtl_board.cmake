# SPDX-License-Identifier: MIT
# The board's gateware (rtl_model/verilog/board/, issue 29; docs/board.md): each module's bench
# under Icarus Verilog, Verilator's -Wall lint, and a fault copy that its bench must catch.
#   rtl.board.crc32.icarus        np_crc32.v against the host's CRC-32 on 204 messages
#   rtl.board.crc32.fault         the copy with one polynomial bit wrong must fail
#   rtl.board.crc32.lint          verilator --lint-only -Wall
# Skipped (exit 77) without iverilog / verilator.
set(NP_BOARD_SRC ${PROJECT_SOURCE_DIR}/rtl_model/verilog/board)
set(NP_BOARD_WORK ${CMAKE_CURRENT_BINARY_DIR}/rtl_board)
file(MAKE_DIRECTORY ${NP_BOARD_WORK})
add_executable(gen_crc_vectors gen_crc_vectors.c)
target_link_libraries(gen_crc_vectors PRIVATE np_tools)

# np_board_bench(NAME DEFINES EXPECT_RE): build the CRC bench with DEFINES and run it on the
# generated messages; the output must match EXPECT_RE.
function(np_board_crc_test name defs expect)
  add_test(NAME ${name}
    COMMAND sh -c "command -v iverilog > /dev/null || { echo 'iverilog not installed: skipped'; exit 77; }
                   \"$0\" 200 1 > \"$1/${name}.memh\" || exit 1
                   iverilog -g2005 -Wall ${defs} -o \"$1/${name}.vvp\" \"$2/board_crc32_tb.v\" \"$3/np_crc32.v\" || exit 1
                   vvp -n \"$1/${name}.vvp\" +vectors=\"$1/${name}.memh\""
            $<TARGET_FILE:gen_crc_vectors> ${NP_BOARD_WORK} ${CMAKE_CURRENT_SOURCE_DIR}/rtl ${NP_BOARD_SRC})
  set_tests_properties(${name} PROPERTIES SKIP_RETURN_CODE 77 LABELS "rtl;board" PASS_REGULAR_EXPRESSION "${expect}")
endfunction()
np_board_crc_test(rtl.board.crc32.icarus "" "In 204 messages, 0 errors found\\.")
np_board_crc_test(rtl.board.crc32.fault "-DNP_FAULT_CRC" "In 204 messages, 20[0-4] errors found\\.")
add_test(NAME rtl.board.crc32.lint
  COMMAND sh -c "command -v verilator > /dev/null || { echo 'verilator not installed: skipped'; exit 77; }
                 verilator --lint-only -Wall \"$0/np_crc32.v\" && echo 'lint clean'" ${NP_BOARD_SRC})
set_tests_properties(rtl.board.crc32.lint PROPERTIES SKIP_RETURN_CODE 77 LABELS "rtl;board;nosan" PASS_REGULAR_EXPRESSION "lint clean")
