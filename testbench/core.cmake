# SPDX-License-Identifier: MIT
# Shared primitives: fixed-point helpers, hash, gradient, generator; the unit registry's
# configuration keys (every unit of np_units[]).
np_test_program(test_core test_core.c)
np_add_cases(test_core core
  fixed_asr fixed_round fixed_sat_sext hash_kat hash_exhaustive grad_all64 grad_fixed_range rng_kat
  unit_keys_roundtrip unit_keys_ranges unit_keys_decimal unit_keys_twice_missing unit_keys_derived
  unit_keys_model_defaults)

# The layer check (testbench/layer_check.c, docs/architecture.md "The layer order"): every
# #include under rtl_model/ and src/ against the order the document states.
add_executable(layer_check layer_check.c)
add_test(NAME layers.check COMMAND layer_check ${PROJECT_SOURCE_DIR})
set_tests_properties(layers.check PROPERTIES PASS_REGULAR_EXPRESSION "layer check: [0-9]+ files, [1-9][0-9]* includes between folders, [0-9]+ known exceptions.* 0 include circles, 0 failures")
# The check must fail on a forbidden include: a copy of the tree with src/units/units.c including
# the renderer's np_render.h (units, level 4, including render, level 6), named with its line.
add_test(NAME layers.check_fails
  COMMAND sh -c "rm -rf \"$1\" && mkdir -p \"$1\" && cp -r \"$2/src\" \"$2/rtl_model\" \"$2/docs\" \"$1/\" || exit 2
                 n=$(( $(wc -l < \"$1/src/units/units.c\") + 1 ))
                 echo '#include \"np_render.h\"' >> \"$1/src/units/units.c\"
                 \"$0\" \"$1\" > /dev/null 2> \"$1.err\"; s=$?; cat \"$1.err\"
                 test $s -eq 1 || { echo \"exit $s, want 1\"; exit 1; }
                 grep -q \"^src/units/units.c:$n: #include .np_render.h. (render, level 6) from units (level 4) goes up\" \"$1.err\" || { echo 'no message naming units.c:'$n; exit 1; }
                 # and a listed exception that matches no include is reported (the list only shrinks):
                 # a row for an include that is not there, added to the copy's table
                 sed -i '/^<!-- .layer-exceptions -->/i | src/units/units.c | np_gone.h | a stale row |' \"$1/docs/architecture.md\"
                 \"$0\" \"$1\" > /dev/null 2> \"$1.err2\"; cat \"$1.err2\"
                 grep -q 'exception src/units/units.c -> np_gone.h matches no forbidden include' \"$1.err2\" || exit 1
                 # and an include circle inside one folder: np_fixed.h <-> np_classic.h
                 echo '#include \"np_classic.h\"' >> \"$1/rtl_model/np_fixed.h\"
                 \"$0\" \"$1\" > /dev/null 2> \"$1.err3\"; cat \"$1.err3\"
                 grep -q 'include circle: np_[a-z]*.h -> np_[a-z]*.h -> np_[a-z]*.h' \"$1.err3\" && grep -q 'np_fixed.h' \"$1.err3\" && grep -q 'np_classic.h' \"$1.err3\""
          $<TARGET_FILE:layer_check> ${CMAKE_CURRENT_BINARY_DIR}/layers_fail ${PROJECT_SOURCE_DIR})
