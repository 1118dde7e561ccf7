#!/usr/bin/env bash
# bash checkpoint.sh FORESTWIND WORK
#
# Long runs (docs/design.md "Long runs") from the command line, on the palm of palm_run.yaml for 20 s with
# checkpoints every 4 s:
# - SIGTERM in mid-run exits 143 after a checkpoint; --resume goes on, SIGUSR1 stops it again (138), and a
#   second --resume finishes: probes.csv and every frame are byte for byte those of the run that never
#   stopped, the .pvd files list each frame once, and run.json lists the three segments.
# - kill -9 while a checkpoint is being written leaves its folder cut short (.partial); --resume takes the
#   whole one before it and still ends on the same bytes. Three kills at random moments of a run that
#   checkpoints every step resume to the same bytes too.
# - A checkpoint with a flipped byte, one cut short, a scenario whose grid changed and one with another probe
#   (probes.csv cannot change its columns) each exit 2 with the reason (file, line and key for the scenario),
#   and leave the output folder as it was.
# - `check --resume` says from which checkpoint and time the run would go on.
forestwind=$1
work=$2
. "$(dirname "$0")/common.sh"
here=$(cd "$(dirname "$0")" && pwd)
cd "$work"

sed -e 's/^time: .*/time: {end: 20.0, dt: 0.05}/' \
  -e 's/^output:/output:\n  checkpoint: {interval: 4.0, keep: 3}\n  statistics: {interval: 3.0, averaging: 2.0, sample_every: 2}/' \
  "$here/palm_run.yaml" >palm.yaml
grep -q "checkpoint: {interval: 4.0" palm.yaml && grep -q "statistics: {interval: 3.0" palm.yaml ||
  fail "could not make the scenario"

# The same bytes as the reference run: probes.csv, stats.nc (whose records straddle the checkpoints), the
# collections and every frame (run.json and the
# checkpoints hold wall times); with a second argument, not the scenario's copy (its output settings differ).
same_as_reference() {
  local folder=$1 skip=${2:-} file
  for file in $(cd ref && find . -type f -not -path './checkpoints/*' -not -name run.json | sort); do
    [ -n "$skip" ] && [ "$file" = ./palm.yaml ] && continue
    cmp -s "ref/$file" "$folder/$file" || fail "$folder/$file differs from the uninterrupted run's"
  done
  [ "$(cd ref && find . -type f -not -path './checkpoints/*' | wc -l)" -eq \
    "$(cd "$folder" && find . -type f -not -path './checkpoints/*' | wc -l)" ] ||
    fail "$folder holds other files than the uninterrupted run: $(cd "$folder" && find . -type f | sort)"
}

"$forestwind" run palm.yaml -o ref --quiet >/dev/null 2>ref_err || fail "the reference run failed: $(cat ref_err)"
[ "$(ls ref/checkpoints | wc -l)" -eq 3 ] || fail "keep: 3 kept $(ls ref/checkpoints)"
[ -f ref/stats.nc ] || fail "the reference run wrote no stats.nc"
ls ref/checkpoints | grep -q "step_0000000400" || fail "no checkpoint at the end (step 400): $(ls ref/checkpoints)"

# Waits until the run in $1 (pid $2) has listed $3 wind frames; returns 1 when it ended first.
wait_frames() {
  for _ in $(seq 1 3000); do
    [ "$(grep -c 'DataSet ' "$1/wind.pvd" 2>/dev/null || echo 0)" -ge "$3" ] && return 0
    kill -0 "$2" 2>/dev/null || return 1
    sleep 0.05
  done
  return 1
}

# SIGTERM, resume, SIGUSR1, resume.
"$forestwind" run palm.yaml -o stopped --quiet >/dev/null 2>stop_err &
pid=$!
wait_frames stopped $pid 9 || fail "the run ended before SIGTERM: $(cat stop_err)"
kill -TERM $pid
wait $pid
code=$?
[ $code -eq 143 ] || fail "SIGTERM: exit $code, expected 143: $(cat stop_err)"
grep -q '"status":"interrupted"' stopped/run.json || fail "run.json does not say interrupted"
"$forestwind" check palm.yaml --resume stopped >check_out 2>&1 || fail "check --resume failed: $(cat check_out)"
grep -q "^resume: from .*stopped/checkpoints/step_[0-9]* at t = .* s (step [0-9]*, [0-9]* frames" check_out ||
  fail "check --resume does not say what would go on: $(cat check_out)"

"$forestwind" run palm.yaml -o stopped --resume stopped --quiet >/dev/null 2>stop_err &
pid=$!
before=$(grep -c 'DataSet ' stopped/wind.pvd)
wait_frames stopped $pid $((before + 10)) || fail "the resumed run ended before SIGUSR1: $(cat stop_err)"
kill -USR1 $pid
wait $pid
code=$?
[ $code -eq 138 ] || fail "SIGUSR1: exit $code, expected 138: $(cat stop_err)"
"$forestwind" run palm.yaml -o stopped --resume stopped --quiet >/dev/null 2>stop_err ||
  fail "the second resume failed: $(cat stop_err)"
