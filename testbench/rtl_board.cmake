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

# The protocol engine (np_link_engine.v; np_board_core.v: the engine with classic3 LERP_SERIAL behind it):
#   rtl.board.engine.lint             verilator --lint-only -Wall: the core, and the engine alone at
#                                     the largest max_payload (65532, a 128 KiB buffer)
#   rtl.board.diff.build[.FAULT]      board_diff: the Verilated core with the C board emulator (fixture)
#   rtl.board.diff                    the same OUT streams into both (a session, 12 faults, each
#                                     also with the IN side stalled): identical IN bytes
#   rtl.board.diff.fault_seq, .fault_pcrc  the engine that takes any seq (NP_FAULT_LINK_SEQ) or
#                                     any pcrc (NP_FAULT_LINK_PCRC) must be caught
set(NP_BOARD_CORE_SRC ${NP_BOARD_SRC}/np_board_core.v ${NP_BOARD_SRC}/np_link_engine.v ${NP_BOARD_SRC}/np_crc32.v
  ${PROJECT_SOURCE_DIR}/rtl_model/verilog/np_classic3.v ${PROJECT_SOURCE_DIR}/rtl_model/verilog/np_pipe_in_reg.v
  ${PROJECT_SOURCE_DIR}/rtl_model/verilog/np_pipe_skid.v)
