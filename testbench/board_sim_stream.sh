#!/bin/sh
# SPDX-License-Identifier: MIT
# board_sim_stream.sh - `noisepipe stream --sim` against the Verilated board (board_sim, docs/board.md):
# the command's own transport, journal, --resume and verdict on the whole gateware.
#
#   board_sim_stream.sh NOISEPIPE BOARD_SIM WORKDIR CASE VECTORS [SIM ARGUMENT...]
#
# CASE:
#   clean   one run must verify every vector (exit 0) and the board's BYE_ACK count the same
#   fault   the first run with the SIM ARGUMENTS (board_sim's --fault ...): exit 0, or 1 with the
#           journal kept; then --resume (a plain board) until exit 0, at most 4 runs
#   kill    the first run (the SIM ARGUMENTS, e.g. --pace) is killed (SIGKILL) once its journal
#           holds 3 verified frames; the simulator must see end of input and exit; then --resume
#   fail    one run against a faulty board: must exit 1 with failing vectors
#   reconnect  one run with the SIM ARGUMENTS (e.g. --fault reset:N) and --reconnect 2 must verify
#           every vector (exit 0) in more than one session on the same board_sim process (one
#           summary line, the fault applied): the board answered a new HELLO after its fault
#   backpressure  as clean, and board_sim's summary must show rts_n high and host bytes held back
#           by it (> 0 clocks) with no overflow: the flow control was exercised and honoured
#   overflow  the first run with the SIM ARGUMENTS (--fault ignore-rts:N) must end in a detected
#           failure: exit 1 with a link fault, board_sim's overflow 1; then --resume (a plain
#           board) until exit 0
# Every case but fail ends with the check that nothing was lost or counted twice: the runs'
# "session: S vectors sent, V verified" add up to the vector count, the journal's R lines cover
# 0..N-1 once each (sorted, no gap, no overlap), and one more --resume finds nothing to send;
# and board_sim's summaries show no overflow (a byte the board lost: rts_n not honoured).
# Exit 0 pass, 1 fail, 77 skipped (no verilator: board_sim cannot have been built).
np=$1 sim=$2 work=$3 case=$4 vec=$5
shift 5
fail() { echo "FAIL ($case): $*"; exit 1; }
if [ "$case" = refuse ]; then
  # Without a simulator run: a program that cannot be run, or one that ends at once, is bad
  # usage (exit 2) with a message that says so; so are simulator arguments without --sim.
  # expect STATUS PATTERN COMMAND...: the command's exit status and a line of its stderr
  expect() {
    want=$1 pat=$2
    shift 2
    "$@" > "$work/refuse.out" 2> "$work/refuse.err"
    got=$?
    cat "$work/refuse.err"
    [ $got -eq "$want" ] || fail "exit $got, expected $want: $*"
    grep -q "$pat" "$work/refuse.err" || fail "no '$pat' on stderr: $*"
  }
  mkdir -p "$work" || exit 1
  expect 2 "cannot run '$work/no-such-sim': No such file or directory" \
    "$np" stream --sim "$work/no-such-sim" --unit classic3 --random 10
  expect 2 "cannot run '$vec': Permission denied" "$np" stream --sim "$vec" --unit classic3 --random 10
  expect 2 "the simulator false ended: exit status 1 before it answered HELLO" \
    "$np" stream --sim false --unit classic3 --random 10
  expect 2 "the simulator sh ended: exit status 3 before it answered HELLO" \
    "$np" stream --sim sh --unit classic3 --random 10 -- -c 'exit 3'
  expect 2 "arguments after '--' are the simulator's" "$np" stream --emulate --unit classic3 --random 10 -- x
  [ ! -e "$work/refuse.journal" ] || fail "a journal was left"
  expect 2 "before it answered HELLO" "$np" stream --sim true --unit classic3 --random 10 --journal "$work/refuse.journal"
  [ ! -e "$work/refuse.journal" ] || fail "the refused run left its new, empty journal"
  echo "board_sim stream refuse: 6 refusals, each exit 2 with its message"
  exit 0
fi
command -v verilator > /dev/null || { echo 'verilator not installed: skipped'; exit 77; }
[ -x "$sim" ] || { echo "no $sim (the fixture rtl.board.board_sim.build builds it)"; exit 1; }
mkdir -p "$work" || exit 1
j=$work/$case.journal
log=$work/$case.log
rm -f "$j" "$log"
n=$(sed -n 's/^# count \([0-9]*\)$/\1/p' "$vec")
[ -n "$n" ] || { echo "$vec: no '# count' header"; exit 1; }

runs=0 verified_sum=0 sums=
# run OUT [--resume] [-- SIM ARGS]: one stream run, output to OUT (and to the log), its exit status in rc
run() {
  out=$1
  shift
  "$np" stream --sim "$sim" --timeout 1 --quiet --journal "$j" "$vec" "$@" > "$out" 2>&1
  rc=$?
  runs=$((runs + 1))
  echo "--- run $runs: noisepipe stream --sim $sim --timeout 1 --quiet --journal $j $vec $* => exit $rc" >> "$log"
  cat "$out" >> "$log"
  # one "session:" line a session (more than one with --reconnect)
  v=0
  for x in $(sed -n 's/^session: [0-9]* vectors sent, \([0-9]*\) verified;.*/\1/p' "$out"); do
    v=$((v + x))
  done
  verified_sum=$((verified_sum + v))
  sums="$sums${sums:+ + }$v"
}

