#!/bin/sh
# SPDX-License-Identifier: MIT
# board_bitstream_check.sh SCRIPT OUTDIR - fpga.board.bitstream (testbench/fpga.cmake): build the
# iCE40-HX8K breakout's bitstream with SCRIPT (rtl_model/verilog/board/hx8k_bitstream.sh), which
# fails unless nextpnr and icetime both meet 12 MHz; then check that every port of the .pcf sits on
# its package pin (nextpnr's "constrained 'port' to bel 'Xx/Yy/ioN'" against the ct256 pin table of
# icestorm's chipdb-8k.txt, a source independent of the .pcf) and that iceunpack reads the bitstream
# back as an 8k device. Exit 77 without the tools.
set -u
script=$1 out=$2
pcf=$(dirname "$script")/hx8k_breakout.pcf
rm -rf "$out"
"$script" "$out" 1; s=$?
test $s -eq 77 && exit 77
test $s -eq 0 || { echo "bitstream script: exit $s"; exit 1; }
db=""
for d in /usr/share/fpga-icestorm/chipdb /usr/local/share/icebox /usr/share/icebox; do
  test -f "$d/chipdb-8k.txt" && db="$d/chipdb-8k.txt" && break
done
test -n "$db" || { echo "chipdb-8k.txt not found (fpga-icestorm-chipdb)"; exit 1; }
n=0 bad=0
while read -r kw port pin rest; do
  test "$kw" = set_io || continue
  loc=$(awk -v p="$pin" '/^\.pins ct256/{on=1;next} /^\./{on=0} on && $1==p {print "X"$2"/Y"$3"/io"$4}' "$db")
  test -n "$loc" || { echo "pin $pin of $port: not a ct256 pin"; bad=$((bad + 1)); continue; }
  if grep -qF "constrained '$port' to bel '$loc'" "$out/nextpnr.log"; then
    n=$((n + 1))
  else
    echo "port $port: not placed on pin $pin ($loc)"; bad=$((bad + 1))
  fi
done < "$pcf"
echo "pins: $n ports on their .pcf pins, $bad wrong"
test $bad -eq 0 && test $n -eq 12 || exit 1
test $(wc -c < "$out/board.bin") -eq 135100 || { echo "bitstream size"; exit 1; }
iceunpack "$out/board.bin" "$out/unpacked.asc" 2> /dev/null && grep -q '^.device 8k' "$out/unpacked.asc" \
  || { echo "iceunpack cannot read board.bin"; exit 1; }
echo "iceunpack: board.bin reads back as an 8k device"
