#!/usr/bin/env bash
# bash check_answers.sh FORESTWIND WORK REGRESSIONS SCENARIOS
#
# Issue 44: `forestwind check` answers every scenario of the fuzz corpus' regressions (REGRESSIONS, the
# mutants of the example scenarios that once hung it, crashed it, exited 1 or took a minute) within a second,
# with exit code 0, or 2 and one line "FILE:LINE: KEY: ..."; and writes no output folder. The second is the
# issue's bound; it is measured in CPU seconds (bash's `time`, user + sys), which a machine busy with other
# tests does not stretch, and the largest here take 0.4 s (storm's, planned in full with a fresh basis cache),
# so 1 s leaves a margin of 2.5. A wall limit of 20 s stops a check that waits rather than computes.
forestwind=$(realpath "$1")
work=$2
regressions=$3
scenarios=$4
. "$(dirname "$0")/common.sh"

readonly cpu_limit=1.0   # s: the issue's bound
readonly cpu_kill=2      # s: ulimit -t, past which a runaway check is killed (whole seconds)
readonly wall_limit=20   # s
# What the scenario fuzz target places beside the mutants it reads (tests/fuzz/scenario_fuzz.cpp).
cp "$scenarios/hills.pgm" "$work/hills.pgm"
printf '0 -1 0 0 0 0.1\n1 0 0 0 1 0.08\n2 1 0 0 2 0.05\n' >"$work/tree.tree"
mkdir -p "$work/mutants"
count=0
for mutant in "$regressions"/*; do
  name=$(basename "$mutant")
  cp "$mutant" "$work/mutants/$name"
  cp "$work/hills.pgm" "$work/tree.tree" "$work/mutants/"
  (
    cd "$work" || exit 1
    TIMEFORMAT='%3U %3S'
    # The shell's own word on a killed check ("CPU time limit exceeded") lands before time's line.
    { time (
      ulimit -t "$cpu_kill"
      FORESTWIND_CACHE_DIR="$work/cache" timeout "$wall_limit" "$forestwind" check "mutants/$name" \
        >"$work/out.txt" 2>"$work/err.txt"
      echo $? >"$work/rc.txt"
    ); } 2>"$work/time.txt"
  )
  cpu=$(tail -n 1 "$work/time.txt" | awk '{ print $1 + $2 }')
  rc=$(cat "$work/rc.txt")
  case $rc in
    0) ;;
    2)
      first=$(head -n 1 "$work/err.txt")
      [[ $first =~ ^forestwind:\ mutants/$name:[0-9]+:\ [^:\ ]+:\ . ]] ||
        fail "$name: exit 2 without FILE:LINE: KEY: $first"
      ;;
    *) fail "$name: exit code $rc (0 or 2 expected) after $cpu s: $(tail -n 3 "$work/err.txt")" ;;
  esac
  awk -v cpu="$cpu" -v limit="$cpu_limit" 'BEGIN { exit !(cpu <= limit) }' ||
    fail "$name: answered (exit $rc) in $cpu CPU seconds, more than $cpu_limit"
  echo "$name: exit $rc in $cpu s"
  count=$((count + 1))
done
[ "$count" -gt 0 ] || fail "no regression in $regressions"
[ ! -e "$work/out" ] || fail "check wrote an output folder: $(ls -R "$work/out" | head)"
echo "$count mutants answered within $cpu_limit CPU s"