case $case in
clean)
  run "$work/$case.1" -- "$@"
  cat "$log"
  [ $rc -eq 0 ] || fail "exit $rc, expected 0"
  grep -q "^In $n tests, no errors found in " "$work/$case.1" || fail "no clean verdict"
  grep -q "; $n records in [0-9]* clocks" "$work/$case.1" || fail "the board's BYE_ACK does not count $n records"
  ;;
fault)
  run "$work/$case.1" -- "$@"
  [ $rc -le 1 ] || { cat "$log"; fail "exit $rc, expected 0 or 1"; }
  grep -q "faults applied" "$work/$case.1" || { cat "$log"; fail "board_sim printed no summary"; }
  grep -q " 0 faults applied" "$work/$case.1" && { cat "$log"; fail "the fault was not applied"; }
  while [ $rc -eq 1 ] && [ $runs -lt 4 ]; do
    run "$work/$case.$((runs + 1))" --resume
  done
  cat "$log"
  [ $rc -eq 0 ] || fail "exit $rc after $runs runs"
  ;;
kill)
  "$np" stream --sim "$sim" --timeout 1 --quiet --journal "$j" "$vec" -- "$@" > "$work/$case.1" 2>&1 &
  pid=$!
  t=0
  while [ "$(grep -c '^R ' "$j" 2> /dev/null)" -lt 3 ] 2> /dev/null || [ ! -s "$j" ]; do
    sleep 0.05
    t=$((t + 1))
    kill -0 $pid 2> /dev/null || break
    [ $t -lt 400 ] || { kill -9 $pid; fail "no 3 frames verified in 20 s"; }
  done
  kill -9 $pid 2> /dev/null || { cat "$work/$case.1"; fail "the stream ended before it could be killed"; }
  wait $pid
  runs=1
  # The simulator's stdin closed with the killed command: it must end by itself and say so.
  t=0
  until grep -q '^board_sim: end of input\|^board_sim: the host is gone' "$work/$case.1"; do
    sleep 0.05
    t=$((t + 1))
    [ $t -lt 100 ] || { cat "$work/$case.1"; fail "board_sim did not exit within 5 s of the kill"; }
  done
  killed=$(grep -c '^R ' "$j")
  echo "--- run 1: killed (SIGKILL) with $killed R lines in the journal" >> "$log"
  cat "$work/$case.1" >> "$log"
  run "$work/$case.2" --resume
  cat "$log"
  [ $rc -eq 0 ] || fail "--resume after the kill: exit $rc"
  before=$(sed -n 's/^resumed: \([0-9]*\) vectors verified before.*/\1/p' "$work/$case.2")
  [ -n "$before" ] && [ "$before" -gt 0 ] || fail "the resumed run found nothing verified before"
  verified_sum=$((verified_sum + before))
  sums="$before (killed run, from the journal) + $sums"
  ;;
reconnect)
  run "$work/$case.1" --reconnect 2 -- "$@"
  cat "$log"
  [ $rc -eq 0 ] || fail "exit $rc, expected 0 (--reconnect)"
  grep -q "^In $n tests, no errors found in " "$work/$case.1" || fail "no clean verdict"
  sessions=$(grep -c '^session: ' "$work/$case.1")
  [ "$sessions" -ge 2 ] || fail "$sessions session, expected a new one after the fault"
  grep -q ': a new session on the same link (--reconnect, 1 of 2)$' "$work/$case.1" || fail "no reconnect line"
  [ "$(grep -c '^board_sim: ' "$work/$case.1")" -eq 1 ] || fail "not one board_sim process (its summary lines)"
  grep -q ' 1 faults applied, 1 resets,' "$work/$case.1" || grep -q ' 1 faults applied,' "$work/$case.1" ||
    fail "the fault was not applied"
  # the board counts the new session from 0: its BYE_ACK holds the last session's vectors, not all
  last=$(sed -n 's/^session: [0-9]* vectors sent, \([0-9]*\) verified; the simulator.*/\1/p' "$work/$case.1")
  grep -q "; $last records in [0-9]* clocks" "$work/$case.1" || fail "the last session's BYE_ACK does not count its $last records"
  [ "$last" -lt "$n" ] || fail "the last session verified all $n: the fault hit nothing"
  echo "board_sim stream $case: $sessions sessions on one board_sim process ($(sed -n 's/^session: \([0-9]*\) vectors sent, \([0-9]*\) verified.*/\1 sent, \2 verified/p' "$work/$case.1" | tr '\n' ';' | sed 's/;$//; s/;/; /g')); the last BYE_ACK counts $last records"
  ;;