add_test(NAME rtl.board.engine.lint
  COMMAND sh -c "command -v verilator > /dev/null || { echo 'verilator not installed: skipped'; exit 77; }
                 verilator --lint-only -Wall -I\"$0/..\" --top-module np_board_core \"$0/np_board_core.v\" \"$0/np_link_engine.v\" \"$0/np_crc32.v\" \"$0/../np_classic3.v\" \"$0/../np_pipe_in_reg.v\" \"$0/../np_pipe_skid.v\" || exit 1
                 verilator --lint-only -Wall -GMAX_PAYLOAD=65532 -GRXB_AW=17 \"$0/np_link_engine.v\" \"$0/np_crc32.v\" || exit 1
                 echo 'lint clean'" ${NP_BOARD_SRC})
set_tests_properties(rtl.board.engine.lint PROPERTIES SKIP_RETURN_CODE 77 LABELS "rtl;board;nosan" PASS_REGULAR_EXPRESSION "lint clean")

# The C side of the harnesses: the link library and what it needs (src/CMakeLists.txt's NP_SRC_DIRS).
set(np_board_cflags "-O2 -Wall -Wextra -Werror -I${PROJECT_SOURCE_DIR}/rtl_model")
foreach(d common cli bench units vectors journal sweep ref render report link wave)
  string(APPEND np_board_cflags " -I${PROJECT_SOURCE_DIR}/src/${d}")
endforeach()
set(np_board_ldflags "$<TARGET_FILE:np_link> $<TARGET_FILE:np_tools> $<TARGET_FILE:np_rtl_model> -lm -lpthread")

# np_board_verilate(name top cpp defines sources...): a Verilated harness ${NP_BOARD_WORK}/<name>/<name>,
# built by the test rtl.board.<name>.build (fixture rtl_board_<name>). A fault copy (an NP_FAULT_
# define) is compiled at -O0: it runs once. defs may also set the top's parameters (-GNAME=V).
function(np_board_verilate name top cpp defs)
  set(dir ${NP_BOARD_WORK}/${name})
  file(MAKE_DIRECTORY ${dir})
  set(vopt)
  if(defs MATCHES "NP_FAULT")
    set(vopt -MAKEFLAGS OPT_FAST=-O0 -MAKEFLAGS OPT_SLOW=-O0 -MAKEFLAGS OPT_GLOBAL=-O0)
  endif()
  np_rtl_test(rtl.board.${name}.build "${NP_VERILATOR}" pass "" "rtl;board;nosan"
    ${NP_VERILATOR} --cc --exe --build -j 1 -Wall -I${PROJECT_SOURCE_DIR}/rtl_model/verilog ${defs} ${vopt} ${NP_VERILATOR_CACHE}
    --top-module ${top} --prefix Vbd -Mdir ${dir} -o ${name} -CFLAGS ${np_board_cflags} -LDFLAGS ${np_board_ldflags}
    ${CMAKE_CURRENT_SOURCE_DIR}/rtl/${cpp} ${ARGN})
  set_tests_properties(rtl.board.${name}.build PROPERTIES FIXTURES_SETUP rtl_board_${name})
endfunction()
# np_board_run(test name expect pattern args...)
function(np_board_run test name expect pattern)
  np_rtl_test(${test} "${NP_VERILATOR}" ${expect} "${pattern}" "rtl;board;nosan" ${NP_BOARD_WORK}/${name}/${name} ${ARGN})
  set_tests_properties(${test} PROPERTIES FIXTURES_REQUIRED rtl_board_${name})
endfunction()

np_board_verilate(diff np_board_core board_diff.cpp "" ${NP_BOARD_CORE_SRC})
np_board_verilate(diff_fault_seq np_board_core board_diff.cpp "-DNP_FAULT_LINK_SEQ" ${NP_BOARD_CORE_SRC})
np_board_verilate(diff_fault_pcrc np_board_core board_diff.cpp "-DNP_FAULT_LINK_PCRC" ${NP_BOARD_CORE_SRC})
np_board_run(rtl.board.diff diff pass "In 28 streams, [0-9]+ frames \\([0-9]+ bytes\\) compared, 0 mismatches\\." --seed 1 --frames 40)
np_board_run(rtl.board.diff.seed2 diff pass "In 28 streams, [0-9]+ frames \\([0-9]+ bytes\\) compared, 0 mismatches\\." --seed 2 --frames 40)
set(np_diff_caught "compared, [1-9][0-9]* mismatches\\.")
np_board_run(rtl.board.diff.fault_seq diff_fault_seq fail "Streams that differ:.* wrong_seq[ .].*${np_diff_caught}" --seed 1 --frames 40)
np_board_run(rtl.board.diff.fault_pcrc diff_fault_pcrc fail "Streams that differ:.* pcrc[ .].*${np_diff_caught}" --seed 1 --frames 40)

# The whole board (np_board_top.v: UART in, engine, classic3, UART out) driven by the real host
# engine (np_host_*, src/link/link_engine.c) through a UART line model (board_e2e.cpp):
#   rtl.board.top.lint               verilator --lint-only -Wall
#   rtl.board.e2e                    2,000 random vectors, one session, every one verified
#   rtl.board.e2e.faults             3,000 vectors with a dropped OUT byte, two flipped OUT bits and a
#                                    flipped IN bit on the line: the host's link faults, new sessions
#                                    on the same journal, every vector verified exactly once
#   rtl.board.e2e.fault_flip         classic3 with NP_FAULT_FLIP behind the engine: the host must
#                                    report failing vectors
set(NP_BOARD_TOP_SRC ${NP_BOARD_SRC}/np_board_top.v ${NP_BOARD_SRC}/np_uart_rx.v ${NP_BOARD_SRC}/np_uart_tx.v
  ${NP_BOARD_CORE_SRC})
add_test(NAME rtl.board.top.lint
  COMMAND sh -c "command -v verilator > /dev/null || { echo 'verilator not installed: skipped'; exit 77; }
                 verilator --lint-only -Wall -I\"$0/..\" --top-module np_board_top \"$0/np_board_top.v\" \"$0/np_uart_rx.v\" \"$0/np_uart_tx.v\" \"$0/np_board_core.v\" \"$0/np_link_engine.v\" \"$0/np_crc32.v\" \"$0/../np_classic3.v\" \"$0/../np_pipe_in_reg.v\" \"$0/../np_pipe_skid.v\" && echo 'lint clean'" ${NP_BOARD_SRC})
set_tests_properties(rtl.board.top.lint PROPERTIES SKIP_RETURN_CODE 77 LABELS "rtl;board;nosan" PASS_REGULAR_EXPRESSION "lint clean")
# The board's top (np_board_hx8k.v: np_board_top with the HX8K breakout's clock, power-on reset and LEDs)
add_test(NAME rtl.board.hx8k.lint
  COMMAND sh -c "command -v verilator > /dev/null || { echo 'verilator not installed: skipped'; exit 77; }
                 verilator --lint-only -Wall -I\"$0/..\" --top-module np_board_hx8k \"$0/np_board_hx8k.v\" \"$0/np_board_led_hold.v\" \"$0/np_board_top.v\" \"$0/np_uart_rx.v\" \"$0/np_uart_tx.v\" \"$0/np_board_core.v\" \"$0/np_link_engine.v\" \"$0/np_crc32.v\" \"$0/../np_classic3.v\" \"$0/../np_pipe_in_reg.v\" \"$0/../np_pipe_skid.v\" && echo 'lint clean'" ${NP_BOARD_SRC})
set_tests_properties(rtl.board.hx8k.lint PROPERTIES SKIP_RETURN_CODE 77 LABELS "rtl;board;nosan" PASS_REGULAR_EXPRESSION "lint clean")
np_board_verilate(e2e np_board_top board_e2e.cpp "" ${NP_BOARD_TOP_SRC})
np_board_verilate(e2e_fault_flip np_board_top board_e2e.cpp "-DNP_FAULT_FLIP" ${NP_BOARD_TOP_SRC})
np_board_run(rtl.board.e2e e2e pass
  "In 2000 records, 2000 verified in 1 sessions \\(2000 counted by the sessions\\), 0 failed: every record verified exactly once\\."
  --records 2000 --seed 1)
np_board_run(rtl.board.e2e.faults e2e pass
  "4 faults injected.*In 3000 records, 3000 verified in [2-8] sessions \\(3000 counted by the sessions\\), 0 failed: every record verified exactly once\\."
  --records 3000 --seed 1 --fault drop-out:4000 --fault flip-in:6000 --fault flip-out:15000 --fault drop-out:20000)
np_board_run(rtl.board.e2e.fault_flip e2e_fault_flip fail "In 2000 records, 2000 verified in 1 sessions .*, [1-9][0-9]* failed: NOT verified\\."
  --records 2000 --seed 1)

# `noisepipe stream --sim` against the whole board (board_sim.cpp: np_board_top under Verilator on
# stdin/stdout, the line model of board_e2e.cpp, faults on the line, a reset of the gateware):
# the command's own fd transport (src/link/link_fd.c), journal, --resume and verdict.
# Driver: board_sim_stream.sh (its cases: clean, fault, kill, fail, refuse). Golden set: the
# checked-in classic3-l1-seed1.vec (4,224 vectors) is of the gateware's configuration,
# out_bits=8 s_frac=12 lerp_frac=11 (classic3's default).
#   rtl.board.board_sim.build[_fault_flip]   the simulator (fixtures rtl_board_board_sim...)
#   rtl.board.sim.golden                     one run: 4,224 verified, BYE_ACK counts them
#   rtl.board.sim.{drop,flip}_{out,in}       a byte lost or a bit flipped on the line: exit 1, --resume
#   rtl.board.sim.stall_{out,in}             the bridge stops (shorter than the time-out): one run
#   rtl.board.sim.stall_long                 the IN side held longer than the time-out: --resume
#   rtl.board.sim.reset                      the gateware reset mid-stream: time-out, --resume
#   rtl.board.sim.reset_reconnect            the same with --reconnect 2: the same board_sim process
#                                            answers a new HELLO; one run verifies every vector once
#   rtl.board.sim.kill_resume                the command SIGKILLed mid-stream, then --resume
#   rtl.board.sim.fault_flip                 classic3 with NP_FAULT_FLIP: the verdict must fail
#   rtl.board.board_sim_bp.build             the gateware at MAX_PAYLOAD 2000: a frame of 2,028 bytes
#                                            in the 2,048-byte OUT buffer, so the next frame's bytes
#                                            meet rts_n high while a RESULT goes out
#   rtl.board.sim.backpressure               on it: rts_n high, host bytes held back, every vector
#                                            verified once, no overflow
#   rtl.board.sim.ignore_rts                 on it, the bridge ignoring rts_n: overflow and a link
#                                            fault must be seen (not silent loss), then --resume
#   link.sim_refusals                        a program that cannot run or ends at once: exit 2
np_board_verilate(board_sim np_board_top board_sim.cpp "" ${NP_BOARD_TOP_SRC})
np_board_verilate(board_sim_fault_flip np_board_top board_sim.cpp "-DNP_FAULT_FLIP" ${NP_BOARD_TOP_SRC})
set(np_sim_vec ${PROJECT_SOURCE_DIR}/vectors/classic3/classic3-l1-seed1.vec)
set(np_sim_driver ${CMAKE_CURRENT_SOURCE_DIR}/board_sim_stream.sh)
# np_board_sim_test(name sim case args...): the driver's CASE against the simulator built as <sim>
function(np_board_sim_test name sim case)
  add_test(NAME rtl.board.sim.${name}
    COMMAND sh ${np_sim_driver} $<TARGET_FILE:noisepipe> ${NP_BOARD_WORK}/${sim}/${sim}
            ${NP_BOARD_WORK}/sim_runs/${name} ${case} ${np_sim_vec} ${ARGN})
  if(case STREQUAL "fail")
    set(pat "the faulty board was caught")
  else()
    set(pat "board_sim stream ${case}: 4224 vectors verified exactly once in")
  endif()
  set_tests_properties(rtl.board.sim.${name} PROPERTIES SKIP_RETURN_CODE 77 TIMEOUT 120 LABELS "rtl;board;nosan"
    FIXTURES_REQUIRED rtl_board_${sim} PASS_REGULAR_EXPRESSION "${pat}")
endfunction()
np_board_sim_test(golden board_sim clean)
np_board_sim_test(drop_out board_sim fault --fault drop-out:9000)
np_board_sim_test(drop_in board_sim fault --fault drop-in:5000)
np_board_sim_test(flip_out board_sim fault --fault flip-out:12000)
np_board_sim_test(flip_in board_sim fault --fault flip-in:7000)
np_board_sim_test(stall_out board_sim fault --fault stall-out:10000:400ms)
np_board_sim_test(stall_in board_sim fault --fault stall-in:6000:200000)
np_board_sim_test(stall_long board_sim fault --fault stall-in:6000:2500ms)
np_board_sim_test(reset board_sim fault --fault reset:15000)
np_board_sim_test(reset_reconnect board_sim reconnect --fault reset:15000)
np_board_sim_test(kill_resume board_sim kill --pace 600000)
np_board_sim_test(fault_flip board_sim_fault_flip fail)
np_board_verilate(board_sim_bp np_board_top board_sim.cpp "-GMAX_PAYLOAD=2000" ${NP_BOARD_TOP_SRC})
np_board_sim_test(backpressure board_sim_bp backpressure)
np_board_sim_test(ignore_rts board_sim_bp overflow --fault ignore-rts:0)
# --tty through a pseudo-terminal with board_sim on its master side (pty_board, tty_stream.sh;
# link_fd.cmake has the emulator's and the refusals):
#   rtl.board.sim.tty             the golden set through /dev/pts/N, --resume on it: 0 to send
#   rtl.board.sim.tty_reconnect   a dropped OUT byte: --reconnect 2 completes the one run
foreach(c tty tty_reconnect)
  if(c STREQUAL "tty")
    set(tcase sim)
    set(targs)
  else()
    set(tcase reconnect)
    set(targs --fault drop-out:9000)
  endif()
  add_test(NAME rtl.board.sim.${c}
    COMMAND sh ${CMAKE_CURRENT_SOURCE_DIR}/tty_stream.sh $<TARGET_FILE:noisepipe> $<TARGET_FILE:pty_board>
            ${NP_BOARD_WORK}/sim_runs/${c} ${tcase} ${np_sim_vec} ${NP_BOARD_WORK}/board_sim/board_sim ${targs})
  set_tests_properties(rtl.board.sim.${c} PROPERTIES SKIP_RETURN_CODE 77 TIMEOUT 120 LABELS "rtl;board;nosan"
    FIXTURES_REQUIRED rtl_board_board_sim PASS_REGULAR_EXPRESSION "tty stream ${tcase}: 4224 vectors verified")
endforeach()
add_test(NAME link.sim_refusals
  COMMAND sh ${np_sim_driver} $<TARGET_FILE:noisepipe> none ${NP_BOARD_WORK}/sim_runs/refuse refuse ${np_sim_vec})
set_tests_properties(link.sim_refusals PROPERTIES LABELS "link;board" TIMEOUT 60
  PASS_REGULAR_EXPRESSION "6 refusals, each exit 2")
