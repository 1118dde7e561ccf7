#!/usr/bin/env bash
# bash disk_space.sh FORESTWIND WORK SCENARIOS
#
# `forestwind run` does not start when the output's disk lacks the predicted output plus the margin: exit 2,
# the numbers and the keys that shrink the output, and nothing written (the folder is not created). The free
# space is faked with FORESTWIND_FAKE_FREE_BYTES (a test hook); --force runs anyway. A bad fake exits 2.
forestwind=$1
work=$2
scenarios=$3
. "$(dirname "$0")/common.sh"

out="$work/calm"
FORESTWIND_FAKE_FREE_BYTES=1000 "$forestwind" run "$scenarios/calm.yaml" -o "$out" --end 2 --quiet \
  >"$work/refused.out" 2>"$work/refused.err"
code=$?
[ "$code" -eq 2 ] || fail "a run without room exited $code, expected 2: $(cat "$work/refused.err")"
[ ! -e "$out" ] || fail "a refused run created its output folder"
message=$(cat "$work/refused.err")
for part in "calm.yaml: not enough disk space" "bytes) free" "5% + 64 MiB" "1000 bytes" output.interval \
  output.vtk.trees_every output.vdb.every output.vtk.fields output.leaves.attached time.end --force; do
  case "$message" in
    *"$part"*) ;;
    *) fail "the refusal does not say '$part': $message" ;;
  esac
done

# The prediction `check` prints is the one the refusal names.
predicted=$("$forestwind" check "$scenarios/calm.yaml" | sed -n 's/.*total .*(\([0-9]*\) bytes.*/\1/p')
[ -n "$predicted" ] || fail "check prints no total in bytes"

FORESTWIND_FAKE_FREE_BYTES=1000 "$forestwind" run "$scenarios/calm.yaml" -o "$out" --end 2 --quiet --force \
  || fail "--force did not run"
[ -f "$out/wind/wind_000001.vti" ] || fail "--force wrote no frames"

# Plenty of room: runs without --force.
FORESTWIND_FAKE_FREE_BYTES=1000000000000 "$forestwind" run "$scenarios/calm.yaml" -o "$work/roomy" --end 2 \
  --quiet || fail "a run with room was refused"

FORESTWIND_FAKE_FREE_BYTES=lots "$forestwind" run "$scenarios/calm.yaml" -o "$work/bad" --end 2 --quiet \
  2>"$work/bad.err"
code=$?
[ "$code" -eq 2 ] || fail "a bad FORESTWIND_FAKE_FREE_BYTES exited $code, expected 2"
grep -q "FORESTWIND_FAKE_FREE_BYTES" "$work/bad.err" || fail "the bad fake is not named: $(cat "$work/bad.err")"
echo ok
