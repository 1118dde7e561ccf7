#!/usr/bin/env bash
# bash disk_full.sh FORESTWIND WORK CHECK_FRAMES ENOSPC_SHIM
#
# A disk that fills at each writer of a run (docs/faults.md): the wind, trees and leaves VTK files, the VDB
# frames, probes.csv, stats.nc, the .pvd collections, run.json, the scenario's copy, view.py and the checkpoints. Writes
# fail with ENOSPC through an LD_PRELOAD shim (tests/tools/enospc_shim.cpp; a tmpfs would need mount
# rights a CI container may lack), on files whose path holds a pattern, after a given number of bytes. Each
# run exits 1 naming the file and "No space left on device"; every frame the collections list reads back
# (check_frames), the frames before the failing one are listed, no temporary or partial checkpoint is left,
# and run.json says "failed" with the message (but where run.json itself cannot be written).
forestwind=$1
work=$2
check_frames=$3
shim=$4
. "$(dirname "$0")/common.sh"
scenario="$(dirname "$0")/faults_run.yaml"
end=1.5 # frames 0..6 at 0.25 s, checkpoints at 0.5, 1.0 and 1.5 s

"$forestwind" run "$scenario" -o "$work/full" --end "$end" --quiet >"$work/full.out" 2>&1 ||
  fail "the run with room failed: $(cat "$work/full.out")"

# full_disk NAME PATTERN AFTER FILE FRAMES: a run whose writes to paths holding PATTERN fail after AFTER
# bytes must fail naming FILE, with at least FRAMES wind frames listed.
full_disk() {
  local name=$1 pattern=$2 after=$3 file=$4 frames=$5
  local out="$work/$name"
  ENOSPC_SHIM_PATTERN=$pattern ENOSPC_SHIM_AFTER=$after LD_PRELOAD=$shim \
    "$forestwind" run "$scenario" -o "$out" --end "$end" --quiet >"$work/$name.out" 2>"$work/$name.err"
  local code=$?
  local message
  message=$(cat "$work/$name.err")
  [ "$code" -eq 1 ] || fail "$name: exit code $code, expected 1: $message"
  expect_texts "$name" "$message" "$file: No space left on device"
  local read
  read=$("$check_frames" "$out" 2>&1) || fail "$name: a listed frame does not read: $read"
  local listed
  listed=$(grep -c 'DataSet ' "$out/wind.pvd" 2>/dev/null)
  [ "${listed:-0}" -ge "$frames" ] || fail "$name: wind.pvd lists ${listed:-0} frames, expected $frames or more"
  [ -z "$(temporaries "$out")" ] || fail "$name: temporaries left: $(temporaries "$out")"
  [ -z "$(find "$out" -name '*.partial')" ] || fail "$name: a partial checkpoint left: $(find "$out" -name '*.partial')"
  if [ "$file" != run.json ]; then
    expect_status "$out" failed
    grep -q 'No space left on device' "$out/run.json" || fail "$name: run.json does not give the message"
  fi
  echo "$name: exit 1, ${listed:-0} wind frames listed, $read; ${message#forestwind: }"
}

size() { stat -c %s "$1"; }
# Frame 3's files: failing at their first byte, and at their last bytes (the writer's last flush, at close).
tail_bytes=16 # under the last write's size: the write that fails is the one at the writer's close
for spec in wind/wind_000003.vti trees/trees_000003.vtp leaves/leaves_000003.vtp vdb/wind.0003.vdb; do
  name=$(basename "$spec" | tr . _)
  full_disk "${name}_start" "$spec" 0 "$(basename "$spec")" 3
  full_disk "${name}_end" "$spec" $(($(size "$work/full/$spec") - tail_bytes)) "$(basename "$spec")" 3
done
# probes.csv: rewritten whole while small; a later rewrite fails.
full_disk probes probes.csv $(($(size "$work/full/probes.csv") / 2)) probes.csv 1
# stats.nc: rewritten whole at each record (0.5 s) and checkpoint; its first write fails, and a later one
# part-way through.
full_disk stats_first stats.nc 0 stats.nc 1
full_disk stats_later stats.nc $(($(size "$work/full/stats.nc") * 2)) stats.nc 2
# The collections: a rewrite after some frames fails.
full_disk wind_pvd wind.pvd $(($(size "$work/full/wind.pvd") * 2)) wind.pvd 1
full_disk trees_pvd trees.pvd $(($(size "$work/full/trees.pvd") * 2)) trees.pvd 1
# The files written once at the start: nothing else is written after them.
full_disk run_json run.json 0 run.json 0
full_disk scenario_copy faults_run.yaml 0 faults_run.yaml 0
full_disk view_py view.py 0 view.py 0
# The first checkpoint (t = 0.5 s): the frames before it are kept.
full_disk checkpoint checkpoints/ 0 rank_0000.fwcheck 2
echo ok
