#!/usr/bin/env bash
# bash site.sh FORESTWIND MPIEXEC WORK COMPARE_RUNS SOURCE_DIR
#
# A GIS site end to end (docs/gis.md), on a corner of scenarios/site's elevation model and inventory:
# `check` counts the inventory's trees inside and outside the domain; a run records the site in run.json and
# the frames, names each tree's inventory id in damage.csv, and `export` writes its wind in EPSG:32632. The
# same run over 2 ranks, and resumed from its checkpoint, writes the same probes.csv and damage.csv byte for
# byte and the same frames value for value. A row the template cannot fit exits 2 at its line and column.
forestwind=$1
mpiexec=$2
work=$3
compare_runs=$4
source_dir=$5
. "$(dirname "$0")/common.sh"
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
cd "$work"
cp "$source_dir/scenarios/site/dem.tif" "$source_dir/scenarios/site/trees.csv" .
# 64 x 64 x 64 m of the stand's west end, 4 m cells, the floor at 421 m (the ground under it rises from
# 421.13 m); spruce that overturn at 13.6 m/s in a 16 m/s wind with a gust, so that damage.csv has failures.
cat >site.yaml <<'YAML'
scenario: site
seed: 3
time: {end: 1.5, dt: auto, cfl: 0.8}
domain: {origin: [512080, 5401160, 421], size: [64, 64, 64], cell_size: 4.0}
terrain: {raster: dem.tif}
boundaries: {west: inflow, east: outflow, south: slip, north: slip, ground: rough, top: slip, roughness_length: 0.1}
wind:
  speed: 16.0
  direction: 270.0
  reference_height: 10.0
  profile: {type: log, roughness_length: 0.1}
events:
  - gust: {start: 0.2, duration: 1.0, peak_speed: 10.0, center: [20, 32, 30], radius: 12.0, travel: with_wind}
forest:
  two_way_coupling: true
  damage: {enabled: true}
  species:
    - name: spruce
      skeleton: {generate: {preset: conifer, height: 20.0, seed: 4}}
      modes: {count: 6, damping_ratio: 0.05, wind_samples: 3}
      canopy: {leaf_area_index: 3.0, drag_coefficient: 0.4}
      strength: {preset: norway_spruce, soil: B}
    - name: beech
      skeleton: {generate: {preset: broadleaf, height: 18.0, seed: 3}}
      modes: {count: 6, damping_ratio: 0.05, wind_samples: 3}
      canopy: {leaf_area_index: 0.8, drag_coefficient: 0.3}
      strength: {preset: birch, soil: A, rooting: deep}
  inventory: {file: trees.csv}
output:
  directory: out
  interval: 0.5
  vtk: {wind: true, trees: true, fields: [velocity, speed]}
  checkpoint: {interval: 0.5}
  probes:
    - {name: stand, position: [32, 40, 40]}
YAML

out=$("$forestwind" check site.yaml 2>&1) || fail "check exited $?: $out"
inside=$(grep -o 'trees.csv: 494 trees, [0-9]* in the domain' <<<"$out" | grep -o '[0-9]* in' | grep -o '[0-9]*')
[ "$inside" = 88 ] || fail "check counts other than 88 of the inventory's trees in the domain: $out"
expect_texts "check" "$out" "406 outside it (not placed):" "T0010 (line 11) at x 512092.63, y 5401224.45" "and 401 more" "dbh within"

"$forestwind" run site.yaml -o one --quiet || fail "the run in one process exited $?"
expect_status one completed
grep -q '"site":{"crs":{"name":"WGS 84 / UTM zone 32N","epsg":32632' one/run.json ||
  fail "run.json records no site: $(cat one/run.json)"
grep -q '"origin":\[512080,5401160,421\]' one/run.json || fail "run.json records the origin otherwise"
head -1 one/damage.csv | grep -q ',inventory_id$' || fail "damage.csv has no inventory_id column"
grep -q ',overturned,.*,T[0-9]*$' one/damage.csv || fail "no tree of the inventory failed: $(head -5 one/damage.csv)"
out=$("$forestwind" export one --height 10 -o speed10.tif 2>&1) || fail "export exited $?: $out"
expect_texts "export" "$out" "in the site's CRS, EPSG:32632: the domain's corner at (512080, 5401160)"
# The frames' string field data (the CRS's WKT, the trees' inventory ids) pass render's checks.
out=$("$forestwind" render one --field damage -o damage.png 2>&1) || fail "render exited $?: $out"

out=$("$mpiexec" --oversubscribe -np 2 "$forestwind" run site.yaml -o ranks 2>&1) ||
  fail "the run over 2 ranks exited $?: $out"
cmp -s one/probes.csv ranks/probes.csv || fail "probes.csv over 2 ranks differs from one process's"
cmp -s one/damage.csv ranks/damage.csv || fail "damage.csv over 2 ranks differs from one process's"
out=$("$compare_runs" one ranks) || fail "the frames over 2 ranks differ from one process's: $out"

cp -r one resumed
first=$(ls resumed/checkpoints | head -n 1)
out=$("$forestwind" run site.yaml -o resumed --resume "resumed/checkpoints/$first" 2>&1) ||
  fail "the resume exited $?: $out"
cmp -s one/probes.csv resumed/probes.csv || fail "probes.csv resumed differs from the uninterrupted run's"
cmp -s one/damage.csv resumed/damage.csv || fail "damage.csv resumed differs from the uninterrupted run's"
out=$("$compare_runs" one resumed) || fail "the resumed frames differ: $out"

# A dbh in centimetres: refused at its line and column, nothing written.
sed '3s/,0\.\([0-9][0-9]\)\([0-9]\)$/,\1.\2/' trees.csv >cm.csv
sed 's/inventory: {file: trees.csv}/inventory: {file: cm.csv}/' site.yaml >cm.yaml
out=$("$forestwind" run cm.yaml -o cm 2>&1)
status=$?
[ "$status" -eq 2 ] || fail "a dbh in centimetres exited $status, not 2: $out"
expect_texts "the centimetre row" "$out" "cm.csv:3: dbh: a dbh its species' template fits"
[ ! -e cm ] || fail "a refused run wrote its folder"
echo "site: check counts the inventory, run.json and the frames carry the site, export writes EPSG:32632, 2 ranks and a resume write the same files"
