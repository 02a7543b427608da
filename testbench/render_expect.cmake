# SPDX-License-Identifier: MIT
# cmake -DCMD=prog -DARGS=a;b -DWANT_RC=n -DWANT=text -P render_expect.cmake:
# run CMD ARGS; fail unless it exits with WANT_RC and its stderr contains WANT.
execute_process(COMMAND ${CMD} ${ARGS} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT rc EQUAL WANT_RC)
  message(FATAL_ERROR "exit status ${rc}, want ${WANT_RC}\nstdout: ${out}\nstderr: ${err}")
endif()
string(FIND "${err}" "${WANT}" at)
if(at EQUAL -1)
  message(FATAL_ERROR "stderr does not say '${WANT}':\n${err}")
endif()
message(STATUS "exit ${rc}: ${err}")
