#!/usr/bin/env bash
# bash output_folder.sh FORESTWIND WORK
#
# The output folder's faults (docs/faults.md):
# - a folder that cannot be written exits 2 naming it, before the OpenCL device is touched: the runs have an
#   ICD loader that finds no platform (as tests/cli/no_platform.cmake), which would exit 3 had they touched
#   it. A read-only folder is refused to an unprivileged user (root writes through permissions), a path under
#   a file to anyone.
# - a grid larger than the device's memory exits 2 with both numbers, before the folder is created (PoCL's
#   device limited to 1 GiB by POCL_MEMORY_LIMIT; the largest allocation is tested in DeviceMemory_test).
# - a second run into a folder that a run is writing exits 2 naming the folder and the first run's process;
#   after the first is killed (kill -9) a run takes the folder over, and its lock file is gone when it ends.
forestwind=$1
work=$2
. "$(dirname "$0")/common.sh"
scenario="$(dirname "$0")/palm_run.yaml"
no_icd="$work/no_icd_vendors"
mkdir -p "$no_icd"
export FORESTWIND_CACHE_DIR="$work/cache" # the palm's basis, cached by the first run below
chmod 777 "$work"                          # the unprivileged user reads the scenario's copy and the cache here
nobody=(setpriv --reuid=65534 --regid=65534 --clear-groups)

# expect_refusal NAME CODE TEXT... -- COMMAND...: COMMAND exits CODE with every TEXT in its stderr.
expect_refusal() {
  local name=$1 code=$2
  shift 2
  local texts=()
  while [ "$1" != -- ]; do
    texts+=("$1")
    shift
  done
  shift
  "$@" >"$work/$name.out" 2>"$work/$name.err"
  local got=$?
  local message
  message=$(cat "$work/$name.err")
  [ "$got" -eq "$code" ] || fail "$name: exit code $got, expected $code: $message"
  expect_texts "$name" "$message" "${texts[@]}"
  echo "$name: exit $code: ${message#forestwind: }"
}
without_device=(env "OCL_ICD_VENDORS=$no_icd" "OCL_ICD_FILENAMES=")

# Read-only, before the device.
mkdir -p "$work/readonly"
chmod 555 "$work/readonly"
chmod 755 "$work/cache" 2>/dev/null
"$forestwind" check "$scenario" >/dev/null || fail "check failed" # fills the basis cache
if "${nobody[@]}" true 2>/dev/null; then
  expect_refusal readonly 2 "$work/readonly" "cannot be written" "Permission denied" -- \
    "${nobody[@]}" "${without_device[@]}" "$forestwind" run "$scenario" -o "$work/readonly" --quiet
  expect_refusal readonly_new 2 "$work/readonly/new" "$work/readonly cannot be written" -- \
    "${nobody[@]}" "${without_device[@]}" "$forestwind" run "$scenario" -o "$work/readonly/new" --quiet
  [ ! -e "$work/readonly/new" ] || fail "the refused run created its folder"
else
  echo "readonly: skipped (setpriv cannot change the user here)"
fi
touch "$work/a_file"
expect_refusal under_a_file 2 "$work/a_file/out" "$work/a_file is not a folder" -- \
  "${without_device[@]}" "$forestwind" run "$scenario" -o "$work/a_file/out" --quiet
expect_refusal a_file 2 "$work/a_file: the output folder is not a folder" -- \
  "${without_device[@]}" "$forestwind" run "$scenario" -o "$work/a_file" --quiet

# A grid the device cannot hold: exit 2 with the numbers, no folder.
expect_refusal device_memory 2 "large_grid.yaml: the run needs about" "of device memory" "has 1024 MiB" \
  "1073741824 bytes" -- env POCL_MEMORY_LIMIT=1 "$forestwind" run "$(dirname "$0")/large_grid.yaml" \
  -o "$work/large" --quiet --force
[ ! -e "$work/large" ] || fail "the run refused for its device memory created its folder"

# Two runs into one folder: the second is held off by the first's lock, also when it resumes there.
shared="$work/shared"
faults="$(dirname "$0")/faults_run.yaml" # it writes checkpoints, for the resume
"$forestwind" run "$faults" -o "$shared" --quiet >"$work/first.out" 2>&1 &
first=$!
# A failing check below exits the script: the first run (endless in simulated time) must not outlive it.
trap 'kill -9 "$first" 2>/dev/null' EXIT
for _ in $(seq 1 3000); do # until its first checkpoint (t = 0.5 s) is written (at most 300 s on a slow machine)
  [ -n "$(ls "$shared/checkpoints" 2>/dev/null)" ] && break
  kill -0 "$first" 2>/dev/null || fail "the first run ended: $(cat "$work/first.out")"
  sleep 0.1
done
expect_refusal second 2 "$shared: another run is writing into this output folder" "process $first on " \
  ".forestwind.lock" -- "$forestwind" run "$faults" -o "$shared" --end 0.5 --quiet
expect_refusal second_resume 2 "another run is writing" "process $first on " -- \
  "$forestwind" run "$faults" -o "$shared" --resume "$shared" --quiet
"$forestwind" check "$faults" --resume "$shared" >/dev/null ||
  fail "check does not run beside a run (it takes no lock)"
kill -9 "$first"
{ wait "$first"; } 2>/dev/null # no "Killed" line from the shell
# The kernel dropped the killed run's lock: a new run takes the folder over and lets go of it at its end.
[ -e "$shared/.forestwind.lock" ] || fail "the killed run left no lock file (expected one, unlocked)"
"$forestwind" run "$faults" -o "$shared" --end 0.5 --quiet 2>"$work/third.err" ||
  fail "a run after the killed one was refused: $(cat "$work/third.err")"
[ ! -e "$shared/.forestwind.lock" ] || fail "the lock file outlived its run"
"$forestwind" render "$shared" -o "$work/shared.png" --quiet || fail "render of the folder failed"
echo ok
rm -rf "$work"
