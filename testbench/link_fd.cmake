# SPDX-License-Identifier: MIT
# The file-descriptor transport and the simulator child (src/link/link_fd.c: stream --sim),
# without a simulator: the board emulator in a thread behind two pipes (test_link_fd).
# The Verilated board behind them: rtl.board.sim.* (rtl_board.cmake).
np_test_program(test_link_fd test_link_fd.c)
target_link_libraries(test_link_fd PRIVATE np_link)  # pthreads through np_tools
np_add_cases(test_link_fd link.fd fd_session fd_eof fd_epipe fd_timeout spawn_missing spawn_cat spawn_stubborn)
foreach(c fd_session fd_eof fd_epipe fd_timeout spawn_missing spawn_cat spawn_stubborn)
  set_tests_properties(link.fd.${c} PROPERTIES LABELS "link" TIMEOUT 60)
endforeach()

# `noisepipe stream --tty DEVICE` (src/link/link_tty.c) without hardware: pty_board puts a
# board on the master side of a pseudo-terminal and the command opens the slave
# (testbench/tty_stream.sh):
#   link.tty.emulated           the C board emulator behind the pty: --random 3000 classic3
#   link.tty_refusals           a missing device, not a tty, a rate termios cannot set, --baud
#                               and --reconnect without a byte-stream transport: exit 2 each
#   rtl.board.sim.tty           board_sim (the Verilated gateware) behind the pty: the golden
#                               set, then --resume finds nothing to send
#   rtl.board.sim.tty_reconnect board_sim with a dropped OUT byte: --reconnect completes the run
np_test_program(pty_board pty_board.c)
target_link_libraries(pty_board PRIVATE np_link)
set(np_tty_driver ${CMAKE_CURRENT_SOURCE_DIR}/tty_stream.sh)
set(np_tty_vec ${PROJECT_SOURCE_DIR}/vectors/classic3/classic3-l1-seed1.vec)
add_test(NAME link.tty.emulated
  COMMAND sh ${np_tty_driver} $<TARGET_FILE:noisepipe> $<TARGET_FILE:pty_board> ${CMAKE_CURRENT_BINARY_DIR}/tty_runs/emulated
          emulated ${np_tty_vec} --emulate)
add_test(NAME link.tty_refusals
  COMMAND sh ${np_tty_driver} $<TARGET_FILE:noisepipe> $<TARGET_FILE:pty_board> ${CMAKE_CURRENT_BINARY_DIR}/tty_runs/refuse
          refuse ${np_tty_vec})
set_tests_properties(link.tty.emulated PROPERTIES LABELS "link" TIMEOUT 60 PASS_REGULAR_EXPRESSION "tty stream emulated: ")
set_tests_properties(link.tty_refusals PROPERTIES LABELS "link" TIMEOUT 60 PASS_REGULAR_EXPRESSION "tty refusals: 6 refusals, each exit 2")
