#!/usr/bin/env bash
# bash mpi_ranks.sh FORESTWIND MPIEXEC WORK COMPARE_RUNS forest|leaves
#
# Two parts, a CTest test each (about half a minute each on 2 cores):
# forest: under mpirun, `check` prints the blocks and each rank's wind grid; a split that cannot work exits 2
# naming file, line and key on every rank and leaves no rank behind. A forest in turbulent wind with a gust,
# run in one process and over 2 and 4 ranks, writes the same probes.csv and stats.nc (its profiles over the
# domain, the stand and a region), byte for byte, and the same frames,
# value for value (compare_runs reads the .pvti and .pvtp pieces as ParaView does).
# leaves: the same forest with leaves that shed and fly across the cuts, and VDB frames, over 2 x 2 ranks:
# the same probes.csv and stats.nc (leaf and tree counts included), frames (the leaves as sets) and VDB frames (gathered on rank 0)
# as one process; and resumed from its checkpoint over 2 x 2 ranks, 2 ranks and one process, the same again.
forestwind=$1
mpiexec=$2
work=$3
compare_runs=$4
part=${5-}
case $part in
  forest | leaves) ;;
  *)
    echo "mpi_ranks.sh: the last argument is forest or leaves, not '$part'" >&2
    exit 2
    ;;
esac
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

cd "$work"
# Whether two run folders' stats.nc hold the same values, every digit of each double (ncdump -p), and the same
# attributes but history, which names the scenario file a run read.
same_stats() {
  [ -f "$1/stats.nc" ] && [ -f "$2/stats.nc" ] &&
    cmp -s <(ncdump -p 9,17 "$1/stats.nc" | grep -v ':history = ') <(ncdump -p 9,17 "$2/stats.nc" | grep -v ':history = ')
}

# 25 trees across the cuts of 2 x 1 and 2 x 2 blocks, turbulent inflow across periodic sides (cut by 2 x 2:
# the frames' vorticity wraps there as in one process), a gust, two-way drag, probes inside
# and outside the stand; 64 x 32 x 16 cells of 2 m for 2 s.
cat >forest.yaml <<'YAML'
scenario: ranks
seed: 2
time: {end: 2.0, dt: auto, cfl: 0.8}
domain: {origin: [0, 0, 0], size: [128, 64, 32], cell_size: 2.0}
boundaries: {west: auto, east: auto, south: periodic, north: periodic, ground: rough, top: slip, roughness_length: 0.1}
wind:
  speed: 6.0
  direction: 260.0
  reference_height: 10.0
  profile: {type: power, alpha: 0.2}
  turbulence: {intensity: 0.2, length_scale: 20.0}
events:
  - gust: {start: 0.5, duration: 3.0, peak_speed: 8.0, center: [40, 32, 12], radius: 15.0, travel: with_wind}
forest:
  two_way_coupling: true
  species:
    - name: beech
      skeleton: {generate: {preset: broadleaf, height: 14.0, seed: 5}}
      modes: {count: 8, damping_ratio: 0.05, wind_samples: 3}
      canopy: {leaf_area_index: 3.0, drag_coefficient: 0.4}
  stands:
    - {species: beech, region: {min: [40, 10], max: [100, 54]}, layout: poisson, spacing: 9.0,
       scale: {min: 0.9, max: 1.1}, seed: 4}
output:
  directory: out
  interval: 1.0
  probes:
    - {name: upwind, position: [20, 32, 12]}
    - {name: stand, position: [64.3, 32.1, 10]}
    - {name: lee, position: [110, 30, 12]}
  statistics:
    interval: 0.5
    stands: true
    regions:
      - {name: lee, min: [100, 0], max: [128, 64]}
YAML
# Weak petioles (0.05 N median): thousands of leaves are shed at once and fly downwind across the cuts.
# Storm damage with consequences: with birch's anchorage at 100 N m/kg, 8 of the 25 trees overturn in the
# first step and 2 more in the gust, on both sides of the cuts, and their drag leaves the air.
sed 's/      canopy: {leaf_area_index: 3.0, drag_coefficient: 0.4}/&\n      leaves: {model: stochastic, area: 0.003, fraction: 0.01, petiole_strength: 0.05, strength_spread: 0.7}\n      strength: {preset: birch, anchorage: 100}/
     s/  two_way_coupling: true/&\n  damage: {enabled: true}/
     s/  interval: 1.0/&\n  vdb: {enabled: true, grids: [vel, speed, leaves]}\n  leaves: {attached: 5}\n  checkpoint: {interval: 1.0}/
     s/cell_size: 2.0}/cell_size: 2.0, decomposition: [2, 2]}/' forest.yaml >leaves.yaml
# The same over 2 x 2 blocks (4 ranks choose 4 x 1 themselves): cuts along y too, and corners.
sed 's/cell_size: 2.0}/cell_size: 2.0, decomposition: [2, 2]}/' forest.yaml >forest_2x2.yaml

