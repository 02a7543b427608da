#!/bin/sh
# SPDX-License-Identifier: MIT
# tty_stream.sh - `noisepipe stream --tty DEVICE` (src/link/link_tty.c) without hardware: pty_board
# puts a board on the master side of a pseudo-terminal, the command opens the slave /dev/pts/N as
# it would the FT2232H's /dev/ttyUSB1 (docs/board.md).
#
#   tty_stream.sh NOISEPIPE PTY_BOARD WORKDIR CASE VECTORS [BOARD...]
#
# BOARD is pty_board's: --emulate (the C board emulator) or PROGRAM [ARG...] (board_sim).
# CASE:
#   emulated, sim  one run must verify every vector (exit 0) on "target: tty /dev/pts/N"; then
#                  --resume on the same tty finds every vector verified and 0 to send; then the
#                  journal is refused for another target (--emulate: exit 2). The board behind the
#                  pty must end when the pty closes, exit 0, and (sim) one board_sim process served
#                  both runs, with no overflow
#   reconnect      as sim, with --reconnect 2 and a fault in BOARD's arguments: the first run needs
#                  more than one session and the sessions' verified counts add up to the vectors
#   refuse         no board: a missing device, a file that is not a tty, a rate termios cannot set,
#                  --baud and --reconnect with --emulate: each exit 2 with its message, no journal
np=$1 ptyb=$2 work=$3 case=$4 vec=$5
shift 5
fail() { echo "FAIL ($case): $*"; exit 1; }
mkdir -p "$work" || exit 1
n=$(sed -n 's/^# count \([0-9]*\)$/\1/p' "$vec")
[ -n "$n" ] || { echo "$vec: no '# count' header"; exit 1; }
j=$work/$case.journal
rm -f "$j" "$work"/*.out "$work/pts"

if [ "$case" = refuse ]; then
  expect() {
    want=$1 pat=$2
    shift 2
    "$@" > "$work/refuse.out" 2> "$work/refuse.err"
    got=$?
    cat "$work/refuse.err"
    [ $got -eq "$want" ] || fail "exit $got, expected $want: $*"
    grep -q -- "$pat" "$work/refuse.err" || fail "no '$pat' on stderr: $*"
    [ ! -e "$j" ] || fail "a journal was left: $*"
  }
  expect 2 "^noisepipe stream: --tty $work/no-such-tty: cannot open: No such file or directory" \
    "$np" stream --tty "$work/no-such-tty" --journal "$j" "$vec"
  expect 2 "^noisepipe stream: --tty /dev/null: not a tty" "$np" stream --tty /dev/null --journal "$j" "$vec"
  expect 2 "^noisepipe stream: --tty $vec: not a tty" "$np" stream --tty "$vec" --journal "$j" "$vec"
  expect 2 "^noisepipe stream: --tty /dev/null: baud 1234 is not a rate termios can set (9600, .*3000000" \
    "$np" stream --tty /dev/null --baud 1234 --journal "$j" "$vec"
  expect 2 "^noisepipe stream: --baud goes with --ftdi or --tty" "$np" stream --emulate --baud 3000000 --journal "$j" "$vec"
  expect 2 "^noisepipe stream: --reconnect goes with --sim or --tty" "$np" stream --emulate --reconnect 1 --journal "$j" "$vec"
  echo "tty refusals: 6 refusals, each exit 2 with its message"
  exit 0
fi

if [ "$case" != emulated ]; then
  command -v verilator > /dev/null || { echo 'verilator not installed: skipped'; exit 77; }
  [ -x "$1" ] || { echo "no $1 (the fixture rtl.board.board_sim.build builds it)"; exit 1; }
fi
"$ptyb" "$work/pts" "$@" 2> "$work/board.err" &
bpid=$!
t=0
until [ -s "$work/pts" ]; do
  sleep 0.05
  t=$((t + 1))
  kill -0 $bpid 2> /dev/null || { cat "$work/board.err"; fail "pty_board ended before it made the pty"; }
  [ $t -lt 200 ] || { kill $bpid; fail "no pty within 10 s"; }
done
dev=$(cat "$work/pts")
stop_board() {
  kill -TERM $bpid 2> /dev/null
  wait $bpid
  brc=$?
  cat "$work/board.err"
}
extra=
[ "$case" = reconnect ] && extra="--reconnect 2"
# shellcheck disable=SC2086
"$np" stream --tty "$dev" --timeout 1 --quiet --journal "$j" $extra "$vec" > "$work/run1.out" 2>&1
rc=$?
cat "$work/run1.out"
[ $rc -eq 0 ] || { stop_board; fail "exit $rc, expected 0"; }
grep -q "^target: tty $dev$" "$work/run1.out" || { stop_board; fail "no 'target: tty $dev'"; }
grep -q "^In $n tests, no errors found in " "$work/run1.out" || { stop_board; fail "no clean verdict"; }
grep -q "^session: [0-9]* vectors sent, [0-9]* verified; tty $dev at 3000000 baud, RTS/CTS " "$work/run1.out" ||
  { stop_board; fail "no session line for the tty at 3000000 baud"; }
sessions=$(grep -c '^session: ' "$work/run1.out")
sum=0
for x in $(sed -n 's/^session: [0-9]* vectors sent, \([0-9]*\) verified;.*/\1/p' "$work/run1.out"); do
  sum=$((sum + x))
done
[ $sum -eq "$n" ] || { stop_board; fail "the sessions verified $sum vectors, not $n"; }
if [ "$case" = reconnect ]; then
  [ "$sessions" -ge 2 ] || { stop_board; fail "one session: the fault hit nothing"; }
else
  [ "$sessions" -eq 1 ] || { stop_board; fail "$sessions sessions, expected 1"; }
fi
"$np" stream --tty "$dev" --timeout 1 --quiet --journal "$j" --resume "$vec" > "$work/again.out" 2>&1
rc=$?
cat "$work/again.out"
[ $rc -eq 0 ] || { stop_board; fail "--resume on the same tty: exit $rc"; }
grep -q "^resumed: $n vectors verified before (0 errors); 0 to send" "$work/again.out" ||
  { stop_board; fail "--resume on the same tty still has vectors to send"; }
"$np" stream --emulate --quiet --journal "$j" --resume "$vec" > "$work/other.out" 2>&1
rc=$?
cat "$work/other.out"
[ $rc -eq 2 ] || { stop_board; fail "--resume of the tty's journal on the emulator: exit $rc, expected 2"; }
stop_board
[ $brc -eq 0 ] || fail "the board behind the pty: exit $brc"
if [ "$case" != emulated ]; then
  [ "$(grep -c '^board_sim: end of input' "$work/board.err")" -eq 1 ] || fail "not one board_sim process that saw the end of its input"
  grep -q ', overflow 0$' "$work/board.err" || fail "board_sim: overflow"
fi
echo "tty stream $case: $n vectors verified through $dev in $sessions session(s) ($(sed -n 's/^session: \([0-9]*\) vectors sent, \([0-9]*\) verified.*/\2/p' "$work/run1.out" | tr '\n' '+' | sed 's/+$//')), resumed with 0 to send, journal refused for another target; $(tail -n 1 "$work/board.err")"
