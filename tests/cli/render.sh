#!/usr/bin/env bash
# bash render.sh FORESTWIND WORK
#
# `forestwind render` and `forestwind plot` on a real (short) run: pictures written, and bad input exiting
# with code 2, a message that lists what there is, and no picture.
forestwind=$1
work=$2
. "$(dirname "$0")/common.sh"
# expect CODE NEEDLE ARGS...: forestwind ARGS exits with CODE and its output (stdout and stderr) holds NEEDLE.
expect() {
  local code=$1 needle=$2
  shift 2
  "$forestwind" "$@" >"$work/out.txt" 2>&1
  local got=$?
  [ "$got" -eq "$code" ] || fail "forestwind $* exited with $got, expected $code: $(cat "$work/out.txt")"
  grep -qF -- "$needle" "$work/out.txt" || fail "forestwind $* did not say '$needle': $(cat "$work/out.txt")"
}

"$forestwind" run "$(dirname "$0")/palm_run.yaml" --end 1.0 -o "$work/out" --quiet || fail "the run failed"

# Pictures.
expect 0 "frame 4, t = 1 s" render "$work/out" -o "$work/last.png"
[ -s "$work/last.png" ] || fail "render wrote no picture"
for view in top side perspective; do
  expect 0 "wrote" render "$work/out" --view "$view" --arrows --frame 2 -o "$work/$view.png"
done
expect 0 "frame 1, t = 0.25 s" render "$work/out" --time 0.3 --field velocity_z --size 800x600 -o "$work/w.png"
expect 0 "wrote 5 pictures" render "$work/out" --all -o "$work/frames"
[ -s "$work/frames/frame_000004.png" ] || fail "render --all did not write the last frame"
if command -v ffmpeg >/dev/null; then
  expect 0 "palm_run.mp4" render "$work/out" --all --mp4 -o "$work/movie"
else
  expect 0 "ffmpeg is not installed" render "$work/out" --all --mp4 -o "$work/movie"
fi
expect 0 "1 probes, 1 trees, 5 samples" plot "$work/out" -o "$work/probes.png"
[ -s "$work/probes.png" ] || fail "plot wrote no picture"
# The same run with statistics: plot --profiles draws stats.nc, the domain's and a region's.
sed 's/^output:/output:\n  statistics: {interval: 0.5, regions: [{name: lee, min: [20, 0], max: [32, 16]}]}/' \
  "$(dirname "$0")/palm_run.yaml" >"$work/stats.yaml"
"$forestwind" run "$work/stats.yaml" --end 1.0 -o "$work/stats" --quiet || fail "the run with statistics failed"
expect 0 "2 records, 8 heights" plot "$work/stats" --profiles -o "$work/profiles.png"
[ -s "$work/profiles.png" ] || fail "plot --profiles wrote no picture"
expect 0 "region lee" plot "$work/stats" --profiles --region lee -o "$work/lee.png"
expect 2 "no such region (it has lee)" plot "$work/stats" --profiles --region gap -o "$work/bad.png"

# A GeoTIFF of the wind at 10 m above the ground (the palm run has no site: local coordinates, no CRS),
# and of another field, height and frame; its values are read back in tests/viz/GroundSlice_test.cpp.
expect 0 "speed at 10 m above the ground, frame 4, t = 1 s: 16 x 8 pixels of 2 m" export "$work/out" -o "$work/speed.tif"
[ "$(head -c 4 "$work/speed.tif" | od -An -c | tr -d ' ')" = 'II*\0' ] || fail "export wrote no TIFF"
expect 0 "no CRS (the scenario has no site)" export "$work/out" --field velocity_z --height 3 --time 0.5 -o "$work/w.tif"
expect 0 "velocity_z at 3 m above the ground, frame 2" export "$work/out" --field velocity_z --height 3 --frame 2 -o "$work/w.tif"
expect 2 "export: no field 'temperature'" export "$work/out" --field temperature -o "$work/bad.tif"
expect 2 "a height above the ground (m, >= 0) expected, got -2" export "$work/out" --height -2 -o "$work/bad.tif"
expect 2 "frames 0..4 (t = 0 .. 1 s)" export "$work/out" --frame 5 -o "$work/bad.tif"
[ ! -e "$work/bad.tif" ] || fail "a refused export wrote a file"