if [ "$part" = forest ]; then
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

  "$forestwind" run forest.yaml -o one --quiet || fail "the run in one process exited $?"
  for n in 2 4 2x2; do
    if [ $n = 2x2 ]; then
      out=$(ranks 4 "$forestwind" run forest_2x2.yaml -o ranks$n 2>&1) || fail "the run over 2 x 2 ranks exited $?: $out"
      grep -q "4 ranks: 2 x 2 blocks" <<<"$out" || fail "the run did not take 2 x 2 blocks: $out"
    else
      out=$(ranks $n "$forestwind" run forest.yaml -o ranks$n 2>&1) || fail "the run over $n ranks exited $?: $out"
    fi
    [ "$(grep -c "steps to t" <<<"$out")" -eq 1 ] || fail "more than rank 0 reported over $n ranks: $out"
    cmp -s one/probes.csv ranks$n/probes.csv || fail "probes.csv over $n ranks differs from one process's"
    same_stats one ranks$n || fail "stats.nc over $n ranks differs from one process's"
    grep -q 'file="wind/wind_000002.pvti"' ranks$n/wind.pvd || fail "wind.pvd over $n ranks lists no .pvti"
    grep -q 'file="trees/trees_000002.pvtp"' ranks$n/trees.pvd || fail "trees.pvd over $n ranks lists no .pvtp"
    [ "$(ls ranks$n/wind/wind_000002_*.vti | wc -l)" -eq "${n/2x2/4}" ] || fail "not one wind piece per rank over $n ranks"
    grep -q '"status":"completed"' ranks$n/run.json || fail "run.json over $n ranks is not complete"
    out=$("$compare_runs" one ranks$n) || fail "the frames over $n ranks differ from one process's: $out"
  done
  echo "mpi ranks: check prints the blocks, bad splits exit 2, runs over 1, 2 and 4 ranks write the same files"
else
  "$forestwind" run leaves.yaml -o leafy_one --quiet || fail "the run with leaves in one process exited $?"
  out=$(ranks 4 "$forestwind" run leaves.yaml -o leafy_ranks 2>&1) || fail "the run with leaves over 2 x 2 ranks exited $?: $out"
  cmp -s leafy_one/probes.csv leafy_ranks/probes.csv || fail "probes.csv with leaves over 2 x 2 ranks differs from one process's"
  cmp -s leafy_one/damage.csv leafy_ranks/damage.csv || fail "damage.csv over 2 x 2 ranks differs from one process's"
  same_stats leafy_one leafy_ranks || fail "stats.nc over 2 x 2 ranks differs from one process's"
  grep -q ",overturned," leafy_one/damage.csv || fail "no tree failed: damage.csv has nothing to compare"
  # Resumed over the same 2 x 2 ranks from the checkpoint at 1 s (every rank its own part): the same bytes.
  # In one process and over 2 ranks (2 blocks) the 4 parts are redistributed: the same probes.csv
  # and frames as one process's, leaves in flight included.
  cp -r leafy_ranks leafy_resumed
  first=$(ls leafy_resumed/checkpoints | head -n 1)
  [ "$(ls "leafy_resumed/checkpoints/$first" | wc -l)" -eq 4 ] || fail "the checkpoint over 4 ranks is not 4 parts"
  out=$(ranks 4 "$forestwind" run leaves.yaml -o leafy_resumed --resume "leafy_resumed/checkpoints/$first" 2>&1) ||
    fail "the resume over 2 x 2 ranks exited $?: $out"
  cmp -s leafy_ranks/probes.csv leafy_resumed/probes.csv || fail "probes.csv resumed over 2 x 2 ranks differs"
  cmp -s leafy_ranks/damage.csv leafy_resumed/damage.csv || fail "damage.csv resumed over 2 x 2 ranks differs"
  same_stats leafy_ranks leafy_resumed || fail "stats.nc resumed over 2 x 2 ranks differs"
  out=$("$compare_runs" leafy_ranks leafy_resumed) || fail "the frames resumed over 2 x 2 ranks differ: $out"
  for n in 1 2; do
    cp -r leafy_ranks "leafy_on$n"
    sed 's/, decomposition: \[2, 2\]}/}/' leaves.yaml >"leaves_on$n.yaml"
    out=$(ranks $n "$forestwind" run "leaves_on$n.yaml" -o "leafy_on$n" --resume "leafy_on$n/checkpoints/$first" 2>&1) ||
      fail "the 2 x 2 checkpoint resumed over $n ranks exited $?: $out"
    grep -q "written by 4 ranks (2 x 2 blocks.*redistributed" <<<"$out" || fail "no redistribution over $n ranks: $out"
    cmp -s leafy_one/probes.csv "leafy_on$n/probes.csv" || fail "probes.csv of the 2 x 2 checkpoint resumed over $n ranks differs"
    cmp -s leafy_one/damage.csv "leafy_on$n/damage.csv" || fail "damage.csv of the 2 x 2 checkpoint resumed over $n ranks differs"
    same_stats leafy_one "leafy_on$n" || fail "stats.nc of the 2 x 2 checkpoint resumed over $n ranks differs"
    out=$("$compare_runs" leafy_one "leafy_on$n") || fail "the frames of the 2 x 2 checkpoint resumed over $n ranks differ: $out"
  done
  grep -q 'file="leaves/leaves_000002.pvtp"' leafy_ranks/leaves.pvd || fail "leaves.pvd over ranks lists no .pvtp"
  out=$("$compare_runs" leafy_one leafy_ranks) || fail "the frames with leaves over 2 x 2 ranks differ from one process's: $out"
  "$forestwind" render leafy_one -o leafy_one.png >/dev/null || fail "render of the leaves in one process exited $?"
  "$forestwind" render leafy_ranks -o leafy_ranks.png >/dev/null || fail "render of the leaves over ranks exited $?"
  cmp -s leafy_one.png leafy_ranks.png || fail "render draws the leaves over 2 x 2 ranks otherwise than one process's"
  # A VDB file's first 57 bytes hold OpenVDB's header with a random UUID of the file; the rest is the grids.
  for vdb in leafy_one/vdb/wind.000[0-2].vdb; do
    other=leafy_ranks/vdb/$(basename "$vdb")
    [ -f "$other" ] || fail "no $other"
    cmp -s <(tail -c +58 "$vdb") <(tail -c +58 "$other") || fail "$other over 2 x 2 ranks differs from one process's"
  done
  echo "mpi ranks: leaves and VDB over 2 x 2 ranks, and resumed over 4, 2 and 1 ranks, write the same files"
fi
