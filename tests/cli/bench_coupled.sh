#!/usr/bin/env bash
# bash bench_coupled.sh FORESTWIND WORK
#
# `forestwind bench coupled` plans its forest through the run's planner: on a small grid with a few trees it
# runs its four cases (converged, turbulent, in leaf, the Jacobi baseline), each with the forest it asked
# for, and the converged case's statistics sample, and its JSON says so. No timing is asserted: only that every case ran and counted what it was given.
forestwind=$1
work=$2
. "$(dirname "$0")/common.sh"
mkdir -p "$work"
"$forestwind" bench coupled --grid 24x16x12 --trees 6 --steps 2 --json >"$work/bench.json" 2>"$work/bench.err" ||
  fail "bench coupled failed: $(cat "$work/bench.err")"
python3 - "$work/bench.json" <<'PY' || fail "bench coupled's JSON is not what was asked: $(cat "$work/bench.json")"
import json, sys
r = json.load(open(sys.argv[1]))
cases = r["cases"]
assert r["trees"] == 6, r["trees"]
assert [c["grid"] for c in cases] == [[24, 16, 12]] * 4, cases
assert [c["pressure"] for c in cases] == ["cg 1e-3", "cg 1e-3", "cg 1e-3", "jacobi 4"], cases
assert [c["turbulent"] for c in cases] == [False, True, False, False], cases
# Only the case in leaf simulates leaves: 6 trees of the same species, so a multiple of 6.
leaves = [c["leaves"] for c in cases]
assert leaves[0] == leaves[1] == leaves[3] == 0 and leaves[2] > 0 and leaves[2] % 6 == 0, leaves
# The converged cases solve the pressure; the baseline sweeps exactly 4 times.
assert all(c["pressure_iterations"] >= 0 for c in cases[:3]) and cases[3]["pressure_iterations"] == 4, cases
assert r["nodes_per_tree"] > 1000 and r["species_seconds"] > 0, r
# The converged case alone times the statistics' sample, and the triad it is held against ran.
assert cases[0]["statistics_ms"] > 0 and cases[0]["statistics_gb_s"] > 0, cases[0]
assert all("statistics_ms" not in c for c in cases[1:]), cases
assert r["stream_gb_s"] > 0, r
PY
echo "bench coupled: 4 cases on the planner's forest"
