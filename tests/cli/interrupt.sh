#!/usr/bin/env bash
# bash interrupt.sh FORESTWIND WORK
#
# Ctrl-C during `forestwind run`: the run stops after the current step with exit code 130, run.json says
# "interrupted", and every frame the .pvd files list is a whole VTK file (it ends with </VTKFile>);
# `forestwind render` draws the folder's last frame.
forestwind=$1
work=$2
. "$(dirname "$0")/common.sh"

"$forestwind" run "$(dirname "$0")/palm_run.yaml" -o "$work/out" --quiet >"$work/stdout" 2>"$work/stderr" &
pid=$!
# Wait for three frames, so the signal lands mid-run (at most 300 s on a slow machine).
for _ in $(seq 1 3000); do
  frames=$(grep -c 'DataSet ' "$work/out/wind.pvd" 2>/dev/null)
  [ "${frames:-0}" -ge 3 ] && break
  kill -0 "$pid" 2>/dev/null || break
  sleep 0.1
done
kill -INT "$pid" 2>/dev/null || fail "forestwind ended before the signal: $(cat "$work/stderr")"
wait "$pid"
code=$?
[ "$code" -eq 130 ] || fail "exit code $code, expected 130; stderr: $(cat "$work/stderr")"

grep -q '"status":"interrupted"' "$work/out/run.json" || fail "run.json does not say interrupted"
for pvd in wind.pvd trees.pvd; do
  tail -c 64 "$work/out/$pvd" | grep -q '</VTKFile>' || fail "$pvd is not complete"
  listed=$(grep -o 'file="[^"]*"' "$work/out/$pvd" | sed -e 's/^file="//' -e 's/"$//')
  count=$(printf '%s\n' "$listed" | grep -c .)
  [ "$count" -ge 3 ] || fail "$pvd lists $count frames, expected at least 3"
  for frame in $listed; do
    [ -f "$work/out/$frame" ] || fail "$pvd lists $frame, which is missing"
    tail -c 64 "$work/out/$frame" | grep -q '</VTKFile>' || fail "$frame is cut short"
  done
done
# No temporary file is left behind.
leftovers=$(find "$work/out" -name '*.tmp*' | head -n 1)
[ -z "$leftovers" ] || fail "a temporary file is left: $leftovers"
# The interrupted folder renders: its last listed frame is complete, so that is the one drawn.
frames=$(grep -c 'DataSet ' "$work/out/wind.pvd")
"$forestwind" render "$work/out" -o "$work/last.png" >"$work/render_out" 2>"$work/render_err" ||
  fail "render of the interrupted folder failed: $(cat "$work/render_err")"
grep -q "frame $((frames - 1))," "$work/render_out" || fail "render did not draw the last frame: $(cat "$work/render_out")"
[ -s "$work/last.png" ] || fail "render wrote no picture"
echo "interrupted with code 130; $(grep -c 'DataSet ' "$work/out/wind.pvd") complete wind frames"
rm -rf "$work"
