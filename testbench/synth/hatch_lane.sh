#!/bin/sh
# SPDX-License-Identifier: MIT
# hatch_lane.sh OUT CHPARAMS...: synthesise one seed lane of np_hatch.v
# (testbench/synth/hatch_lane.v) with report gates --synth's flow
# (src/report/report_synth.c: synth -flatten; dfflegalize; abc -g NAND with the
# bounded SAT sweep; opt_clean; stat -tech cmos) and print its NAND2
# equivalents (transistors / 4). CHPARAMS: "-set NAME V" pairs for hatch_lane.
# The lanes of docs/hatch.md ("Synthesis"), from the repository's top:
#   testbench/synth/hatch_lane.sh /tmp/l0 -set ST_U 1392005880 -set ST_V 496573849 -set W0_U 0 -set W0_V 1 \
#     -set RC 11585 -set RS 11585 -set FADE 0 -set N 16 -set I 3 -set F 17 -set KU_BITS 27 -set KV_BITS 31
set -e
out=$1
shift
here=$(dirname "$0")
rtl=$here/../../rtl_model/verilog
mkdir -p "$out"
printf '%s\n' 'strash; &get -n; &fraig -x -C 1000; &put; scorr; dc2; dretime; strash; &get -n; &dch -f; &nf; &put' > "$out/abc.script"
cat > "$out/lane.ys" <<YS
read_verilog $rtl/np_hatch_seed.v $here/hatch_lane.v
chparam $* hatch_lane
synth -top hatch_lane -flatten
dfflegalize -cell \$_DFF_P_ 01
abc -g NAND -script $out/abc.script
opt_clean
tee -q -o $out/stat.txt stat -tech cmos
YS
yosys -q -s "$out/lane.ys" > "$out/yosys.log" 2>&1
t=$(sed -n 's/.*Estimated number of transistors: *\([0-9]*\).*/\1/p' "$out/stat.txt")
echo "hatch lane ($*): $t transistors, $(awk "BEGIN { print $t / 4 }") NAND2 equivalents"