# Bad input: exit 2, what there is, nothing written.
expect 2 "frames 0..4 (t = 0 .. 1 s)" render "$work/out" --frame 5 -o "$work/bad.png"
expect 2 "choose one of velocity, velocity_x" render "$work/out" --field temperature -o "$work/bad.png"
expect 2 "choose one of top, side, perspective" render "$work/out" --view diagonal -o "$work/bad.png"
expect 2 "expected a run's output folder" render "$work/nowhere" -o "$work/bad.png"
expect 2 "a spectrum needs at least 256" plot "$work/out" --spectrum -o "$work/bad.png"
expect 2 "no stats.nc: the scenario has no output.statistics" plot "$work/out" --profiles -o "$work/bad.png"
expect 2 "--region goes with --profiles" plot "$work/out" --region gap -o "$work/bad.png"
# Storm damage: --field damage needs the folder's damage.csv; with one (written here by hand: the palm breaks
# at 0.6 s) the trees are drawn over the wind, standing in the frames before the failure, and plot adds the
# damage panel from it.
expect 2 "has no damage.csv (run with forest.damage.enabled)" render "$work/out" --field damage -o "$work/bad.png"
header="tree_id,species,x,y,height_m,dbh_m,state,time_s,break_height_m,top_wind_m_s,max_base_moment_Nm"
header="$header,critical_breakage_Nm,critical_overturning_Nm,max_utilisation"
printf '%s\n0,palm,12,8,8,0.3,broken,0.6,3,5.2,1e5,5e4,6e4,1.4\n' "$header" >"$work/out/damage.csv"
expect 0 "frame 4, t = 1 s, 0 standing, 1 broken, 0 overturned" render "$work/out" --field damage -o "$work/damage.png"
[ -s "$work/damage.png" ] || fail "render --field damage wrote no picture"
expect 0 "frame 2, t = 0.5 s, 1 standing, 0 broken" render "$work/out" --field damage --frame 2 -o "$work/d2.png"
expect 0 "wrote 5 pictures" render "$work/out" --field damage --all -o "$work/damage_frames"
expect 0 "5 samples, damage" plot "$work/out" -o "$work/damage_plot.png"
expect 2 "draws the top view only" render "$work/out" --field damage --view side -o "$work/bad.png"
printf '%s\n0,palm,12,8,8,0.3,standing,0.6,,,1e5,5e4,6e4,0.4\n' "$header" >"$work/out/damage.csv"
expect 2 "damage.csv:2: time_s: expected no value for a standing tree, got '0.6'" \
  render "$work/out" --field damage -o "$work/bad.png"
# A damaged frame file is bad input too: the frame asked for exits 2 naming the file; without --frame the
# last complete one is drawn, and a folder where no frame reads exits 2.
last=$(ls "$work/out/wind/"*.vti | sort | tail -1)
printf 'XXXX' | dd of="$last" bs=1 seek=200 conv=notrunc status=none
expect 2 "$(basename "$last")" render "$work/out" --frame 4 -o "$work/bad.png"
expect 0 "rendering frame 3" render "$work/out" -o "$work/fallback.png"
for frame in "$work/out/wind/"*.vti; do printf 'XXXX' | dd of="$frame" bs=1 seek=200 conv=notrunc status=none; done
expect 2 "no frame up to 4 reads" render "$work/out" -o "$work/bad.png"
[ ! -e "$work/bad.png" ] || fail "a refused command wrote a picture"
echo "render, plot and export: pictures and GeoTIFFs written, bad input refused"
rm -rf "$work"
