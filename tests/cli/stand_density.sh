#!/usr/bin/env bash
# bash stand_density.sh FORESTWIND WORK
#
# `forestwind check` prints each stand's leaf and frontal area index on stdout, and warns on stderr, with exit
# code 0, of a stand whose leaf area index no forest has, naming the stand's line and the keys that set it.
forestwind=$1
work=$2
. "$(dirname "$0")/common.sh"

# A 4 m tree whose branches span a 2.4 m^2 crown hull (as in tests/host/app/SimulationPlan_test.cpp).
cat >"$work/tree.tree" <<'TREE'
0 -1 0 0 0 0.12
1 0 0 0 1.0 0.10
2 1 0 0 2.0 0.08
3 2 0 0 3.0 0.06
4 3 0 0 4.0 0.04
5 2 0.6 0 2.4 0.03
6 5 1.2 0 2.7 0.02
7 2 -0.6 0 2.4 0.03
8 7 -1.2 0 2.7 0.02
9 3 0 0.5 3.3 0.03
10 9 0 1.0 3.5 0.02
11 3 0 -0.5 3.3 0.03
12 11 0 -1.0 3.5 0.02
TREE
# scenario NAME SPACING [MORE]: a grid stand of crowns at leaf area index 10 over [2, 14]^2 (stand on line 12).
scenario() {
  cat >"$work/$1.yaml" <<YAML
scenario: $1
time: {end: 1.0}
domain: {size: [16, 16, 8], cell_size: 2.0}
wind: {speed: 5.0, direction: 270}
forest:
  species:
    - name: oak
      skeleton: {file: tree.tree}
      modes: {count: 4}
      canopy: {leaf_area_index: 10}
  stands:
    - {species: oak, region: {min: [2, 2], max: [14, 14]}, layout: grid, spacing: $2${3:+, $3}}
output: {directory: $work/out_$1}
YAML
}
# check NAME: runs check on NAME.yaml, which must exit 0 and write nothing.
check() {
  "$forestwind" check "$work/$1.yaml" >"$work/$1.out" 2>"$work/$1.err"
  local code=$?
  [ "$code" -eq 0 ] || fail "check $1 exited with $code: $(cat "$work/$1.out" "$work/$1.err")"
  [ ! -e "$work/out_$1" ] || fail "check $1 wrote its output folder"
}

# 9 trees of 24 m^2 of leaves on 144 m^2: a forest's leaf area index, no warning.
scenario forest 4.5
check forest
grep -qF "stand 0: 9 oak trees on 12 x 12 m, leaf area index 1.50 (the species' 10 a crown), frontal area index 1.56" \
  "$work/forest.out" || fail "check forest printed no stand line: $(cat "$work/forest.out")"
[ ! -s "$work/forest.err" ] || fail "check forest warned: $(cat "$work/forest.err")"

# 81 trees 1.5 m apart: leaf area index 13.5, above the 12 of forests.
scenario dense 1.5
check dense
grep -qF "stand 0: 81 oak trees on 12 x 12 m, leaf area index 13.50" "$work/dense.out" ||
  fail "check dense printed no stand line: $(cat "$work/dense.out")"
for needle in "warning: $work/dense.yaml:12: forest.stands[0]: the oak stand's leaf area index is 13.5" \
  "forest.stands[0].spacing 1.5 m" "forest.species[0].canopy.leaf_area_index 10" \
  "forest.stands[0].leaf_area_index"; do
  grep -qF -- "$needle" "$work/dense.err" || fail "check dense did not warn '$needle': $(cat "$work/dense.err")"
done
[ "$(wc -l <"$work/dense.err")" -eq 1 ] || fail "check dense warned more than once: $(cat "$work/dense.err")"

# The same stand given its own leaf area index: the figure given, no warning.
scenario given 1.5 "leaf_area_index: 4"
check given
grep -qF "stand 0: 81 oak trees on 12 x 12 m, leaf area index 4.00 (given;" "$work/given.out" ||
  fail "check given printed no stand line: $(cat "$work/given.out")"
[ ! -s "$work/given.err" ] || fail "check given warned: $(cat "$work/given.err")"

rm -rf "$work"
echo "stand_density: check prints stand lines and warns of a stand denser than forests"