backpressure)
  run "$work/$case.1" -- "$@"
  cat "$log"
  [ $rc -eq 0 ] || fail "exit $rc, expected 0"
  grep -q "^In $n tests, no errors found in " "$work/$case.1" || fail "no clean verdict"
  grep -q "; $n records in [0-9]* clocks" "$work/$case.1" || fail "the board's BYE_ACK does not count $n records"
  high=$(sed -n 's/.*, rts_n high \([0-9]*\) clocks, .*/\1/p' "$work/$case.1")
  held=$(sed -n 's/.*, host bytes held back by rts_n \([0-9]*\) clocks (at most \([0-9]*\) waiting).*/\1 \2/p' "$work/$case.1")
  [ -n "$high" ] && [ -n "$held" ] || fail "board_sim printed no rts_n figures"
  [ "$high" -gt 0 ] || fail "rts_n was never high: the back-pressure was not exercised"
  [ "${held% *}" -gt 0 ] || fail "no host byte was held back by rts_n"
  echo "board_sim stream $case: rts_n high $high clocks; host bytes held back ${held% *} clocks, at most ${held#* } waiting"
  ;;
overflow)
  run "$work/$case.1" -- "$@"
  [ $rc -eq 1 ] || { cat "$log"; fail "exit $rc with the bridge ignoring rts_n, expected 1 (a detected failure)"; }
  grep -q ', overflow 1$' "$work/$case.1" || { cat "$log"; fail "board_sim saw no overflow: the buffer never filled"; }
  grep -q " 0 OUT bytes sent against rts_n" "$work/$case.1" && { cat "$log"; fail "no byte was sent against rts_n"; }
  grep -q "^In [0-9]* tests, no errors found in " "$work/$case.1" || { cat "$log"; fail "the overflowed run's verified vectors are not all good"; }
  first_fault=$(grep -m1 '^noisepipe stream: ' "$work/$case.1")
  [ -n "$first_fault" ] || { cat "$log"; fail "the first run named no link fault"; }
  while [ $rc -eq 1 ] && [ $runs -lt 4 ]; do
    run "$work/$case.$((runs + 1))" --resume
  done
  cat "$log"
  [ $rc -eq 0 ] || fail "exit $rc after $runs runs"
  echo "board_sim stream $case: the first run was stopped by a link fault ($first_fault) with overflow 1"
  ;;
fail)
  run "$work/$case.1" -- "$@"
  cat "$log"
  [ $rc -eq 1 ] || fail "exit $rc, expected 1 (failing vectors)"
  grep -q "^In [0-9]* tests, [1-9][0-9]* errors\? found in " "$work/$case.1" || fail "no failing verdict"
  echo "board_sim stream $case: the faulty board was caught: $(grep '^In ' "$work/$case.1")"
  exit 0
  ;;
*)
  fail "unknown case"
  ;;
esac

# Nothing lost, nothing counted twice; and the bridge honoured rts_n (the board never lost a byte).
# (in the overflow case the first run is meant to overflow: the runs after it must not)
if [ "$case" = overflow ]; then
  sed '1,/^--- run 2:/d' "$log" | grep -q ', overflow 1$' && fail "the board lost OUT bytes (overflow) after the first run"
else
  grep -q ', overflow 1$' "$log" && fail "the board lost OUT bytes (overflow): rts_n not honoured"
fi
grep -q "^In $n tests, no errors found in " "$work/$case.$runs" || fail "the last run's verdict is not clean"
[ $verified_sum -eq "$n" ] || fail "the runs verified $sums = $verified_sum vectors, not $n"
next=0 lines=0
# R FIRST COUNT ERRORS (hex) as decimal "FIRST COUNT ERRORS", sorted by FIRST
ranges=$(sed -n 's/^R \([0-9a-f]*\) \([0-9a-f]*\) \([0-9a-f]*\) \*.*/\1 \2 \3/p' "$j" |
  while read -r a b c; do echo "$((0x$a)) $((0x$b)) $((0x$c))"; done | sort -n -k1,1)
for r in $(echo "$ranges" | tr ' ' ':'); do
  first=${r%%:*}
  rest=${r#*:}
  count=${rest%%:*}
  errs=${rest#*:}
  [ $errs -eq 0 ] || fail "journal: $errs errors in the range at $first"
  [ $first -eq $next ] || fail "journal: a range starts at $first, expected $next (a gap or an overlap)"
  next=$((first + count))
  lines=$((lines + 1))
done
[ $next -eq "$n" ] || fail "journal: the ranges end at $next, not $n"
"$np" stream --sim "$sim" --timeout 1 --quiet --journal "$j" "$vec" --resume > "$work/$case.again" 2>&1 ||
  { cat "$work/$case.again"; fail "one more --resume: exit $?"; }
grep -q "^resumed: $n vectors verified before (0 errors); 0 to send" "$work/$case.again" ||
  { cat "$work/$case.again"; fail "one more --resume still has vectors to send"; }
faults=$(sed -n 's/.* \([0-9]*\) faults applied.*/\1/p' "$work/$case.1")
echo "board_sim stream $case: $n vectors verified exactly once in $runs runs ($sums), journal $lines ranges, ${faults:-?} faults applied"
