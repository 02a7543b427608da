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
