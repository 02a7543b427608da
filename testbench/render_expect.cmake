# SPDX-License-Identifier: MIT
# cmake -DCMD=prog -DARGS=a;b -DWANT_RC=n -DWANT=text -P render_expect.cmake:
# run CMD ARGS; fail unless it exits with WANT_RC and its stderr contains WANT.
# Optional: -DFIRST=1: stderr must begin with WANT (the first line is the project's
# message); -DREMOVE=path: removed before the run; -DWANT_FILE=path: must exist after.
if(REMOVE)
  file(REMOVE_RECURSE ${REMOVE})
endif()
execute_process(COMMAND ${CMD} ${ARGS} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT rc EQUAL WANT_RC)
  message(FATAL_ERROR "exit status ${rc}, want ${WANT_RC}\nstdout: ${out}\nstderr: ${err}")
endif()
string(FIND "${err}" "${WANT}" at)
if(at EQUAL -1)
  message(FATAL_ERROR "stderr does not say '${WANT}':\n${err}")
endif()
if(FIRST AND NOT at EQUAL 0)
  message(FATAL_ERROR "stderr does not begin with '${WANT}':\n${err}")
endif()
if(WANT_FILE AND NOT EXISTS ${WANT_FILE})
  message(FATAL_ERROR "${WANT_FILE} was not written")
endif()
message(STATUS "exit ${rc}: ${err}")
