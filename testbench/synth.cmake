# SPDX-License-Identifier: MIT
# noisepipe report gates --synth (src/report/report_synth.c, docs/cost-model.md):
# Yosys on the reference RTL per stage beside the cost model.
# Without yosys the flag says so and exits 2 (checked with an empty PATH).
add_test(NAME synth.no_yosys
  COMMAND sh -c "PATH=/nonexistent \"$0\" report gates --synth --unit classic3 > /dev/null 2> \"$1\"; s=$?; cat \"$1\";
                 test $s -eq 2 || { echo \"exit $s, want 2\"; exit 1; }; grep -q 'needs yosys' \"$1\""
          $<TARGET_FILE:noisepipe> ${CMAKE_CURRENT_BINARY_DIR}/synth_no_yosys.err)
# A unit without reference RTL, and --tolerance without --synth, are usage errors.
add_test(NAME synth.bad_usage
  COMMAND sh -c "\"$0\" report gates --synth --unit fdiff > /dev/null 2>&1; s=$?; test $s -eq 2 || { echo \"fdiff: exit $s\"; exit 1; }
                 \"$0\" report gates --tolerance 10 > /dev/null 2>&1; s=$?; test $s -eq 2 || { echo \"--tolerance alone: exit $s\"; exit 1; }"
          $<TARGET_FILE:noisepipe>)
# np_synth_test(NAME LABELS PATTERN ARGS...): `noisepipe report gates --synth ARGS...`, skipped
# (exit 77) without yosys on PATH, passing when its output matches PATTERN.
function(np_synth_test name labels pattern)
  add_test(NAME ${name}
    COMMAND sh -c "command -v yosys > /dev/null || { echo 'yosys not installed: skipped'; exit 77; }
                   exec \"$0\" report gates --synth \"$@\"" $<TARGET_FILE:noisepipe> ${ARGN})
  set_tests_properties(${name} PROPERTIES SKIP_RETURN_CODE 77 TIMEOUT 900 LABELS "${labels}"
    PASS_REGULAR_EXPRESSION "${pattern}")
endfunction()

# The drift test: the synthesis on a small configuration of classic3 (about 20 s
# of CPU) and every stage of the cost model within 10 % of it (exit 1 otherwise;
# docs/cost-model.md has the table for the default and other configurations).
np_synth_test(synth.classic3_cheap "synth"
  "\\| O \\|.*\\| \\*\\*total\\*\\* \\|.*largest stage deviation [0-9]\\.[0-9] %"
  --unit classic3 --config out_bits=8,s_frac=4,lerp_frac=6 --tolerance 10)
# The same for simplex3 at its cheapest calibrated configuration (f only, t_frac = p_frac = 9,
# k_frac = 6: the front end SK..P2 is as at the default, the rest narrow; about 95 s of CPU
# with --per-stage, which keeps ABC on one stage at a time). docs/cost-model.md has the table
# for it, the default and two other configurations.
np_synth_test(synth.simplex3_cheap "synth;nosan"
  "\\| KT \\|.*\\| O \\|.*\\| \\*\\*total\\*\\* \\|.*largest stage deviation [0-9]\\.[0-9] %"
  --unit simplex3 --per-stage --config deriv=0,out_bits=4,t_frac=9,p_frac=9,k_frac=6 --tolerance 10)
# The n-D classic RTL (np_classicn.v, by --unit only) at classic2's default, about 25 s of Yosys:
# every stage's bank found (its row has Yosys flip-flops and gates; the banks are selected by
# name, report_synth.c classicn_bank_sel). Its tolerance is checked by synth.dims_classic2 below.
set(row "\\| [0-9]+ \\| [0-9]+ \\([0-9]+\\) \\| [0-9]+ \\| [1-9][0-9]* \\| [1-9][0-9]* \\|")
set(cn2 "")
foreach(st L H I1m I1a I2m I2a O)
  string(APPEND cn2 "\\| ${st} ${row}.*")
endforeach()
np_synth_test(synth.classic2 "synth;nosan" "${cn2}\\| \\*\\*total\\*\\* \\|.*largest stage deviation"
  --unit classic2)
# --rtl-param (RTL parameters that are not configuration keys): bad uses exit 2 before any
# synthesis (an unknown name, naming the allowed ones; a value other than 0/1; without --unit;
# with --tolerance, since the cost model declares no variant).
add_test(NAME synth.rtl_param_usage
  COMMAND sh -c "for a in '--unit classic3 --rtl-param FOO=1' '--unit classic3 --rtl-param S_TABLE=2' \\
                          '--unit classic3 --rtl-param S_TABLE' '--rtl-param S_TABLE=1' \\
                          '--unit simplex3 --rtl-param HASH_SERIAL=1' '--unit classic3 --rtl-param S_TABLE=1 --tolerance 10'; do
                   \"$0\" report gates --synth $a > /dev/null 2> \"$1\"; s=$?; cat \"$1\";
                   test $s -eq 2 || { echo \"$a: exit $s, want 2\"; exit 1; }; done
                 \"$0\" report gates --synth --unit classic3 --rtl-param FOO=1 2>&1 | grep -q 'IN_REG, OUT_SKID, S_TABLE, HASH_SERIAL, LERP_SERIAL'"
          $<TARGET_FILE:noisepipe> ${CMAKE_CURRENT_BINARY_DIR}/synth_rtl_param.err)
# A variant synthesised (classic3 with the table s-curve and the serial hash, at the small
# configuration): Yosys per stage beside the as-built model, labelled as such.
np_synth_test(synth.classic3_variant "synth;nosan"
  "RTL `S_TABLE=1 HASH_SERIAL=1`.*cost model of the as-built circuit \\(not this variant\\).*\\| L \\| [0-9]+ \\| [0-9]+ \\|.*\\| \\*\\*total\\*\\* \\|.*a variant the cost model does not declare"
  --unit classic3 --config out_bits=8,s_frac=4,lerp_frac=6 --rtl-param S_TABLE=1,HASH_SERIAL=1)
# Perlin's "under 10K gates" (docs/classic3.md): the fully serial classic3 (LERP_SERIAL, one lerp
# unit, 1 result / 8 clocks) at the default configuration must synthesise to fewer than 10,000
# NAND2 equivalents (about 8.4K; 20-60 s of Yosys). The as-built pipeline (31K) fails this pattern.
np_synth_test(synth.classic3_under_10k "synth;nosan"
  "\\| \\*\\*total\\*\\* \\| \\*\\*[0-9]+\\*\\* \\| \\*\\*[1-9][0-9]?[0-9]?[0-9]?\\*\\* \\|"
  --unit classic3 --rtl-param LERP_SERIAL=1)
# report dims --synth (report_dims.c) on its cheapest row, classic2 (about 15 s of Yosys's CPU): the
# synthesis runs, every classic2 stage within 10 % of the cost model (--tolerance 10: exit 1
# otherwise), its per-stage table in DIR/dims-synth.md, its figures cached in DIR/synth-cache/;
# a second run with no yosys on PATH must take them from the cache (and say so), a third with
# the cache's key altered must try to synthesise again (and so fail without yosys: exit 2).
add_test(NAME synth.dims_classic2
  COMMAND sh -c "command -v yosys > /dev/null || { echo 'yosys not installed: skipped'; exit 77; }
                 d=\"$1\"; rm -rf \"$d\"
                 \"$0\" report dims --synth --unit classic2 --tolerance 10 -o \"$d\" || { echo \"first run: exit $?\"; exit 1; }
                 grep -q '^| 2 | classic2 | [0-9]* | [0-9]* | .* | synthesised in this run |' \"$d/dims-synth.md\" || { echo 'no synthesised classic2 row'; exit 1; }
                 grep -q '^## classic2 (' \"$d/dims-synth.md\" && grep -q '^| I2a | ' \"$d/dims-synth.md\" || { echo 'no per-stage table'; exit 1; }
                 grep -q '^key [0-9a-f]*$' \"$d/synth-cache/classic2.txt\" || { echo 'no cache'; exit 1; }
                 PATH=/nonexistent \"$0\" report dims --synth --unit classic2 --tolerance 10 -o \"$d\" > /dev/null || { echo \"cached run: exit $?\"; exit 1; }
                 grep -q '^| 2 | classic2 | .* | cached |' \"$d/dims-synth.md\" || { echo 'second run did not use the cache'; exit 1; }
                 sed -i 's/^key .*/key 0000000000000000/' \"$d/synth-cache/classic2.txt\"
                 PATH=/nonexistent \"$0\" report dims --synth --unit classic2 -o \"$d\" > /dev/null 2>&1; s=$?
                 test $s -eq 2 || { echo \"stale cache: exit $s, want 2 (a new synthesis)\"; exit 1; }
                 echo 'dims --synth: synthesised, within 10 %, cached, stale cache refused'"
          $<TARGET_FILE:noisepipe> ${CMAKE_CURRENT_BINARY_DIR}/dims-synth-test)
set_tests_properties(synth.dims_classic2 PROPERTIES SKIP_RETURN_CODE 77 TIMEOUT 900 LABELS "synth;nosan")
