# SPDX-License-Identifier: MIT
# The fast paths (issue 13) against the specification: table hash and gradient,
# batch APIs, against the bit loop and the per-input models.
np_test_program(test_fast test_fast.c)
np_add_cases(test_fast fast hash_exhaustive grad_table classic_batch_random classic_batch_block
  simplex_batch_random simplex_batch_block simplex_batch_paths simplex_kernel_block simplex_kernel_random
  simplex32_exhaustive
  pipe_no_copy ref_grad_fast)
# noisepipe bench runs every figure (a crash or an overrun shows, under ASan too); timing is not asserted.
add_test(NAME fast.bench_runs COMMAND noisepipe bench --seconds 0.05)
set_tests_properties(fast.bench_runs PROPERTIES PASS_REGULAR_EXPRESSION "simplex3 \\+ derivatives, sweep kernel.*targets \\(issue 13")
# The table of every unit (bench_units.cmake): a row for each registered unit with positive figures.
add_test(NAME fast.bench_every_unit COMMAND ${CMAKE_COMMAND} -DNP=$<TARGET_FILE:noisepipe>
  -P ${CMAKE_CURRENT_SOURCE_DIR}/bench_units.cmake)
# Bad usage of the table: an unknown unit, --config without one unit, a bad configuration: exit 2, named.
foreach(c "unit;--unit;nosuch;--unit nosuch: unknown unit" "config;--config;irr=0;--config needs --unit U"
    "badcfg;--unit;wave;--config;bogus=1;unknown configuration key 'bogus'")
  list(POP_FRONT c name)
  list(POP_BACK c want)
  add_test(NAME fast.bench_usage_${name} COMMAND ${CMAKE_COMMAND} -DCMD=$<TARGET_FILE:noisepipe> "-DARGS=bench;${c}"
    -DWANT_RC=2 "-DWANT=${want}" -P ${CMAKE_CURRENT_SOURCE_DIR}/render_expect.cmake)
endforeach()
