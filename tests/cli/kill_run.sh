#!/usr/bin/env bash
# bash kill_run.sh FORESTWIND WORK CHECK_FRAMES [SEED]
#
# kill -9 at pseudo-random points of a run, 20 trials (docs/faults.md): every frame the .pvd files list reads
# back (tests/tools/check_frames: VTK's XML readers and OpenVDB, not a grep), and run.json is either absent
# (killed before the output began: then no collection exists either) or says "running", the run not
# finished; stats.nc reads back with every record up to the last listed frame. Odd trials wait for a frame's temporary file to exist and kill then, mid-frame; even trials
# kill after a pseudo-random delay. The points come from bash's RANDOM seeded with SEED (default below):
# a failure names the seed and the trial, and the same seed repeats the same points.
forestwind=$1
work=$2
check_frames=$3
seed=${4:-30}
. "$(dirname "$0")/common.sh"
scenario="$(dirname "$0")/faults_run.yaml"
trials=20
max_delay_ms=2500 # the delays span the start (planning, device, kernels from PoCL's cache) and ~2 s of steps
max_frame=8       # the mid-frame kills wait for a frame up to this one (a frame every 5 steps)
poll_s=0.002      # a frame's temporaries live a few ms on this grid: poll faster than that
statistics_interval=0.5 # faults_run.yaml's output.statistics.interval: stats.nc's records up to the frames

# True once every thread of process $1 has stopped (state T in /proc), or the process is gone.
all_stopped() {
  local stat
  for stat in /proc/"$1"/task/*/stat; do
    [ -r "$stat" ] || continue
    # The state follows the command name's closing parenthesis.
    [[ $(sed 's/.*) //' "$stat" 2>/dev/null | cut -c1) == [Tt] ]] || return 1
  done
  return 0
}

# One short run first: kernels into PoCL's cache and the palm's basis into the basis cache, so that every
# trial starts alike.
"$forestwind" run "$scenario" -o "$work/warm" --end 0.5 --quiet >"$work/warm.out" 2>&1 ||
  fail "the warm-up run failed: $(cat "$work/warm.out")"

RANDOM=$seed
mid_frame=0
start=$SECONDS
for trial in $(seq 1 $trials); do
  out="$work/trial$trial"
  where="trial $trial of seed $seed"
  "$forestwind" run "$scenario" -o "$out" --quiet >"$work/stdout" 2>"$work/stderr" &
  pid=$!
  if ((trial % 2)); then
    frame=$((RANDOM % max_frame + 1))
    file=$(printf 'wind_%06d.vti' "$frame")
    # Until frame `frame`'s wind file is listed and a temporary of a later file exists. A temporary lives a
    # few ms, so seeing it and killing would race it: stop the run first, wait until every thread of it has
    # stopped, look again, and kill only a run stopped with a temporary on disk; otherwise let it go on.
    while kill -0 "$pid" 2>/dev/null; do
      if grep -q "$file" "$out/wind.pvd" 2>/dev/null && [ -n "$(temporaries "$out")" ]; then
        kill -STOP "$pid" 2>/dev/null
        until all_stopped "$pid"; do sleep "$poll_s"; done
        [ -n "$(temporaries "$out")" ] && break
        kill -CONT "$pid" 2>/dev/null
      fi
      sleep "$poll_s"
    done
    point="mid-frame after frame $frame"
  else
    delay_ms=$((RANDOM % max_delay_ms))
    sleep "$(printf '%d.%03d' $((delay_ms / 1000)) $((delay_ms % 1000)))"
    point="after $delay_ms ms"
  fi
  kill -9 "$pid" 2>/dev/null || fail "$where: the run ended before the kill ($point): $(cat "$work/stderr")"
  { wait "$pid"; } 2>/dev/null # no "Killed" line from the shell
  code=$?
  [ "$code" -eq 137 ] || fail "$where: exit code $code after kill -9, expected 137 ($point)"
  left=$(temporaries "$out" | head -n 1)
  [ -n "$left" ] && mid_frame=$((mid_frame + 1))
  ((trial % 2)) && [ -z "$left" ] && fail "$where: the run was stopped with a temporary on disk, but none is left after kill -9"

  if [ -f "$out/run.json" ]; then
    expect_status "$out" running
  else
    for pvd in wind.pvd trees.pvd leaves.pvd; do
      [ ! -e "$out/$pvd" ] || fail "$where: $pvd exists but run.json does not ($point)"
    done
  fi
  read=$("$check_frames" "$out" "$statistics_interval" 2>&1) || fail "$where ($point): a listed frame does not read: $read"
  echo "$where: killed $point: $read${left:+, a temporary left: ${left#"$out/"}}"
  rm -rf "$out"
done
[ "$mid_frame" -ge 1 ] || fail "no kill of seed $seed landed mid-frame (no temporary was left behind)"
echo "ok: $trials kills, $mid_frame of them mid-write (a temporary left behind), in $((SECONDS - start)) s"
rm -rf "$work"
