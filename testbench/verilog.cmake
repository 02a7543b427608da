# SPDX-License-Identifier: MIT
# The Icarus Verilog scoreboard (classic3_tb.v, np_vec_check.v) on golden
# vectors exported as $readmemh files. Driver: verilog_check.cmake.
#   verilog.bench_selftest               hand-made files: pass, flipped bit, counts
#   verilog.classic3_readmemh            noisepipe vectors + device results: pass
#   verilog.classic3_detects_flipped_bit one result bit flipped: the bench must fail
# Without iverilog (Debian package iverilog; .ci/bootstrap installs it) the
# tests are registered and report themselves skipped.
find_program(NP_IVERILOG iverilog)
find_program(NP_VVP vvp)
if(NOT NP_IVERILOG OR NOT NP_VVP)
  message(STATUS "iverilog/vvp not found: the verilog.* tests will be skipped (apt-get install iverilog)")
endif()

# Vectors: level 1 of the default seed. The device reads the text vector file.
set(NP_VERILOG_VECTORS_ARGS "--level,1")
set(NP_VERILOG_DEVICE_ARGS "")

function(np_verilog_test name mode)
  add_test(NAME verilog.${name}
    COMMAND ${CMAKE_COMMAND}
      -DMODE=${mode}
      -DIVERILOG=${NP_IVERILOG} -DVVP=${NP_VVP}
      -DTB_DIR=${CMAKE_CURRENT_SOURCE_DIR}
      -DWORK=${CMAKE_CURRENT_BINARY_DIR}/verilog/${name}
      -DNOISEPIPE=$<TARGET_FILE:noisepipe>
      -DVECTORS_ARGS=${NP_VERILOG_VECTORS_ARGS}
      -DDEVICE_ARGS=${NP_VERILOG_DEVICE_ARGS}
      ${ARGN}
      -P ${CMAKE_CURRENT_SOURCE_DIR}/verilog_check.cmake)
  set_tests_properties(verilog.${name} PROPERTIES
    TIMEOUT 300
    SKIP_REGULAR_EXPRESSION "verilog: SKIPPED: ")
endfunction()

np_verilog_test(bench_selftest selftest)
np_verilog_test(classic3_readmemh readmemh)
np_verilog_test(classic3_detects_flipped_bit flip -DFLIP_AT=100 -DFLIP_BIT=3)
