#!/usr/bin/env bash
# bash bench_models.sh FORESTWIND WORK
#
# `forestwind bench models` times the three tree models on one forest: its JSON lists modal, rigid_bodies and
# springs in that order, each with a step, a frame and the damage check's loads, and the modal case is its own
# baseline. No timing is asserted: only that every model ran on the forest it was given.
forestwind=$1
work=$2
. "$(dirname "$0")/common.sh"
mkdir -p "$work"
"$forestwind" bench models --trees 3 --json >"$work/bench.json" 2>"$work/bench.err" ||
  fail "bench models failed: $(cat "$work/bench.err")"
python3 - "$work/bench.json" <<'PY' || fail "bench models' JSON is not what was asked: $(cat "$work/bench.json")"
import json, sys
r = json.load(open(sys.argv[1]))
cases = r["cases"]
assert r["trees"] == 3 and r["nodes_per_tree"] > 1000, r
assert [c["model"] for c in cases] == ["modal", "rigid_bodies", "springs"], cases
assert all(c["step_ms"] > 0 and c["frame_ms"] > 0 and c["loads_ms"] > 0 for c in cases), cases
assert cases[0]["step_vs_modal"] == 1 and cases[0]["frame_vs_modal"] == 1, cases
assert r["fma_peak_gfma_s"] > 0, r
PY
echo "bench models: the three models on one forest"
