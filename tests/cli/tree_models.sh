#!/usr/bin/env bash
# bash tree_models.sh FORESTWIND MPIEXEC WORK COMPARE_RUNS
#
# scenarios/models.yaml, cut to 6 s: the modal, rigid-body and spring trees side by side. After the scenario's
# spin-up (time.spin_up: the wind steps before t = 0, nothing written; check and run report it) the three
# trees start bent by the sheltered wind (none starts at rest) and their tips move as their models say: the rigid bodies within
# 10% of the modal tree at the start (both bend as the FEM does), the springs far less. Resumed from a
# checkpoint in one process, and over 2 ranks that cut the forest between its trees (the checkpoint
# redistributed), it writes the same probes.csv, byte for byte, and the same frames as the run without a stop.
forestwind=$1
mpiexec=$2
work=$3
compare_runs=$4
. "$(dirname "$0")/common.sh"
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
scenarios=$(cd "$(dirname "$0")/../../scenarios" && pwd)

sed -e 's/end: 30.0/end: 6.0/' -e 's/cell_size: 1.0}/cell_size: 1.0, decomposition: [1, 2]}/' \
  -e 's/^  interval: 1.0/  interval: 1.0\n  checkpoint: {interval: 3.0, keep: 3}/' \
  "$scenarios/models.yaml" >"$work/models.yaml"
grep -q "checkpoint: {interval: 3.0" "$work/models.yaml" || fail "the scenario's output block has changed"

"$forestwind" check "$work/models.yaml" >"$work/check.log" 2>&1 || fail "check exited $?: $(cat "$work/check.log")"
grep -q "^spin-up: at most about [0-9]* steps before t = 0 (3 s of wind" "$work/check.log" ||
  fail "check does not plan the spin-up: $(cat "$work/check.log")"
"$forestwind" run "$work/models.yaml" -o "$work/whole" >"$work/whole.log" 2>&1 ||
  fail "run exited $?: $(cat "$work/whole.log")"
grep -q "^spin-up: [1-9][0-9]* steps, 3 s of wind before t = 0" "$work/whole.log" ||
  fail "run does not report the spin-up: $(cat "$work/whole.log")"
grep -q '"spin_up":{"seconds":3,"steps":[1-9]' "$work/whole/run.json" ||
  fail "run.json does not record the spin-up: $(cat "$work/whole/run.json")"
python3 - "$work/whole/probes.csv" <<'PY' || fail "the models' tips are not as their models say: $(head -3 "$work/whole/probes.csv")"
import csv, sys
rows = list(csv.DictReader(open(sys.argv[1])))
assert float(rows[0]["time_s"]) == 0.0, rows[0]["time_s"]  # the spin-up writes no row
modal, rigid, springs = (float(rows[0][f"tree{k}_tip_dx"]) for k in range(3))
# In equilibrium with the spun-up wind: bent downwind, not at rest.
assert modal > 0.5 and rigid > 0.5, (modal, rigid)
# Both bend as the FEM does (docs/tree-models.md: -2% and -6% of its static tip on the broadleaf).
assert abs(rigid - modal) < 0.1 * modal, (modal, rigid)
# A spring bends by its own element's load only: millimetres.
assert 0 < springs < 0.01 * modal, springs
PY

checkpoint=$(ls -d "$work/whole/checkpoints"/step_* | sort | head -1)
[ -n "$checkpoint" ] || fail "no checkpoint was written"
for ranks in 1 2; do
  cp -r "$work/whole" "$work/resumed_$ranks"
  step=$(basename "$checkpoint")
  "$mpiexec" --oversubscribe -np "$ranks" "$forestwind" run "$work/models.yaml" -o "$work/resumed_$ranks" \
    --resume "$work/resumed_$ranks/checkpoints/$step" >"$work/resumed_$ranks.log" 2>&1 ||
    fail "the resume on $ranks rank(s) exited $?: $(cat "$work/resumed_$ranks.log")"
  # The checkpoint holds the spun-up wind: a resumed run does not spin up again.
  ! grep -q "^spin-up:" "$work/resumed_$ranks.log" || fail "the resume on $ranks rank(s) spun up again"
  cmp "$work/whole/probes.csv" "$work/resumed_$ranks/probes.csv" ||
    fail "probes.csv resumed on $ranks rank(s) differs from the run without a stop"
  "$compare_runs" "$work/whole" "$work/resumed_$ranks" >"$work/compare_$ranks.log" 2>&1 ||
    fail "frames resumed on $ranks rank(s) differ: $(cat "$work/compare_$ranks.log")"
done
echo "tree models: all three bent at the start, resumed on 1 and 2 ranks to the same probes and frames"
