#!/usr/bin/env bash
# bash mpi_ranks.sh FORESTWIND MPIEXEC WORK
#
# Under mpirun: `check` prints the blocks and each rank's wind grid; a split that cannot work exits 2 naming
# file, line and key on every rank and leaves no rank behind; `run` over several ranks exits 2 before it
# touches a device or writes anything (the stages on blocks are not built yet, docs/parallel.md).
forestwind=$1
mpiexec=$2
work=$3
. "$(dirname "$0")/common.sh"
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
ranks() { "$mpiexec" --oversubscribe -np "$@"; }

cat >"$work/blocks.yaml" <<'YAML'
scenario: blocks
time: {end: 1.0}
domain:
  size: [64, 32, 16]
  cell_size: 2.0
wind: {speed: 5.0, direction: 270}
output: {directory: out}
YAML
sed 's/  cell_size: 2.0/  cell_size: 2.0\n  decomposition: [3, 1]/' "$work/blocks.yaml" >"$work/bad_blocks.yaml"

out=$(ranks 4 "$forestwind" check "$work/blocks.yaml" 2>&1) || fail "check over 4 ranks exited $?: $out"
# 32 x 16 cells: 4 x 1 exchanges 3 faces of 16 x 8 cells, 2 x 2 more; 32 = 4 blocks of 8 on multiples of 8.
grep -q "decomposition: 4 x 1 blocks of 8 x 16 x 8 cells over 4 ranks, halo 3 cells" <<<"$out" ||
  fail "check did not print the blocks: $out"
[ "$(grep -c "^  rank [0-3]: cells x" <<<"$out")" -eq 4 ] || fail "check did not print 4 ranks' blocks: $out"
[ "$(grep -c "is valid" <<<"$out")" -eq 1 ] || fail "more than rank 0 reported: $out"

out=$(ranks 2 "$forestwind" check "$work/bad_blocks.yaml" 2>&1)
code=$?
[ $code -eq 2 ] || fail "a decomposition of 3 blocks for 2 ranks exited $code, not 2: $out"
grep -q "bad_blocks.yaml:6: domain.decomposition: 3 x 1 blocks for 2 ranks" <<<"$out" ||
  fail "the error does not name file, line and key: $out"

cd "$work"
out=$(ranks 2 "$forestwind" run blocks.yaml 2>&1)
code=$?
[ $code -eq 2 ] || fail "run over 2 ranks exited $code, not 2: $out"
grep -q "rank [01] of 2: blocks.yaml: a run over 2 ranks (2 x 1 blocks of 16 x 16 x 8 cells)" <<<"$out" ||
  fail "run over 2 ranks did not say why: $out"
[ ! -e out ] || fail "run over 2 ranks created its output folder"
echo "mpi ranks: check prints the blocks, bad splits and runs over ranks exit 2"
