#!/bin/sh
# SPDX-License-Identifier: MIT
# hx8k_bitstream.sh OUTDIR [SEED] - the board's bitstream for the iCE40-HX8K breakout
# (docs/board.md): yosys synth_ice40 -> nextpnr-ice40 (hx8k, ct256, hx8k_breakout.pcf, 12 MHz)
# -> icepack -> icetime. Needs only the open flow (yosys, nextpnr-ice40, fpga-icestorm), not
# noisepipe. Writes OUTDIR/board.{json,asc,bin}, yosys.log, nextpnr.log, icetime.log and prints
# the figures. Exit 0 when the bitstream is made and 12 MHz is met, 1 otherwise, 77 without
# the tools.
set -u
out=${1:?usage: hx8k_bitstream.sh OUTDIR [SEED]}
seed=${2:-1}
here=$(cd "$(dirname "$0")" && pwd)
w=$(dirname "$here")
for t in yosys nextpnr-ice40 icepack icetime; do
  command -v $t > /dev/null || { echo "$t not installed (apt-get install yosys nextpnr-ice40 fpga-icestorm): skipped"; exit 77; }
done
mkdir -p "$out" || exit 1
src="$w/np_classic3.v $w/np_pipe_in_reg.v $w/np_pipe_skid.v"
for m in np_crc32 np_link_engine np_board_core np_uart_rx np_uart_tx np_board_top np_board_led_hold np_board_hx8k; do
  src="$src $here/$m.v"
done
t0=$(date +%s)
yosys -q -l "$out/yosys.log" -p "read_verilog -I$w $src; synth_ice40 -top np_board_hx8k -json $out/board.json" \
  || { echo "yosys failed: $out/yosys.log"; exit 1; }
nextpnr-ice40 --hx8k --package ct256 --pcf "$here/hx8k_breakout.pcf" --json "$out/board.json" \
  --asc "$out/board.asc" --freq 12 --seed "$seed" > "$out/nextpnr.log" 2>&1 \
  || { tail -20 "$out/nextpnr.log"; echo "nextpnr-ice40 failed: $out/nextpnr.log"; exit 1; }
icepack "$out/board.asc" "$out/board.bin" || { echo "icepack failed"; exit 1; }
icetime -d hx8k -P ct256 -p "$here/hx8k_breakout.pcf" -c 12 -t "$out/board.asc" > "$out/icetime.log" 2>&1
it=$?
t1=$(date +%s)
cells=$(grep 'ICESTORM_LC:' "$out/nextpnr.log" | tail -1 | sed 's/.*ICESTORM_LC: *//')
rams=$(grep 'ICESTORM_RAM:' "$out/nextpnr.log" | tail -1 | sed 's/.*ICESTORM_RAM: *//')
ios=$(grep 'SB_IO:' "$out/nextpnr.log" | tail -1 | sed 's/.*SB_IO: *//')
fmax=$(grep "Max frequency for clock" "$out/nextpnr.log" | tail -1 | sed 's/.*Max frequency for clock *//')
echo "board.bin: $(wc -c < "$out/board.bin") bytes, seed $seed, $((t1 - t0)) s"
echo "logic cells: $cells"
echo "block RAMs: $rams"
echo "I/O: $ios"
echo "nextpnr Fmax: $fmax"
grep -E 'Total path delay|Timing estimate' "$out/icetime.log" | sed 's/^/icetime: /'
grep -q "Max frequency for clock.*PASS" "$out/nextpnr.log" || { echo "12 MHz not met (nextpnr)"; exit 1; }
test $it -eq 0 || { echo "icetime: 12 MHz not met (or failed): $out/icetime.log"; exit 1; }
echo "12 MHz met"
