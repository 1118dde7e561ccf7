#!/usr/bin/env bash
# bash basis_cache.sh FORESTWIND WORK
#
# A basis cache that fails (docs/faults.md): an entry with corrupt bytes, a truncated entry, and a cache
# folder that cannot be written. The run goes on, computing the basis, with a warning that names the file
# and why; a corrupt entry is replaced, so that the next run is a hit again.
forestwind=$1
work=$2
. "$(dirname "$0")/common.sh"
scenario="$(dirname "$0")/palm_run.yaml"
export FORESTWIND_CACHE_DIR="$work/cache"

# run NAME: a short run whose stderr is kept in $work/NAME.err; fails unless it completes.
run() {
  "$forestwind" run "$scenario" -o "$work/$1" --end 0.25 >"$work/$1.out" 2>"$work/$1.err" ||
    fail "$1: the run failed: $(cat "$work/$1.err")"
  expect_status "$work/$1" completed
}
# expect_warning NAME TEXT...: NAME's stderr has a warning holding every TEXT.
expect_warning() {
  local name=$1
  shift
  local warning
  warning=$(grep '^warning: basis cache' "$work/$name.err")
  [ -n "$warning" ] || fail "$name: no warning about the cache: $(cat "$work/$name.err")"
  expect_texts "$name" "$warning" "$@"
  echo "$name: $warning"
}

run fresh
entry=$(find "$work/cache" -name '*.fwbasis')
[ -n "$entry" ] || fail "the first run cached no basis"
size=$(stat -c %s "$entry")

# Bytes changed in the middle: the checksum finds them.
printf 'garbage!' | dd of="$entry" bs=1 seek=$((size / 2)) conv=notrunc status=none
run corrupt
expect_warning corrupt "$entry" "the checksum does not match" "computed again"
grep -q '"cache":"corrupt_recomputed"' "$work/corrupt/run.json" || fail "run.json does not say corrupt_recomputed"
run replaced
grep -q '"cache":"hit"' "$work/replaced/run.json" || fail "the corrupt entry was not replaced"
! grep -q 'warning: basis cache' "$work/replaced.err" || fail "a warning after the entry was replaced"

# Cut short: shorter than its checksum, and cut at a third (the checksum, read from the wrong bytes, fails).
truncate -s 4 "$entry"
run truncated
expect_warning truncated "$entry" "the record is truncated" "computed again"
truncate -s $((size / 3)) "$entry"
run third
expect_warning third "$entry" "the checksum does not match" "computed again"

# A cache folder that cannot be made: a file stands in its place.
touch "$work/a_file"
FORESTWIND_CACHE_DIR="$work/a_file/cache" run unwritable
expect_warning unwritable "$work/a_file/cache" "Not a directory" "goes on without caching"

# A read-only cache folder, to an unprivileged user (root writes through permissions): check plans as run does.
rm -f "$entry"
chmod 555 "$work/cache"
chmod 777 "$work"
if setpriv --reuid=65534 --regid=65534 --clear-groups true 2>/dev/null; then
  setpriv --reuid=65534 --regid=65534 --clear-groups "$forestwind" check "$scenario" >/dev/null \
    2>"$work/readonly.err" || fail "check with a read-only cache failed: $(cat "$work/readonly.err")"
  expect_warning readonly "$work/cache" "Permission denied" "goes on without caching"
else
  echo "readonly: skipped (setpriv cannot change the user here)"
fi
echo ok
rm -rf "$work"