same_as_reference stopped
grep -q '"status":"completed"' stopped/run.json || fail "run.json does not say completed"
[ "$(grep -o '"status":"stopped"' stopped/run.json | wc -l)" -eq 2 ] ||
  fail "run.json does not list the two stopped segments: $(cat stopped/run.json)"
grep -q '"steps":400,' stopped/run.json || fail "run.json does not count 400 steps: $(cat stopped/run.json)"

# kill -9 in the middle of writing a checkpoint: what it leaves is a .partial folder with a file cut short
# (the checkpoint is renamed whole only after every part is written).
cp -r ref killed
rm -rf killed/checkpoints/step_0000000400
last=$(ls killed/checkpoints | tail -n 1)
cp -r "killed/checkpoints/$last" killed/checkpoints/step_0000000400.partial
truncate -s 1000 killed/checkpoints/step_0000000400.partial/rank_0000.fwcheck
"$forestwind" run palm.yaml -o killed --resume killed --quiet >killed_out 2>killed_err ||
  fail "resuming past a checkpoint cut short failed: $(cat killed_err)"
same_as_reference killed
[ ! -e killed/checkpoints/step_0000000400.partial ] || fail "the checkpoint cut short was left behind"

# kill -9 at random moments of a run that checkpoints every step (a write is under way much of the time).
mkdir every_step
sed 's/checkpoint: {interval: 4.0, keep: 3}/checkpoint: {interval: 0.05, keep: 2}/' palm.yaml >every_step/palm.yaml
for trial in 1 2 3; do
  "$forestwind" run every_step/palm.yaml -o "kill$trial" --quiet >/dev/null 2>&1 &
  pid=$!
  wait_frames "kill$trial" $pid $((4 * trial)) || fail "trial $trial: the run ended before kill -9"
  kill -KILL $pid
  wait $pid 2>/dev/null
  "$forestwind" run every_step/palm.yaml -o "kill$trial" --resume "kill$trial" --quiet >/dev/null 2>kill_err ||
    fail "trial $trial: the resume after kill -9 failed: $(cat kill_err)"
  same_as_reference "kill$trial" skip_scenario
done

# Damaged checkpoints and a changed scenario: exit 2, the reason, and the folder untouched.
snapshot() { (cd ref && find . -type f -not -name '*.fwcheck' | sort | xargs md5sum); }
expect_refusal() {  # what, pattern, command...
  local what=$1 pattern=$2 before
  shift 2
  before=$(snapshot)
  "$@" >refused_out 2>refused_err
  code=$?
  [ $code -eq 2 ] || fail "$what: exit $code, expected 2: $(cat refused_err)"
  grep -q "$pattern" refused_err || fail "$what: the message does not say '$pattern': $(cat refused_err)"
  [ "$(snapshot)" = "$before" ] || fail "$what: the output folder changed"
}
checkpoint=ref/checkpoints/step_0000000320
cp "$checkpoint/rank_0000.fwcheck" good.fwcheck
size=$(stat -c %s good.fwcheck)
printf '\xff' | dd of="$checkpoint/rank_0000.fwcheck" bs=1 seek=$((size / 2)) conv=notrunc status=none
expect_refusal "a flipped byte" "rank_0000.fwcheck: the checksum does not match" \
  "$forestwind" run palm.yaml -o ref --resume "$checkpoint" --quiet
cp good.fwcheck "$checkpoint/rank_0000.fwcheck"
truncate -s $((size - 9)) "$checkpoint/rank_0000.fwcheck"
expect_refusal "a checkpoint cut short" "rank_0000.fwcheck: the file is truncated: $((size - 9)) of its $size bytes" \
  "$forestwind" run palm.yaml -o ref --resume "$checkpoint" --quiet
cp good.fwcheck "$checkpoint/rank_0000.fwcheck"
# Another probe: output may change on resume, but probes.csv cannot take other columns in the same folder.
sed 's/    - {name: mast, position: \[4, 8, 10\]}/&\n    - {name: gap, position: [20, 8, 10]}/' palm.yaml >more_probes.yaml
grep -q "name: gap" more_probes.yaml || fail "could not add a probe"
expect_refusal "another probe" "probes.csv: the columns differ from this run's" \
  "$forestwind" run more_probes.yaml -o ref --resume "$checkpoint" --quiet
sed 's/size: \[32, 16, 16\]/size: [32, 16, 24]/' palm.yaml >taller.yaml
line=$(grep -n "^domain:" taller.yaml | cut -d: -f1)
expect_refusal "a taller domain" "taller.yaml:$line: domain.size: the value the checkpoint was written with" \
  "$forestwind" run taller.yaml -o ref --resume ref --quiet
expect_refusal "check with a taller domain" "taller.yaml:$line: domain.size" \
  "$forestwind" check taller.yaml --resume ref
expect_refusal "a folder without checkpoints" "no checkpoint there" \
  "$forestwind" run palm.yaml -o ref --resume "$work/ref/wind" --quiet

echo "SIGTERM (143) and SIGUSR1 (138) resumed to the same bytes; kill -9 resumed 4 times; 6 refusals exit 2"
cd / && rm -rf "$work"
