# SPDX-License-Identifier: MIT
# The board's gateware (rtl_model/verilog/board/, issue 29; docs/board.md): each module's bench
# under Icarus Verilog, Verilator's -Wall lint, and a fault copy that its bench must catch.
#   rtl.board.crc32.icarus        np_crc32.v against the host's CRC-32 on 204 messages
#   rtl.board.crc32.fault         the copy with one polynomial bit wrong must fail
#   rtl.board.crc32.lint          verilator --lint-only -Wall
# and the UART below.
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

# The UART (np_uart_tx.v, np_uart_rx.v; the FT2232H's channel to the FPGA):
#   rtl.board.uart.cpb8           board_uart_tb.v at 8 clocks a bit, the sender's bit time +-3 %
#   rtl.board.uart.cpb4           at 4 clocks a bit (12 MHz / 3 Mbaud), +-2 %
#   rtl.board.uart.fault_{tx,rx}  the fault copies (a rotated byte) must fail
#   rtl.board.uart.lint           verilator -Wall at 4 and at 104 clocks a bit
function(np_board_uart_test name defs expect)
  add_test(NAME ${name}
    COMMAND sh -c "command -v iverilog > /dev/null || { echo 'iverilog not installed: skipped'; exit 77; }
                   iverilog -g2005 -Wall -Wno-timescale ${defs} -o \"$0/${name}.vvp\" \"$1/board_uart_tb.v\" \"$2/np_uart_tx.v\" \"$2/np_uart_rx.v\" || exit 1
                   vvp -n \"$0/${name}.vvp\""
            ${NP_BOARD_WORK} ${CMAKE_CURRENT_SOURCE_DIR}/rtl ${NP_BOARD_SRC})
  set_tests_properties(${name} PROPERTIES SKIP_RETURN_CODE 77 LABELS "rtl;board" PASS_REGULAR_EXPRESSION "${expect}")
endfunction()
np_board_uart_test(rtl.board.uart.cpb8 "-DCPB=8 -DEPPM=30000" "75 framing errors flagged.*In 1925 bytes, 0 errors found\\.")
np_board_uart_test(rtl.board.uart.cpb4 "-DCPB=4 -DEPPM=20000" "75 framing errors flagged.*In 1925 bytes, 0 errors found\\.")
np_board_uart_test(rtl.board.uart.fault_tx "-DNP_FAULT_UART_TX" "In 1925 bytes, [1-9][0-9]* errors found\\.")
np_board_uart_test(rtl.board.uart.fault_rx "-DNP_FAULT_UART_RX" "In 1925 bytes, [1-9][0-9]* errors found\\.")
add_test(NAME rtl.board.uart.lint
  COMMAND sh -c "command -v verilator > /dev/null || { echo 'verilator not installed: skipped'; exit 77; }
                 for m in tx rx; do for c in 4 104; do verilator --lint-only -Wall -GCLKS_PER_BIT=$c \"$0/np_uart_$m.v\" || exit 1; done; done; echo 'lint clean'" ${NP_BOARD_SRC})
set_tests_properties(rtl.board.uart.lint PROPERTIES SKIP_RETURN_CODE 77 LABELS "rtl;board;nosan" PASS_REGULAR_EXPRESSION "lint clean")
