#!/usr/bin/env bash
# Runs every fuzz target of tests/fuzz for a set time (docs/fuzzing.md); `make fuzz` calls it.
#
#   bash tests/fuzz/run.sh BUILD_DIR SECONDS [TARGET...]   # default: every target
#
# Each target fuzzes a working corpus in BUILD_DIR/fuzz/corpus/TARGET, seeded from the tracked seeds
# (tests/fuzz/corpus/TARGET) and regressions (tests/fuzz/regressions/TARGET), with a time limit per input
# and limits on memory; crashes, hangs and huge allocations land in BUILD_DIR/fuzz/artifacts/TARGET. It prints
# a line per target (seconds, executions, outcome) and exits 1 when any target found something.
#
# With FUZZ_SEED=N set, a run is repeatable: each target starts from a fresh working corpus (the tracked seeds
# and regressions only) and libFuzzer draws its mutations from seed N, so a run of S seconds tries the same
# inputs first as any shorter run with that seed: what a run finds, a longer run with the same seed on
# another machine finds too.
set -uo pipefail

if [ $# -lt 2 ]; then
  echo "usage: bash tests/fuzz/run.sh BUILD_DIR SECONDS [TARGET...]" >&2
  exit 2
fi
build=$1
seconds=$2
shift 2
source_dir=$(cd "$(dirname "$0")/../.." && pwd)
targets=("$@")
if [ ${#targets[@]} -eq 0 ]; then
  targets=(scenario_fuzz expression_fuzz tree_file_fuzz qsm_fuzz heightmap_fuzz basis_cache_fuzz
           run_folder_fuzz probe_table_fuzz)
fi

# An input that takes longer than this many seconds is a hang. The planner computes species bases (an
# eigen solve of a whole tree): the leaf-count regression's generated 3 m broadleaf took 4.7 s of CPU under
# ASan, a mutant of it 7.2 s, so the scenario target gets 20 s, room for a busy machine.
timeout_of() {
  case "$1" in
    scenario_fuzz) echo 20 ;;
    *) echo 1 ;;
  esac
}
# No reader of a user file needs more than this for one input: a bigger allocation is a size field believed.
rss_limit_mb=2048
malloc_limit_mb=1024

failed=0
summary=()
for target in "${targets[@]}"; do
  corpus="$build/fuzz/corpus/$target"
  artifacts="$build/fuzz/artifacts/$target"
  if [ -n "${FUZZ_SEED-}" ]; then
    rm -rf "$corpus"
  fi
  mkdir -p "$corpus" "$artifacts"
  for seeds in "$source_dir/tests/fuzz/corpus/$target" "$source_dir/tests/fuzz/regressions/$target"; do
    [ -d "$seeds" ] && cp -n "$seeds"/* "$corpus"/ 2>/dev/null
  done
  # The basis cache's seed is written by the code itself, so that it follows the format of this build.
  if [ "$target" = basis_cache_fuzz ]; then
    "$build/basis_cache_seed" "$build/fuzz" && cp "$build/fuzz/entry.body" "$corpus/entry.body"
  fi
  before=$(ls "$artifacts")
  log="$build/fuzz/$target.log"
  start=$(date +%s)
  "$build/fuzz_$target" "$corpus" -max_total_time="$seconds" -timeout="$(timeout_of "$target")" \
    -rss_limit_mb=$rss_limit_mb -malloc_limit_mb=$malloc_limit_mb -print_final_stats=1 \
    -artifact_prefix="$artifacts/" ${FUZZ_SEED:+-seed="$FUZZ_SEED"} >"$log" 2>&1
  code=$?
  took=$(($(date +%s) - start))
  runs=$(grep -o 'stat::number_of_executed_units: [0-9]*' "$log" | grep -o '[0-9]*$' | tail -1)
  if [ $code -eq 0 ]; then
    outcome=ok
  else
    # Only what this run found: the folder keeps earlier runs' findings too.
    outcome="FOUND (exit $code): $(comm -13 <(echo "$before") <(ls "$artifacts") | tr '\n' ' ')"
    failed=1
  fi
  summary+=("$(printf '%-18s %5s s %10s runs  %s' "$target" "$took" "${runs:-?}" "$outcome")")
  echo "${summary[-1]}   (log: $log)"
done

echo
echo "fuzz: ${seconds} s per target${FUZZ_SEED:+, seed $FUZZ_SEED}; crashes, hangs and huge allocations: $build/fuzz/artifacts/<target>/"
printf '%s\n' "${summary[@]}"
if [ $failed -ne 0 ]; then
  echo "fuzz: a target found an input it does not refuse cleanly; replay it with $build/fuzz_<target> FILE," \
    "fix it, and add it to tests/fuzz/regressions/<target>/ (docs/fuzzing.md)" >&2
fi
exit $failed
