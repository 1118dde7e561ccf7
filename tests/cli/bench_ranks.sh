#!/usr/bin/env bash
# bash bench_ranks.sh FORESTWIND MPIEXEC WORK
#
# Under mpirun, `bench wind` and `bench coupled` split their grid over the ranks as a run would and rank 0
# alone prints one JSON object with every rank's step and halo figures: the step is the slowest rank's, each
# rank sends halo bytes, and every rank ran the whole grid alone for the baseline. `bench trees` has no ranks
# and exits 2. No timing is asserted: only that each figure is there and what it must be.
forestwind=$1
mpiexec=$2
work=$3
. "$(dirname "$0")/common.sh"
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
ranks() { "$mpiexec" --oversubscribe -np "$@"; }

check_json() {
  python3 - "$1" "$2" <<'PY'
import json, sys
r = json.load(open(sys.argv[1]))  # one object: only rank 0 printed
assert r["bench"] == sys.argv[2] and r["ranks"] == 2, r
(c,) = r["cases"]
assert c["grid"] == [32, 16, 8] and c["blocks"] == [2, 1], c
ranks = c["per_rank"]
assert len(ranks) == 2, ranks
assert c["ms_per_step"] == max(k["ms_per_step"] for k in ranks), c
assert all(k["halo_bytes_per_step"] > 0 and k["halo_messages_per_step"] > 0 for k in ranks), ranks
assert all(k["neighbour_sides"] == 1 for k in ranks), ranks
assert c["halo_bytes_per_step"] == sum(k["halo_bytes_per_step"] for k in ranks), c
assert all(k["alone_ms_per_step"] > 0 for k in ranks) and c["parallel_efficiency"] > 0, c
w = c["weak_scaling"]
assert w["ranks"] == 64 and w["halo_bytes_per_step"] > 0 and 0 < w["efficiency"] <= 1, w
PY
}

ranks 2 "$forestwind" bench wind --grid 32x16x8 --steps 2 --json >"$work/wind.json" 2>"$work/wind.err" ||
  fail "bench wind over 2 ranks failed: $(cat "$work/wind.err")"
check_json "$work/wind.json" wind || fail "bench wind's JSON over 2 ranks: $(cat "$work/wind.json")"

ranks 2 "$forestwind" bench coupled --grid 32x16x8 --trees 4 --steps 2 --json >"$work/coupled.json" \
  2>"$work/coupled.err" || fail "bench coupled over 2 ranks failed: $(cat "$work/coupled.err")"
check_json "$work/coupled.json" coupled || fail "bench coupled's JSON over 2 ranks: $(cat "$work/coupled.json")"

out=$(ranks 2 "$forestwind" bench wind --grid 32x16x8 --steps 2 2>&1) || fail "bench wind's table failed: $out"
[ "$(grep -c "^forestwind bench wind over 2 ranks" <<<"$out")" -eq 1 ] || fail "not one table from rank 0: $out"

out=$(ranks 2 "$forestwind" bench trees 2>&1)
code=$?
[ $code -eq 2 ] || fail "bench trees over 2 ranks exited $code, not 2: $out"
echo "bench over ranks: wind and coupled report every rank; trees refuses"
