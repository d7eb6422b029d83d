#!/usr/bin/env bash
# End-to-end checks of the vksplat CLI: the demo, info, render with metrics, and the message each
# bad input gets. usage: cli_test.sh VKSPLAT_BINARY WORK_DIR
set -u
vksplat=$1
work=$2
rm -rf "$work" && mkdir -p "$work"
passed=0
failed=0

# expect NAME EXPECTED_EXIT PATTERN -- COMMAND...: the command exits as expected and its output
# (stdout and stderr) contains PATTERN.
expect() {
  local name=$1 want_exit=$2 pattern=$3
  shift 4
  local output status
  output=$("$@" 2>&1)
  status=$?
  if { [ "$want_exit" = any-failure ] && [ $status -ne 0 ] || [ "$status" = "$want_exit" ]; } &&
     grep -qF -- "$pattern" <<<"$output"; then
    passed=$((passed + 1))
  else
    failed=$((failed + 1))
    echo "FAILED: $name (exit $status, wanted $want_exit and '$pattern')"
    echo "$output" | sed 's/^/    /' | tail -n 15
  fi
}

expect demo 0 "wrote 2 views and demo.ply" -- "$vksplat" demo --out "$work/demo" --views 2 --width 96 --height 64
expect demo-refuses-overwrite any-failure "exists" -- "$vksplat" demo --out "$work/demo" --views 2 --width 96 --height 64
expect info 0 "Gaussians: 38605" -- "$vksplat" info "$work/demo/demo.ply"
expect devices 0 "subgroup" -- "$vksplat" devices
expect help-has-example 0 "Example:" -- "$vksplat" render --help
expect version 0 "vksplat 0.1.0" -- "$vksplat" --version

# One INRIA camera above the demo scene looking down.
cat >"$work/cameras.json" <<'JSON'
[{"id": 0, "img_name": "top", "width": 80, "height": 60, "position": [0, 0, 5],
  "rotation": [[1, 0, 0], [0, -1, 0], [0, 0, -1]], "fx": 70, "fy": 70}]
JSON
expect render 0 "wrote 1 views" -- "$vksplat" render "$work/demo/demo.ply" --cameras "$work/cameras.json" \
  --out "$work/render" --depth --alpha --background 1,1,1
[ -f "$work/render/top.png" ] && [ -f "$work/render/top.alpha.png" ] && [ -f "$work/render/top.depth.npy" ] &&
  passed=$((passed + 1)) || { failed=$((failed + 1)); echo "FAILED: render outputs missing"; }
mkdir -p "$work/photos" && cp "$work/render/top.png" "$work/photos/top.png"
expect render-metrics 0 "mean PSNR" -- "$vksplat" render "$work/demo/demo.ply" --cameras "$work/cameras.json" \
  --out "$work/scored" --images "$work/photos" --background 1,1,1

# A memory budget: the frame goes in depth-ordered chunks and the files are the same; a budget too
# small for even one chunk is a clear error.
expect render-budget 0 "depth-ordered chunks" -- "$vksplat" render "$work/demo/demo.ply" --cameras "$work/cameras.json" \
  --out "$work/chunked" --depth --alpha --background 1,1,1 --memory-budget 2
for file in top.png top.alpha.png top.depth.npy; do
  cmp -s "$work/render/$file" "$work/chunked/$file" && passed=$((passed + 1)) ||
    { failed=$((failed + 1)); echo "FAILED: chunked $file differs from the whole render"; }
done
expect render-budget-too-small any-failure "is too small for a 80x60 frame" -- "$vksplat" render "$work/demo/demo.ply" \
  --cameras "$work/cameras.json" --out "$work/tiny" --memory-budget 0.01

# Prune: by ratio (saving the view totals), the refusal to overwrite, and a PSNR budget re-scored
# from the saved totals against the photo.
expect prune 0 "Gaussians: 38605 -> 19302" -- "$vksplat" prune "$work/demo/demo.ply" --cameras "$work/cameras.json" \
  --method blend --ratio 0.5 --background 1,1,1 --save-totals "$work/totals.npy" -o "$work/half.ply"
expect prune-in-chunks 0 "depth-ordered chunks" -- "$vksplat" prune "$work/demo/demo.ply" --cameras "$work/cameras.json" \
  --method blend --ratio 0.5 --background 1,1,1 --memory-budget 2 -o "$work/half_chunked.ply"
cmp -s "$work/half.ply" "$work/half_chunked.ply" && passed=$((passed + 1)) ||
  { failed=$((failed + 1)); echo "FAILED: pruning in chunks kept other Gaussians"; }
expect prune-refuses-overwrite 2 "half.ply: already exists" -- "$vksplat" prune "$work/demo/demo.ply" \
  --cameras "$work/cameras.json" --method blend --ratio 0.5 -o "$work/half.ply"
expect prune-budget 0 "against the photos" -- "$vksplat" prune "$work/demo/demo.ply" --cameras "$work/cameras.json" \
  --method volume-blend --load-scores "$work/totals.npy" --max-psnr-drop 1 --images "$work/photos" \
  --background 1,1,1 -o "$work/budget.ply"
expect prune-one-selector any-failure "--ratio excludes --keep" -- "$vksplat" prune "$work/demo/demo.ply" \
  --cameras "$work/cameras.json" --method blend --ratio 0.2 --keep 3 -o "$work/x.ply"
# fisher (PUP 3D-GS): its view totals keep the scores as a sixth column, which a later run selects
# from without rendering; totals saved for another method hold none and are refused for it.
expect prune-fisher 0 "Gaussians: 38605 -> 19302" -- "$vksplat" prune "$work/demo/demo.ply" --cameras "$work/cameras.json" \
  --method fisher --ratio 0.5 --background 1,1,1 --save-totals "$work/fisher_totals.npy" -o "$work/fisher_half.ply"
expect prune-fisher-from-totals 0 "Gaussians: 38605 -> 3860" -- "$vksplat" prune "$work/demo/demo.ply" \
  --cameras "$work/cameras.json" --method fisher --load-scores "$work/fisher_totals.npy" --ratio 0.9 \
  --background 1,1,1 -o "$work/fisher_tenth.ply"
expect prune-fisher-needs-its-totals 2 "--method fisher: the view totals hold no Fisher scores" -- "$vksplat" prune \
  "$work/demo/demo.ply" --cameras "$work/cameras.json" --method fisher --load-scores "$work/totals.npy" --ratio 0.5 \
  -o "$work/fisher_none.ply"

# Bench: per-stage times and the JSON, a tiled scene, and the refusal to overwrite its output.
expect bench 0 "mean of per-view medians" -- "$vksplat" bench "$work/demo/demo.ply" --cameras "$work/cameras.json" \
  --reps 2 --warmup 1 --json "$work/bench.json"
grep -q '"tile_entries"' "$work/bench.json" && passed=$((passed + 1)) || { failed=$((failed + 1)); echo "FAILED: bench.json"; }
expect bench-tiled 0 "154420 Gaussians" -- "$vksplat" bench "$work/demo/demo.ply" --tiled 2x2 --reps 1 --warmup 0 \
  --width 64 --height 36 --half-sh
expect bench-refuses-overwrite 2 "bench.json: already exists" -- "$vksplat" bench "$work/demo/demo.ply" \
  --cameras "$work/cameras.json" --reps 1 --warmup 0 --json "$work/bench.json"
expect bench-bad-grid 2 "expected NxM" -- "$vksplat" bench "$work/demo/demo.ply" --tiled 5by5

# Convert: the demo scene through every writable format and back, the refusal to overwrite, --force.
expect convert-to-splat 0 "wrote 38605 Gaussians (SH degree 0)" -- "$vksplat" convert "$work/demo/demo.ply" "$work/demo.splat"
expect convert-to-spz 0 "(ply) to $work/demo.spz (spz)" -- "$vksplat" convert "$work/demo/demo.ply" "$work/demo.spz"
expect convert-sh-bits 0 "rounded to 6 and 6 bits" -- "$vksplat" convert "$work/demo/demo.ply" "$work/demo66.spz" \
  --sh-bits 6,6
[ "$(stat -c %s "$work/demo66.spz")" -lt "$(stat -c %s "$work/demo.spz")" ] && passed=$((passed + 1)) ||
  { failed=$((failed + 1)); echo "FAILED: convert --sh-bits 6,6 wrote no smaller SPZ"; }
expect convert-sh-bits-range 2 "--sh-bits 0,6: SH bits must be whole numbers from 1 to 8" -- "$vksplat" convert \
  "$work/demo/demo.ply" "$work/demo06.spz" --sh-bits 0,6
expect convert-named-format 0 "(ply)" -- "$vksplat" convert "$work/demo.spz" "$work/from_spz.bin" --format ply
expect convert-back 0 "wrote 38605 Gaussians (SH degree 3)" -- "$vksplat" convert "$work/from_spz.bin" \
  "$work/from_spz.ply" --input-format ply
expect convert-splat-back 0 "from $work/demo.splat (splat)" -- "$vksplat" convert "$work/demo.splat" "$work/from_splat.ply"
expect info-reads-spz 0 "Gaussians: 38605" -- "$vksplat" info "$work/demo.spz"
expect convert-refuses-overwrite 2 "demo.spz: already exists" -- "$vksplat" convert "$work/demo/demo.ply" "$work/demo.spz"
expect convert-force 0 "wrote 38605" -- "$vksplat" convert "$work/from_splat.ply" "$work/demo.spz" --force
# The output's name says its format: an existing .ply that holds SPZ is replaced by a plain PLY.
cp "$work/demo.spz" "$work/impostor.ply"
expect convert-output-format-by-name 0 "to $work/impostor.ply (ply)" -- "$vksplat" convert "$work/demo/demo.ply" \
  "$work/impostor.ply" --force
expect convert-output-is-a-plain-ply 0 "Gaussians: 38605" -- "$vksplat" info "$work/impostor.ply"
expect convert-read-only-format 2 "cannot write format 'gsplat-pt'" -- "$vksplat" convert "$work/demo.spz" "$work/x.pt"
expect convert-unknown-extension 2 "cannot write a scene as '.obj'" -- "$vksplat" convert "$work/demo.spz" "$work/x.obj"
# Sweep: a quick one against the photo, then the refusal to overwrite its results.
expect sweep 0 "wrote $work/sweep/report.html" -- "$vksplat" sweep "$work/demo/demo.ply" \
  --cameras "$work/cameras.json" --images "$work/photos" --background 1,1,1 --out "$work/sweep" \
  --methods blend,random --fractions 0,0.5 --timing-reps 0 --no-scoring-cost
[ "$(wc -l <"$work/sweep/sweep.csv")" -eq 5 ] && [ -f "$work/sweep/charts/psnr_vs_fraction.svg" ] &&
  passed=$((passed + 1)) || { failed=$((failed + 1)); echo "FAILED: sweep outputs missing"; }
expect sweep-cluster-options 0 "cluster      drop 0.5" -- "$vksplat" sweep "$work/demo/demo.ply" \
  --cameras "$work/cameras.json" --images "$work/photos" --out "$work/sweep_cluster" --methods cluster \
  --fractions 0.5 --timing-reps 0 --no-scoring-cost --max-views 4 --delta-dist auto --seg-k 150 --kappa 0 --gamma 1
expect sweep-cluster-bad-delta 2 "--delta-dist x: expected a distance or auto" -- "$vksplat" sweep \
  "$work/demo/demo.ply" --cameras "$work/cameras.json" --images "$work/photos" --out "$work/sweep_bad" \
  --methods cluster --delta-dist x
expect sweep-refuses-overwrite 2 "sweep.csv: already exists" -- "$vksplat" sweep "$work/demo/demo.ply" \
  --cameras "$work/cameras.json" --images "$work/photos" --out "$work/sweep" --methods blend --fractions 0
# Cluster pruning: all stages, a re-run of one stage from the saved outputs, and the refusals.
cat >"$work/three.json" <<'JSON'
[{"id": 0, "img_name": "a", "width": 80, "height": 60, "position": [0, 0, 5],
  "rotation": [[1, 0, 0], [0, -1, 0], [0, 0, -1]], "fx": 70, "fy": 70},
 {"id": 1, "img_name": "b", "width": 80, "height": 60, "position": [0.4, 0, 5],
  "rotation": [[1, 0, 0], [0, -1, 0], [0, 0, -1]], "fx": 70, "fy": 70},
 {"id": 2, "img_name": "c", "width": 80, "height": 60, "position": [0, 0.4, 5],
  "rotation": [[1, 0, 0], [0, -1, 0], [0, 0, -1]], "fx": 70, "fy": 70}]
JSON
expect cluster-run 0 "Gaussians: 38605 ->" -- "$vksplat" cluster run "$work/demo/demo.ply" --cameras "$work/three.json" \
  --work "$work/cw" --delta-dist auto --seg-k 150 -o "$work/clustered.ply"
expect cluster-refuses-overwrite 2 "cluster_scores.npy: already exists" -- "$vksplat" cluster score \
  "$work/demo/demo.ply" --cameras "$work/three.json" --work "$work/cw"
expect cluster-rescore 0 "percentile" -- "$vksplat" cluster score "$work/demo/demo.ply" --cameras "$work/three.json" \
  --work "$work/cw" --gamma 0.5 --force
expect cluster-reprune 0 "wrote $work/half_clusters.ply" -- "$vksplat" cluster prune "$work/demo/demo.ply" \
  --cameras "$work/three.json" --work "$work/cw" --prune-ratio 0.5 -o "$work/half_clusters.ply"
expect cluster-original-method 0 "percentile" -- "$vksplat" cluster score "$work/demo/demo.ply" \
  --cameras "$work/three.json" --work "$work/cw" --alpha 0.1 --beta 0.1 --gamma 1 --kappa 0 --lambda 0 --force
expect cluster-original-prune 0 "wrote $work/original_clusters.ply" -- "$vksplat" cluster prune "$work/demo/demo.ply" \
  --cameras "$work/three.json" --work "$work/cw" --prune-ratio 0.9 --ratio-of clusters --max-contribution-loss 1 \
  -o "$work/original_clusters.ply"
# --preset original is those flags by name: the same scores, the same bytes.
expect cluster-preset-score 0 "percentile" -- "$vksplat" cluster score "$work/demo/demo.ply" \
  --cameras "$work/three.json" --work "$work/cw" --preset original --force
expect cluster-preset-prune 0 "wrote $work/original_preset.ply" -- "$vksplat" cluster prune "$work/demo/demo.ply" \
  --cameras "$work/three.json" --work "$work/cw" --preset original -o "$work/original_preset.ply"
cmp -s "$work/original_clusters.ply" "$work/original_preset.ply" && passed=$((passed + 1)) ||
  { failed=$((failed + 1)); echo "FAILED: --preset original differs from its flags"; }
expect cluster-preset-and-its-option any-failure "excludes" -- "$vksplat" cluster prune "$work/demo/demo.ply" \
  --cameras "$work/three.json" --work "$work/cw" --preset keep-subject --prune-ratio 0.5 -o "$work/x.ply"
expect cluster-quality-budget 0 "quality budget 0.500 dB: kept" -- "$vksplat" cluster prune "$work/demo/demo.ply" \
  --cameras "$work/three.json" --work "$work/cw" --max-psnr-drop 0.5 --test-views 0-2 -o "$work/budget_clusters.ply"
expect cluster-budget-or-ratio any-failure "--max-psnr-drop" -- "$vksplat" cluster prune "$work/demo/demo.ply" \
  --cameras "$work/three.json" --work "$work/cw" --max-psnr-drop 0.5 --prune-ratio 0.5 -o "$work/bad.ply"
expect cluster-help-says-the-original 0 "--kappa 0 --prune-ratio 0.9 --ratio-of clusters" -- "$vksplat" cluster --help
expect cluster-bad-ratio-of any-failure "--ratio-of" -- "$vksplat" cluster prune "$work/demo/demo.ply" \
  --cameras "$work/three.json" --work "$work/cw" --ratio-of splats -o "$work/bad.ply"
expect cluster-needs-earlier-stage 2 "run \`vksplat cluster project\` first" -- "$vksplat" cluster build \
  "$work/demo/demo.ply" --cameras "$work/three.json" --work "$work/empty_work"
expect cluster-bad-delta 2 "--delta-dist x: expected a distance or auto" -- "$vksplat" cluster build \
  "$work/demo/demo.ply" --cameras "$work/three.json" --work "$work/cw" --delta-dist x --force

# The subject region and a subject-masked re-fit, on a ring of cameras around the demo scene.
cat >"$work/ring.json" <<'JSON'
[{"id": 0, "img_name": "r0", "width": 80, "height": 60, "position": [1.477601, 0.8, 4.776682], "rotation": [[-0.955336, -0.046689, -0.291809], [0.0, 0.987441, -0.157991], [0.29552, -0.150934, -0.943338]], "fx": 70, "fy": 70},
 {"id": 1, "img_name": "r1", "width": 80, "height": 60, "position": [4.776682, 0.8, -1.477601], "rotation": [[0.29552, -0.150934, -0.943338], [0.0, 0.987441, -0.157991], [0.955336, 0.046689, 0.291809]], "fx": 70, "fy": 70},
 {"id": 2, "img_name": "r2", "width": 80, "height": 60, "position": [-1.477601, 0.8, -4.776682], "rotation": [[0.955336, 0.046689, 0.291809], [0.0, 0.987441, -0.157991], [-0.29552, 0.150934, 0.943338]], "fx": 70, "fy": 70},
 {"id": 3, "img_name": "r3", "width": 80, "height": 60, "position": [-4.776682, 0.8, 1.477601], "rotation": [[-0.29552, 0.150934, 0.943338], [-0.0, 0.987441, -0.157991], [-0.955336, -0.046689, -0.291809]], "fx": 70, "fy": 70}]
JSON
expect ring-photos 0 "wrote 4 views" -- "$vksplat" render "$work/demo/demo.ply" --cameras "$work/ring.json" \
  --out "$work/ring_photos"
expect cluster-subject 0 "subject region (automatic ball at" -- "$vksplat" cluster run "$work/demo/demo.ply" \
  --cameras "$work/ring.json" --work "$work/ring_work" --seg-k 150 --images "$work/ring_photos" -o "$work/ring.ply" \
  --sheets "$work/ring_sheets"
[ -f "$work/ring_sheets/r2_subject.png" ] && passed=$((passed + 1)) ||
  { failed=$((failed + 1)); echo "FAILED: cluster --sheets wrote no r2_subject.png"; }
expect cluster-recover 0 "re-fitted 10 iterations" -- "$vksplat" cluster prune "$work/demo/demo.ply" \
  --cameras "$work/ring.json" --work "$work/ring_work" --images "$work/ring_photos" --recover 10 -o "$work/ring_refit.ply"
expect cluster-recover-needs-photos 2 "--recover: needs the photos" -- "$vksplat" cluster prune "$work/demo/demo.ply" \
  --cameras "$work/ring.json" --work "$work/ring_work" --recover 10 -o "$work/ring_x.ply"
expect cluster-bad-subject 2 "expected auto or x,y,z,r" -- "$vksplat" cluster prune "$work/demo/demo.ply" \
  --cameras "$work/ring.json" --work "$work/ring_work" --images "$work/ring_photos" --subject 1,2 -o "$work/ring_x.ply"
expect cluster-subject-needs-focus 2 "the cameras have no common focus" -- "$vksplat" cluster prune \
  "$work/demo/demo.ply" --cameras "$work/three.json" --work "$work/cw" --images "$work/photos" -o "$work/x.ply"

# The automatic preset: three cameras zoomed in on the middle of the demo scene leave most of it far
# from every picture's centre (a room the views do not look at), so `cluster` chooses keep-subject and
# says why; the object-centred three.json got whole-picture. An explicit selection option wins.
cat >"$work/zoom.json" <<'JSON'
[{"id": 0, "img_name": "a", "width": 80, "height": 60, "position": [0, 0, 5],
  "rotation": [[1, 0, 0], [0, -1, 0], [0, 0, -1]], "fx": 350, "fy": 350},
 {"id": 1, "img_name": "b", "width": 80, "height": 60, "position": [0.1, 0, 5],
  "rotation": [[1, 0, 0], [0, -1, 0], [0, 0, -1]], "fx": 350, "fy": 350},
 {"id": 2, "img_name": "c", "width": 80, "height": 60, "position": [0, 0.1, 5],
  "rotation": [[1, 0, 0], [0, -1, 0], [0, 0, -1]], "fx": 350, "fy": 350}]
JSON
expect cluster-auto-object 0 "preset: whole-picture (automatic: 0.0% of the 38605 Gaussians are room" -- \
  "$vksplat" cluster score "$work/demo/demo.ply" --cameras "$work/three.json" --work "$work/cw" --force
expect cluster-auto-room 0 "preset: keep-subject (automatic:" -- "$vksplat" cluster run "$work/demo/demo.ply" \
  --cameras "$work/zoom.json" --work "$work/zw" --seg-k 150 -o "$work/zoom_auto.ply"
expect cluster-auto-is-keep-subject 0 "(20.0% kept)" -- "$vksplat" cluster prune "$work/demo/demo.ply" \
  --cameras "$work/zoom.json" --work "$work/zw" --preset keep-subject -o "$work/zoom_keep.ply"
cmp -s "$work/zoom_auto.ply" "$work/zoom_keep.ply" && passed=$((passed + 1)) ||
  { failed=$((failed + 1)); echo "FAILED: the automatic choice differs from --preset keep-subject"; }
expect cluster-whole-picture 0 "wrote $work/zoom_whole.ply" -- "$vksplat" cluster prune "$work/demo/demo.ply" \
  --cameras "$work/zoom.json" --work "$work/zw" --preset whole-picture -o "$work/zoom_whole.ply"
given=$("$vksplat" cluster prune "$work/demo/demo.ply" --cameras "$work/zoom.json" --work "$work/zw" \
  --max-contribution-loss 0.002 -o "$work/zoom_given.ply" 2>&1)
if ! grep -q "preset:" <<<"$given" && cmp -s "$work/zoom_given.ply" "$work/zoom_whole.ply" &&
   ! cmp -s "$work/zoom_given.ply" "$work/zoom_auto.ply"; then
  passed=$((passed + 1))
else
  failed=$((failed + 1)); echo "FAILED: an explicit --max-contribution-loss did not win over the automatic preset"
  echo "$given" | sed 's/^/    /' | tail -n 15
fi
expect cluster-help-says-auto 0 "score and prune choose (--preset auto)" -- "$vksplat" cluster --help

# Bad input, each with the message that names it.
head -c 9000000 "$work/demo/demo.ply" >"$work/truncated.ply"
expect truncated-ply 2 "truncated.ply" -- "$vksplat" info "$work/truncated.ply"
expect truncated-ply-says-so 2 "truncated body: 38605 vertices expected" -- "$vksplat" info "$work/truncated.ply"
sed 's/property float opacity/property float opacity\nproperty float extra_a\nproperty float extra_b/' \
  "$work/demo/demo.ply" >"$work/wrong_count.ply" 2>/dev/null
expect wrong-property-count 2 "wrong_count.ply" -- "$vksplat" info "$work/wrong_count.ply"
expect missing-camera-file any-failure "does not exist" -- "$vksplat" render "$work/demo/demo.ply" \
  --cameras "$work/nope.json" --out "$work/x"
sed 's/"fx": 70/"fx": 0/' "$work/cameras.json" >"$work/zero_focal.json"
expect zero-focal 2 "zero_focal.json" -- "$vksplat" render "$work/demo/demo.ply" --cameras "$work/zero_focal.json" --out "$work/y"
expect zero-focal-says-so 2 "camera 0 ('top'): focal length (0.000000, 70.000000) must be positive" -- "$vksplat" render "$work/demo/demo.ply" --cameras "$work/zero_focal.json" --out "$work/y"
sed 's/"fx": 70/"fx": 1e300/' "$work/cameras.json" >"$work/blank_focal.json"
expect focal-makes-no-picture 2 "blank_focal.json: camera 0 ('top'): focal length (1e+300, 70) makes no picture" -- \
  "$vksplat" render "$work/demo/demo.ply" --cameras "$work/blank_focal.json" --out "$work/y"
sed 's/"fx": 70/"fx": 1e400/' "$work/cameras.json" >"$work/overflow.json"
expect json-number-overflow 2 "overflow.json: unreadable JSON" -- "$vksplat" render "$work/demo/demo.ply" \
  --cameras "$work/overflow.json" --out "$work/y"
sed 's/^element vertex 38605/element vertex 20000/' "$work/demo/demo.ply" >"$work/count_too_small.ply" 2>/dev/null
expect ply-count-too-small 2 "room for 18605 more vertices" -- "$vksplat" info "$work/count_too_small.ply"
# Bad numbers are refused with the option's name, NaN and infinities included, and no message
# prints DBL_MAX as a bound.
scene_args=("$work/demo/demo.ply" --cameras "$work/cameras.json")
expect background-nan any-failure "--background: 'nan' is not a finite number in [0, 1]" -- "$vksplat" render \
  "${scene_args[@]}" --out "$work/bg" --background nan,0,0
expect background-inf any-failure "--background: 'inf' is not" -- "$vksplat" bench "${scene_args[@]}" --background 0,inf,0
expect background-above-one any-failure "--background: '2' is not" -- "$vksplat" prune "${scene_args[@]}" \
  --method blend --background 2,-1,0 -o "$work/bg.ply"
expect background-negative any-failure "--background: '-1' is not" -- "$vksplat" sweep "${scene_args[@]}" \
  --images "$work/photos" --out "$work/bg" --background 0,-1,0
expect keep-negative any-failure "--keep: '-3' is not a whole number >= 0" -- "$vksplat" prune "${scene_args[@]}" \
  --method blend --keep -3 -o "$work/bg.ply"
expect ratio-nan any-failure "--ratio: 'nan' is not a finite number in [0, 1]" -- "$vksplat" prune "${scene_args[@]}" \
  --method blend --ratio nan -o "$work/bg.ply"
expect memory-budget-nan any-failure "--memory-budget: 'nan' is not a finite number in [0.001, 1e+09]" -- \
  "$vksplat" render "${scene_args[@]}" --out "$work/bg" --memory-budget nan
expect memory-budget-tiny any-failure "--memory-budget: '1e-9' is not" -- "$vksplat" finetune "${scene_args[@]}" \
  --images "$work/photos" -o "$work/bg.ply" --memory-budget 1e-9
expect psnr-drop-negative any-failure "--max-psnr-drop: '-1' is not a finite number >= 0" -- "$vksplat" prune \
  "${scene_args[@]}" --method blend --max-psnr-drop -1 -o "$work/bg.ply"
"$vksplat" prune "${scene_args[@]}" --method blend --max-psnr-drop -1 -o "$work/bg.ply" 2>&1 | grep -q 17976931 &&
  { failed=$((failed + 1)); echo "FAILED: a message prints DBL_MAX"; } || passed=$((passed + 1))
expect iters-nan any-failure "--iters: 'nan' is not a whole number >= 1" -- "$vksplat" train "$work/photos" \
  -o "$work/bg" --iters nan
expect test-every-negative any-failure "--test-every: '-1' is not a whole number >= 0" -- "$vksplat" train \
  "$work/photos" -o "$work/bg" --test-every -1
expect grad-threshold-nan any-failure "--densify-grad-threshold: 'nan' is not a finite number > 0" -- "$vksplat" \
  train "$work/photos" -o "$work/bg" --densify-grad-threshold nan
expect fractions-nan any-failure "--fractions: 'nan' is not" -- "$vksplat" sweep "${scene_args[@]}" \
  --images "$work/photos" --out "$work/bg" --fractions 0.5,nan
expect delta-dist-nan 2 "--delta-dist nan: expected a distance or auto" -- "$vksplat" cluster build \
  "${scene_args[@]}" --work "$work/cw" --delta-dist nan --force
expect cluster-weight-inf any-failure "--kappa: 'inf' is not a finite number" -- "$vksplat" cluster score \
  "${scene_args[@]}" --work "$work/cw" --kappa inf
expect width-negative any-failure "--width: '-5' is not a whole number in [1, 16384]" -- "$vksplat" bench \
  "${scene_args[@]}" --width -5 --height 5
# Finetune: a short re-fit to photos of the demo (the three views above, rendered), the refusals,
# and Ctrl-C: the run stops with its checkpoint and no output, and --resume finishes it.
expect photos-of-three 0 "wrote 3 views" -- "$vksplat" render "$work/demo/demo.ply" --cameras "$work/three.json" \
  --out "$work/photos3" --background 1,1,1
# The re-fits below start from the demo's 6,000 most opaque Gaussians: a re-fit step on lavapipe
# costs ~10 us a Gaussian, and what they check does not need the whole demo.
expect small-scene 0 "Gaussians: 38605 -> 6000" -- "$vksplat" prune "$work/demo/demo.ply" --cameras "$work/cameras.json" \
  --method opacity --keep 6000 -o "$work/small.ply"
expect finetune 0 "test views (3, also trained on: not held out) against the photos: PSNR" -- "$vksplat" finetune "$work/small.ply" \
  --cameras "$work/three.json" --images "$work/photos3" --background 1,1,1 --iters 10 --quiet -o "$work/refit.ply"
expect finetune-refuses-overwrite 2 "refit.ply: already exists" -- "$vksplat" finetune "$work/demo/demo.ply" \
  --cameras "$work/three.json" --images "$work/photos3" --iters 10 -o "$work/refit.ply"
expect finetune-missing-photo 2 "'a'" -- "$vksplat" finetune "$work/demo/demo.ply" \
  --cameras "$work/three.json" --images "$work/photos" --iters 10 -o "$work/refit_missing.ply"
sed 's/"width": 80/"width": 81/' "$work/three.json" >"$work/three_wider.json"
expect finetune-wrong-size 2 "photo is 80x60 but camera 'a' renders 81x60" -- "$vksplat" finetune "$work/demo/demo.ply" \
  --cameras "$work/three_wider.json" --images "$work/photos3" --iters 10 -o "$work/refit_wide.ply"
expect finetune-resume-nothing 2 "no checkpoint to resume from" -- "$vksplat" finetune "$work/demo/demo.ply" \
  --cameras "$work/three.json" --images "$work/photos3" --iters 10 --resume -o "$work/refit_none.ply"
"$vksplat" finetune "$work/small.ply" --cameras "$work/three.json" --images "$work/photos3" --iters 100000 \
  --checkpoint-every 5 --quiet -o "$work/refit_stopped.ply" >"$work/stopped.log" 2>&1 &
finetune_pid=$!
for _ in $(seq 1 600); do [ -f "$work/refit_stopped.ply.checkpoint" ] && break; sleep 0.1; done
kill -INT $finetune_pid
wait $finetune_pid
stopped=$?
if [ $stopped -eq 130 ] && [ ! -e "$work/refit_stopped.ply" ] && [ -f "$work/refit_stopped.ply.checkpoint" ] &&
   grep -q "interrupted at iteration" "$work/stopped.log"; then
  passed=$((passed + 1))
else
  failed=$((failed + 1)); echo "FAILED: finetune on Ctrl-C (exit $stopped)"; sed 's/^/    /' "$work/stopped.log" | tail -5
fi
done_before=$(grep -o "interrupted at iteration [0-9]*" "$work/stopped.log" | grep -o "[0-9]*$")
expect finetune-resume 0 "iterations: $((done_before + 5))" -- "$vksplat" finetune "$work/small.ply" \
  --cameras "$work/three.json" --images "$work/photos3" --iters $((done_before + 5)) --resume --quiet \
  -o "$work/refit_stopped.ply"
# Nothing the user gave is lost: a checkpoint is never the input, the output or a file of another
# kind; only its own run continues it and only --force replaces it; no output is an input; a
# wrong output is refused before the first step.
same_file_or_fail() {  # NAME FILE COPY: FILE still holds what COPY holds
  cmp -s "$2" "$3" && passed=$((passed + 1)) || { failed=$((failed + 1)); echo "FAILED: $1 changed $2"; }
}
cp "$work/demo/demo.ply" "$work/in.ply" && cp "$work/cameras.json" "$work/notes.json"
finetune_in() { "$vksplat" finetune "$work/in.ply" --cameras "$work/three.json" --images "$work/photos3" --quiet "$@"; }
expect finetune-checkpoint-is-input 2 "in.ply: is an input of this command" -- finetune_in --iters 5 \
  --checkpoint "$work/in.ply" -o "$work/out1.ply"
expect finetune-checkpoint-is-output 2 "out1.ply: is also the run's output" -- finetune_in --iters 5 \
  --checkpoint "$work/out1.ply" -o "$work/out1.ply"
expect finetune-checkpoint-not-a-checkpoint 2 "notes.json: exists and is not a vksplat checkpoint" -- finetune_in \
  --iters 5 --checkpoint "$work/notes.json" --force -o "$work/out1.ply"
expect finetune-output-is-input 2 "in.ply: is an input of this command" -- finetune_in --iters 5 --force -o "$work/in.ply"
expect prune-output-is-input 2 "in.ply: is an input of this command" -- "$vksplat" prune "$work/in.ply" \
  --cameras "$work/cameras.json" --method opacity --ratio 0.5 --force -o "$work/in.ply"
same_file_or_fail finetune/prune "$work/in.ply" "$work/demo/demo.ply"
same_file_or_fail finetune "$work/notes.json" "$work/cameras.json"
[ ! -e "$work/out1.ply" ] && passed=$((passed + 1)) || { failed=$((failed + 1)); echo "FAILED: out1.ply written"; }
expect finetune-unwritable-format 2 "out.xyz: cannot write a scene as '.xyz'" -- finetune_in --iters 5 -o "$work/out.xyz"
expect finetune-missing-folder 2 "folder $work/nowhere does not exist" -- finetune_in --iters 5 -o "$work/nowhere/out.ply"
[ ! -e "$work/out.xyz.checkpoint" ] && passed=$((passed + 1)) ||
  { failed=$((failed + 1)); echo "FAILED: a refused output still left a checkpoint"; }
# A folder that takes no files (read-only for this user; /sys for root, who may write anywhere
# else) is an input error naming the path, found before any work.
mkdir -p "$work/readonly" && chmod a-w "$work/readonly"
readonly_dir=
if ! touch "$work/readonly/probe" 2>/dev/null; then readonly_dir=$work/readonly
elif ! touch /sys/vksplat_probe 2>/dev/null; then readonly_dir=/sys; fi
[ -n "$readonly_dir" ] && expect prune-read-only-folder 2 "$readonly_dir/out.ply: cannot be written: folder $readonly_dir" -- \
  "$vksplat" prune "$work/in.ply" --cameras "$work/cameras.json" --method opacity --ratio 0.5 -o "$readonly_dir/out.ply"
chmod u+w "$work/readonly"
cp "$work/refit_stopped.ply.checkpoint" "$work/stopped.checkpoint.copy"
expect finetune-rerun-keeps-checkpoint 2 "holds iteration $((done_before + 5)) of an earlier run" -- "$vksplat" finetune \
  "$work/small.ply" --cameras "$work/three.json" --images "$work/photos3" --iters 5 \
  --checkpoint "$work/refit_stopped.ply.checkpoint" -o "$work/rerun.ply"
same_file_or_fail finetune-rerun "$work/refit_stopped.ply.checkpoint" "$work/stopped.checkpoint.copy"
expect finetune-resume-another-scene 2 "made by another run (finetune of $work/small.ply): its scene is" -- \
  "$vksplat" finetune "$work/half.ply" --cameras "$work/three.json" --images "$work/photos3" --iters 50 --resume \
  --checkpoint "$work/refit_stopped.ply.checkpoint" -o "$work/other.ply"
expect finetune-resume-past-iters 0 "no steps are taken" -- "$vksplat" finetune "$work/small.ply" \
  --cameras "$work/three.json" --images "$work/photos3" --iters 1 --resume --quiet \
  --checkpoint "$work/refit_stopped.ply.checkpoint" -o "$work/past.ply"
expect prune-recover 0 "test views (3) against the photos" -- "$vksplat" prune "$work/small.ply" \
  --cameras "$work/three.json" --method blend --ratio 0.5 --recover 6 --rounds 2 --images "$work/photos3" \
  --background 1,1,1 -o "$work/recovered.ply"
# Without --method: blend weight, or blend-mix with a re-fit (the best measured for each).
expect prune-default-method 0 "Gaussians by blend on" -- "$vksplat" prune "$work/demo/demo.ply" \
  --cameras "$work/three.json" --ratio 0.5 -o "$work/default_method.ply"
expect prune-recover-default-method 0 "Gaussians by blend-mix on" -- "$vksplat" prune "$work/small.ply" \
  --cameras "$work/three.json" --ratio 0.5 --recover 6 --rounds 2 --images "$work/photos3" \
  --background 1,1,1 -o "$work/recovered_mix.ply"
expect prune-recover-needs-photos 2 "--recover: re-fits to the photos" -- "$vksplat" prune "$work/demo/demo.ply" \
  --cameras "$work/three.json" --method blend --ratio 0.5 --recover 6 -o "$work/recovered_nophotos.ply"
# Each round after the first ranks the re-fitted model by fisher again, so it gathers fisher too.
expect prune-fisher-recover 0 "round 2: pruned to 3000" -- "$vksplat" prune "$work/small.ply" \
  --cameras "$work/three.json" --method fisher --ratio 0.5 --recover 6 --rounds 2 --images "$work/photos3" \
  --background 1,1,1 -o "$work/fisher_recovered.ply"
# --recover-seconds: a wall-time budget instead of a count (issue 30), refused unless a positive
# number of seconds and alone; a bare --recover takes its count from the fraction dropped.
for seconds in 0 -3 nan inf; do
  expect "prune-recover-seconds-$seconds" 2 "--recover-seconds $seconds: must be a finite number of seconds above 0" -- \
    "$vksplat" prune "$work/demo/demo.ply" --cameras "$work/three.json" --method blend --ratio 0.5 \
    --recover-seconds "$seconds" --images "$work/photos3" -o "$work/recover_seconds_bad.ply"
done
expect prune-recover-seconds-and-count 2 "--recover-seconds 5: is a budget instead of an iteration count" -- \
  "$vksplat" prune "$work/demo/demo.ply" --cameras "$work/three.json" --method blend --ratio 0.5 --recover 6 \
  --recover-seconds 5 --images "$work/photos3" -o "$work/recover_seconds_both.ply"
expect prune-rounds-need-recover any-failure "--rounds requires --recover or --recover-seconds" -- "$vksplat" prune \
  "$work/demo/demo.ply" --cameras "$work/three.json" --method blend --ratio 0.5 --rounds 2 -o "$work/rounds_only.ply"
expect prune-round-keep-needs-recover any-failure "--round-keep requires --recover or --recover-seconds" -- "$vksplat" \
  prune "$work/demo/demo.ply" --cameras "$work/three.json" --method blend --ratio 0.5 --round-keep best \
  -o "$work/round_keep_only.ply"
expect prune-round-keep-unknown any-failure "--round-keep: top not in {sample,best}" -- "$vksplat" prune \
  "$work/demo/demo.ply" --cameras "$work/three.json" --method blend --ratio 0.5 --recover 6 --round-keep top \
  --images "$work/photos3" -o "$work/round_keep_top.ply"
# --round-spacing sets the early rounds' iterations (here 1 of 6, the last round the other 5), and
# --round-keep best keeps the best-scored instead of a sample (the schedule before issue 30's change).
expect prune-recover-spaced-best 0 "round 2: pruned to 3000 Gaussians and re-fitted, 5 iterations" -- "$vksplat" prune \
  "$work/small.ply" --cameras "$work/three.json" --method blend --ratio 0.5 --recover 6 --rounds 2 \
  --round-spacing 1 --round-keep best --images "$work/photos3" --background 1,1,1 -o "$work/recovered_spaced_best.ply"
expect finetune-seconds-and-iters 2 "--seconds: is a budget instead of an iteration count" -- "$vksplat" finetune \
  "$work/demo/demo.ply" --cameras "$work/three.json" --images "$work/photos3" --iters 5 --seconds 5 \
  -o "$work/refit_both.ply"
expect finetune-seconds-nan 2 "--seconds nan: must be a finite number of seconds above 0" -- "$vksplat" finetune \
  "$work/demo/demo.ply" --cameras "$work/three.json" --images "$work/photos3" --seconds nan -o "$work/refit_nan.ply"
expect cluster-recover-seconds-negative 2 "--recover-seconds -1: must be a finite number of seconds above 0" -- \
  "$vksplat" cluster prune "$work/demo/demo.ply" --cameras "$work/ring.json" --work "$work/ring_work" \
  --images "$work/ring_photos" --recover-seconds -1 -o "$work/ring_seconds.ply"
expect prune-recover-seconds 0 "round 2: pruned to" -- "$vksplat" prune "$work/small.ply" \
  --cameras "$work/three.json" --method blend --ratio 0.5 --recover-seconds 3 --rounds 2 --images "$work/photos3" \
  --background 1,1,1 -o "$work/recovered_seconds.ply"
# Every command that reads a scene reads every format (here SPZ).
expect render-reads-spz 0 "wrote 1 views" -- "$vksplat" render "$work/demo.spz" --cameras "$work/cameras.json" \
  --out "$work/render_spz"
expect bench-reads-spz 0 "mean of per-view medians" -- "$vksplat" bench "$work/demo.spz" --cameras "$work/cameras.json" \
  --reps 1 --warmup 0
expect prune-reads-spz 0 "Gaussians: 38605 -> 19302" -- "$vksplat" prune "$work/demo.spz" --cameras "$work/cameras.json" \
  --method opacity --ratio 0.5 -o "$work/half_from_spz.ply"
# Sweep --sizes: each model sized by a writer, so a format vksplat only reads is refused before any work.
expect sweep-sizes-unwritable 2 "size format 'gsplat-pt': is not one vksplat writes" -- "$vksplat" sweep \
  "$work/demo.spz" --cameras "$work/three.json" --images "$work/photos3" --out "$work/sweep_sizes" --methods blend \
  --sizes spz,gsplat-pt
# Sweep --recover: a re-fitted row beside the pruned one.
expect sweep-recover 0 "blend+recover" -- "$vksplat" sweep "$work/demo.spz" --cameras "$work/three.json" \
  --images "$work/photos3" --background 1,1,1 --out "$work/sweep_recover" --methods blend --fractions 0.5 \
  --recover 5 --recover-rounds 1 --timing-reps 0 --no-scoring-cost
# Train: an INRIA folder (cameras.json beside images/), a few steps from random points (2,000 of
# them where the count is not what a check is about: 100,000 cost lavapipe ~1 s a step), then the
# refusal to overwrite its outputs.
mkdir -p "$work/train_data" && cp "$work/three.json" "$work/train_data/cameras.json" &&
  cp -r "$work/photos3" "$work/train_data/images"
expect train 0 "test views (3): PSNR" -- "$vksplat" train "$work/train_data" -o "$work/trained" --iters 20 \
  --random-points 2000 --white-background --quiet
[ -f "$work/trained/point_cloud.ply" ] && [ -f "$work/trained/metrics.json" ] && [ -f "$work/trained/cameras.json" ] &&
  passed=$((passed + 1)) || { failed=$((failed + 1)); echo "FAILED: train outputs missing"; }
expect train-refuses-overwrite 2 "already exists" -- "$vksplat" train "$work/train_data" -o "$work/trained" --iters 20
# Without a budget the lean recipe runs (its window outlasts these 20 iterations, so nothing
# settles); its share must be one.
grep -q '"strategy": "lean"' "$work/trained/metrics.json" && passed=$((passed + 1)) ||
  { failed=$((failed + 1)); echo "FAILED: a run without a budget did not name the lean recipe"; }
expect train-keep-share-zero any-failure "--keep-share: '0' is not a finite number in" -- "$vksplat" train "$work/train_data" \
  -o "$work/trained_share" --iters 5 --keep-share 0
# Training to a budget: 0 is no budget, the budget recipe needs one, a budget below the starting
# points starts from a subset of them (said), one beyond memory is lowered (said).
expect train-random-points-zero any-failure "--random-points: '0' is not a whole number >= 1" -- "$vksplat" train \
  "$work/train_data" -o "$work/trained_nopoints" --iters 5 --random-points 0
expect train-budget-zero any-failure "--max-gaussians: '0' is not a whole number >= 1" -- "$vksplat" train "$work/train_data" \
  -o "$work/trained_zero" --iters 5 --max-gaussians 0
expect train-budget-needs-count 2 "--strategy budget: needs --max-gaussians" -- "$vksplat" train "$work/train_data" \
  -o "$work/trained_nobudget" --iters 5 --strategy budget
[ ! -e "$work/trained_nobudget" ] && passed=$((passed + 1)) ||
  { failed=$((failed + 1)); echo "FAILED: a refused budget run left its output folder"; }
"$vksplat" train "$work/train_data" -o "$work/trained_budget" --iters 20 --max-gaussians 1000 --white-background \
  --quiet >"$work/trained_budget.log" 2>&1
grep -q "budget 1000: starting from a random 500 of the 100000 starting points" "$work/trained_budget.log" &&
  grep -q "budget 1000: growing to 3000 Gaussians, then keeping the 1000 of most blend weight from step 20 on" \
    "$work/trained_budget.log" && passed=$((passed + 1)) ||
  { failed=$((failed + 1)); echo "FAILED: the budget run does not say where it starts and how far it grows"; cat "$work/trained_budget.log"; }
grep -q '"strategy": "budget"' "$work/trained_budget/metrics.json" && [ -f "$work/trained_budget/report.html" ] &&
  passed=$((passed + 1)) || { failed=$((failed + 1)); echo "FAILED: budget run's metrics.json or report.html"; }
# Growth beyond the budget stops at 400,000 Gaussians unless --budget-peak asks for a multiple.
expect train-budget-peak-limit 0 "budget 200000: growing to 400000 Gaussians, then keeping the 200000 of most blend weight from step 1 on (growth beyond the budget stops at 400000 Gaussians; --budget-peak lifts the limit)" -- \
  "$vksplat" train "$work/train_data" -o "$work/trained_limit" --iters 1 --max-gaussians 200000 --random-points 2000 \
  --white-background --quiet
expect train-budget-peak-asked 0 "budget 200000: growing to 600000 Gaussians, then keeping" -- \
  "$vksplat" train "$work/train_data" -o "$work/trained_peak3" --iters 1 --max-gaussians 200000 --budget-peak 3 --random-points 2000 \
  --white-background --quiet
expect train-budget-beyond-memory 0 "--max-gaussians 100000000: the memory budget holds about" -- "$vksplat" train \
  "$work/train_data" -o "$work/trained_huge" --iters 2 --max-gaussians 100000000 --memory-budget 400 --random-points 2000 --quiet
expect train-profile 0 "GPU time per step by pass (medians):  preprocess" -- "$vksplat" train "$work/train_data" \
  -o "$work/trained_profile" --iters 5 --random-points 2000 --white-background --quiet --profile
grep -q '"gpu_ms_per_stage"' "$work/trained_profile/metrics.json" && passed=$((passed + 1)) ||
  { failed=$((failed + 1)); echo "FAILED: metrics.json has no per-pass GPU times"; }
grep -q '"frame_allocation"' "$work/trained_profile/metrics.json" && passed=$((passed + 1)) ||
  { failed=$((failed + 1)); echo "FAILED: metrics.json does not split the scene changes' host time"; }
# Fixed-point sums, the default where the device has 64-bit atomics (lavapipe has): two runs write the
# same bytes (with --fast-sums, float sums added in another order make two such runs of 250 steps
# differ on lavapipe too); finetune and prune --recover likewise, there with the flag given.
for run in 1 2; do
  "$vksplat" train "$work/train_data" -o "$work/trained_det$run" --iters 250 --max-gaussians 3000 --white-background \
    --quiet >/dev/null 2>&1
  "$vksplat" finetune "$work/trained_det1/point_cloud.ply" --cameras "$work/three.json" --images "$work/photos3" \
    --background 1,1,1 --iters 20 --quiet --deterministic -o "$work/refit_det$run.ply" >/dev/null 2>&1
  "$vksplat" prune "$work/small.ply" --cameras "$work/three.json" --method blend --ratio 0.5 --recover 6 \
    --rounds 2 --images "$work/photos3" --background 1,1,1 --deterministic -o "$work/recovered_det$run.ply" >/dev/null 2>&1
done
cmp -s "$work/trained_det1/point_cloud.ply" "$work/trained_det2/point_cloud.ply" &&
  cmp -s "$work/refit_det1.ply" "$work/refit_det2.ply" && cmp -s "$work/recovered_det1.ply" "$work/recovered_det2.ply" && grep -q '"deterministic": true' "$work/trained_det1/metrics.json" &&
  passed=$((passed + 1)) || { failed=$((failed + 1)); echo "FAILED: two --deterministic runs differ"; }
expect train-fast-and-deterministic any-failure "excludes" -- "$vksplat" train "$work/train_data" -o "$work/trained_fast" \
  --iters 5 --deterministic --fast-sums
expect train-into-its-data 2 "cameras.json: is an input of this command" -- "$vksplat" train "$work/train_data" \
  -o "$work/train_data" --iters 20 --force
same_file_or_fail train-into-its-data "$work/train_data/cameras.json" "$work/three.json"
# An interrupted run (outputs not yet written, checkpoint kept) is not silently restarted, and
# another run (another seed: other random starts) cannot continue it.
mkdir -p "$work/trained_cut" && cp "$work/trained/checkpoint" "$work/trained_cut/checkpoint"
expect train-rerun-keeps-checkpoint 2 "holds iteration 20 of an earlier run" -- "$vksplat" train "$work/train_data" \
  -o "$work/trained_cut" --iters 20 --random-points 2000 --white-background
expect train-resume-another-run 2 "made by another run" -- "$vksplat" train "$work/train_data" -o "$work/trained_cut" \
  --iters 30 --random-points 2000 --white-background --seed 1 --resume
same_file_or_fail train-rerun "$work/trained_cut/checkpoint" "$work/trained/checkpoint"
# Photos of another shape are refused at a resolution scale too, never stretched to fit.
sed 's/"height": 60/"height": 50/' "$work/three.json" >"$work/three_short.json"
"$vksplat" render "$work/demo/demo.ply" --cameras "$work/three_short.json" --out "$work/photos_short" >/dev/null 2>&1
mkdir -p "$work/train_short" && cp "$work/three.json" "$work/train_short/cameras.json" &&
  cp -r "$work/photos_short" "$work/train_short/images"
expect train-scaled-wrong-aspect 2 "a resolution scale of 0.5 makes 40x25, but camera 'a' is 40x30" -- "$vksplat" train \
  "$work/train_short" -o "$work/trained_short" --iters 5 --resolution-scale 0.5
expect train-not-a-dataset 2 "holds neither a COLMAP model" -- "$vksplat" train "$work/photos3" -o "$work/trained2"
# A NeRF folder without transforms_test.json holds no view out: no test PSNR, not 0 dB.
mkdir -p "$work/nerf_data" && cp "$work/photos3/"*.png "$work/nerf_data/"
cat >"$work/nerf_data/transforms_train.json" <<'JSON'
{"camera_angle_x": 1.0383, "frames": [
 {"file_path": "a", "w": 80, "h": 60, "transform_matrix": [[1, 0, 0, 0], [0, 1, 0, 0], [0, 0, 1, 5], [0, 0, 0, 1]]},
 {"file_path": "b", "w": 80, "h": 60, "transform_matrix": [[1, 0, 0, 0.4], [0, 1, 0, 0], [0, 0, 1, 5], [0, 0, 0, 1]]},
 {"file_path": "c", "w": 80, "h": 60, "transform_matrix": [[1, 0, 0, 0], [0, 1, 0, 0.4], [0, 0, 1, 5], [0, 0, 0, 1]]}]}
JSON
expect train-no-test-views 0 "test views: none held out, so no test PSNR" -- "$vksplat" train "$work/nerf_data" \
  -o "$work/trained_nerf" --iters 5 --random-points 2000 --quiet
grep -q '"test_psnr": null' "$work/trained_nerf/metrics.json" && passed=$((passed + 1)) ||
  { failed=$((failed + 1)); echo "FAILED: metrics.json of a run without test views has a test PSNR"; }
sed 's/"width": 80/"width": 81/' "$work/cameras.json" >"$work/wider.json"
expect wrong-size-photo 2 "photo is 80x60 but camera 'top' renders 81x60" -- "$vksplat" render "$work/demo/demo.ply" \
  --cameras "$work/wider.json" --out "$work/z" --images "$work/photos"
expect bad-view-list 2 "view 4 does not exist" -- "$vksplat" render "$work/demo/demo.ply" \
  --cameras "$work/cameras.json" --out "$work/w" --views 0,4

# Render, prune --recover and sweep: every output checked and named before any work (issue 27).
# A view asked for twice is refused; cameras whose names collide get x.png, x-2.png, x-3.png; no
# file is written before all are checked; no output is a photo, --force or not; a refused render
# or sweep leaves no folder; a frame larger than any budget says what its pixels need; the
# re-fit's photos and rounds are checked before the views are scored.
expect render-view-twice 2 "view 0: is named twice" -- "$vksplat" render "$work/demo/demo.ply" \
  --cameras "$work/three.json" --out "$work/twice" --views 0,0
[ ! -e "$work/twice" ] && passed=$((passed + 1)) || { failed=$((failed + 1)); echo "FAILED: render left $work/twice"; }
sed -e 's/"img_name": "a"/"img_name": "left\/x.jpg"/' -e 's/"img_name": "b"/"img_name": "right\/x.jpg"/' \
  -e 's/"img_name": "c"/"img_name": "x"/' "$work/three.json" >"$work/same_names.json"
expect render-same-names 0 "wrote 3 views (3 files)" -- "$vksplat" render "$work/demo/demo.ply" \
  --cameras "$work/same_names.json" --out "$work/same_names"
[ -f "$work/same_names/x.png" ] && [ -f "$work/same_names/x-2.png" ] && [ -f "$work/same_names/x-3.png" ] &&
  passed=$((passed + 1)) || { failed=$((failed + 1)); echo "FAILED: x.png, x-2.png, x-3.png not all written"; }
expect render-help-says-how-names-collide 0 "x-2.png" -- "$vksplat" render --help
mkdir -p "$work/half_done" && echo mine >"$work/half_done/c.alpha.png"
expect render-checks-every-output-first 2 "c.alpha.png: already exists; not overwritten (--force replaces it)" -- \
  "$vksplat" render "$work/demo/demo.ply" --cameras "$work/three.json" --out "$work/half_done" --alpha
[ ! -e "$work/half_done/a.png" ] && passed=$((passed + 1)) ||
  { failed=$((failed + 1)); echo "FAILED: render wrote a.png before refusing c.alpha.png"; }
cp "$work/photos3/a.png" "$work/photo_a.copy"
expect render-over-its-photos 2 "a.png: is an input of this command" -- "$vksplat" render "$work/demo/demo.ply" \
  --cameras "$work/three.json" --out "$work/photos3" --images "$work/photos3" --force
cmp -s "$work/photos3/a.png" "$work/photo_a.copy" && passed=$((passed + 1)) ||
  { failed=$((failed + 1)); echo "FAILED: render wrote over its photo a.png"; }
sed -e 's/"width": 80/"width": 16384/' -e 's/"height": 60/"height": 16384/' "$work/cameras.json" >"$work/huge.json"
expect render-frame-says-what-its-pixels-need any-failure "however the Gaussians are chunked (its per-pixel buffers: " \
  -- "$vksplat" render "$work/demo/demo.ply" --cameras "$work/huge.json" --out "$work/huge" --memory-budget 1000
mkdir -p "$work/photos_ab" && cp "$work/photos3/a.png" "$work/photos3/b.png" "$work/photos_ab/"
output=$("$vksplat" prune "$work/demo/demo.ply" --cameras "$work/three.json" --method blend --ratio 0.5 \
  --recover 6 --test-views 0,1 --images "$work/photos_ab" -o "$work/recover_no_c.ply" 2>&1)
if [ $? -eq 2 ] && grep -qF "no image for camera 'c'" <<<"$output" && ! grep -q "scored views" <<<"$output"; then
  passed=$((passed + 1))
else
  failed=$((failed + 1)); echo "FAILED: prune --recover scored before finding the missing photo"
  echo "$output" | sed 's/^/    /' | tail -n 5
fi
output=$("$vksplat" sweep "$work/demo/demo.ply" --cameras "$work/three.json" --images "$work/photos3" \
  --out "$work/sweep_refused/out" --methods blend --fractions 0.5 --recover 2 --recover-rounds 3 --timing-reps 0 2>&1)
if [ $? -eq 2 ] && grep -qF "leaves no iterations for each of 3 rounds" <<<"$output" &&
   ! grep -q "scoring" <<<"$output" && [ ! -e "$work/sweep_refused" ]; then
  passed=$((passed + 1))
else
  failed=$((failed + 1)); echo "FAILED: sweep --recover scored before refusing its rounds, or left a folder"
  echo "$output" | sed 's/^/    /' | tail -n 5
fi
expect sweep-refusal-names-force 2 "(--force replaces it)" -- "$vksplat" sweep "$work/demo/demo.ply" \
  --cameras "$work/cameras.json" --images "$work/photos" --out "$work/sweep" --methods blend --fractions 0

# Scene outputs: every command writes the format its output's name says, and refuses a name no
# writer has before any work (exit 2, nothing written).
# starts_with NAME FILE BYTES: FILE begins with BYTES (e.g. an SPZ 4's "NGSP", a PLY's "ply").
starts_with() {
  if [ "$(head -c ${#3} "$2" 2>/dev/null)" = "$3" ]; then passed=$((passed + 1)); else
    failed=$((failed + 1)); echo "FAILED: $1: $2 does not start with '$3'"; fi
}
# refused_before_work NAME OUTPUT PATTERN -- COMMAND...: exit 2 with PATTERN, no progress line, no OUTPUT.
refused_before_work() {
  local name=$1 out=$2 pattern=$3
  shift 4
  local output status
  output=$("$@" 2>&1)
  status=$?
  if [ $status -eq 2 ] && grep -qF -- "$pattern" <<<"$output" && ! grep -qE "scored views|\[regions\]" <<<"$output" &&
     [ ! -e "$out" ]; then
    passed=$((passed + 1))
  else
    failed=$((failed + 1)); echo "FAILED: $name (exit $status, expected 2 before any work and no $out)"
    echo "$output" | sed 's/^/    /' | tail -n 5
  fi
}
expect prune-writes-spz 0 "wrote $work/half.spz" -- "$vksplat" prune "$work/demo/demo.ply" --cameras "$work/cameras.json" \
  --method opacity --ratio 0.5 -o "$work/half.spz"
starts_with prune-spz-is-spz-3 "$work/half.spz" $'\x1f'
expect prune-spz-reads-back 0 "Gaussians: 19302" -- "$vksplat" info "$work/half.spz"
expect prune-writes-compressed-ply 0 "bytes written" -- "$vksplat" prune "$work/demo/demo.ply" \
  --cameras "$work/cameras.json" --method opacity --ratio 0.5 -o "$work/half.compressed.ply"
expect prune-compressed-ply-reads-back 0 "Gaussians: 19302" -- "$vksplat" info "$work/half.compressed.ply"
if head -c 400 "$work/half.compressed.ply" | grep -qa "^element chunk 76$"; then passed=$((passed + 1)); else
  failed=$((failed + 1)); echo "FAILED: prune -o half.compressed.ply wrote no chunk element"; fi
refused_before_work prune-refuses-obj "$work/x.obj" "x.obj: cannot write a scene as '.obj'" -- "$vksplat" prune \
  "$work/demo/demo.ply" --cameras "$work/cameras.json" --method blend --ratio 0.5 -o "$work/x.obj"
refused_before_work prune-refuses-read-only "$work/x.pt" ".ply, .compressed.ply, .splat, .spz" -- "$vksplat" prune \
  "$work/demo/demo.ply" --cameras "$work/cameras.json" --method blend --ratio 0.5 -o "$work/x.pt"
expect cluster-writes-splat 0 "wrote $work/half_clusters.splat" -- "$vksplat" cluster prune "$work/demo/demo.ply" \
  --cameras "$work/three.json" --work "$work/cw" --prune-ratio 0.5 -o "$work/half_clusters.splat" --force
expect cluster-splat-reads-back 0 "SH degree: 0" -- "$vksplat" info "$work/half_clusters.splat"
refused_before_work cluster-refuses-obj "$work/x.obj" "x.obj: cannot write a scene as '.obj'" -- "$vksplat" cluster run \
  "$work/demo/demo.ply" --cameras "$work/three.json" --work "$work/cw_obj" --delta-dist auto -o "$work/x.obj"
[ ! -e "$work/cw_obj" ] && passed=$((passed + 1)) || { failed=$((failed + 1)); echo "FAILED: cluster run -o x.obj made its work folder"; }
expect convert-writes-compressed-ply 0 "to $work/demo.compressed.ply (compressed-ply)" -- "$vksplat" convert \
  "$work/demo/demo.ply" "$work/demo.compressed.ply"
expect convert-writes-spz-4 0 "(spz-v4)" -- "$vksplat" convert "$work/demo/demo.ply" "$work/demo_v4.spz" --format spz-v4
starts_with convert-spz-4-is-ngsp "$work/demo_v4.spz" "NGSP"
expect convert-reads-spz-4 0 "Gaussians: 38605" -- "$vksplat" info "$work/demo_v4.spz"
refused_before_work convert-refuses-obj "$work/y.obj" "y.obj: cannot write a scene as '.obj'" -- "$vksplat" convert \
  "$work/demo/demo.ply" "$work/y.obj"

# A COLMAP data folder whose camera has an OPENCV lens (the top camera): trained from its photo
# undistorted at load, as the log says; a fisheye lens is refused by its model's name.
mkdir -p "$work/colmap_lens/sparse/0" "$work/colmap_lens/images" && cp "$work/photos/top.png" "$work/colmap_lens/images/"
echo "1 OPENCV 80 60 70 70 40 30 -0.1 0.01 0.001 0" >"$work/colmap_lens/sparse/0/cameras.txt"
printf '1 0 1 0 0 0 0 5 1 top.png\n\n' >"$work/colmap_lens/sparse/0/images.txt"
printf '1 0 0 0 200 200 200 0.5\n2 0.2 0.1 0 100 100 100 0.5\n' >"$work/colmap_lens/sparse/0/points3D.txt"
expect train-undistorts-opencv-lens 0 "camera 1 (OPENCV k1=-0.1 k2=0.01 p1=0.001 p2=0): photos undistorted to PINHOLE fx=" \
  -- "$vksplat" train "$work/colmap_lens" -o "$work/trained_lens" --iters 5 --test-every 0 --quiet
sed -i 's/OPENCV/OPENCV_FISHEYE/' "$work/colmap_lens/sparse/0/cameras.txt"
expect train-refuses-fisheye-lens 2 "camera model OPENCV_FISHEYE is not supported" -- "$vksplat" train \
  "$work/colmap_lens" -o "$work/trained_fisheye" --iters 5 --test-every 0

# Sweep progress and report (issue 32): each re-fit reports its iterations with the time the whole
# sweep has left, no line says "0.0 s left" before the last, and the report opens with a one-line
# summary, says "identical" where sweep.csv keeps inf, and has JPEG sheets.
output=$("$vksplat" sweep "$work/demo/demo.ply" --cameras "$work/three.json" --images "$work/photos3" \
  --background 1,1,1 --out "$work/sweep_progress" --methods blend --fractions 0,0.5 --recover 6 --recover-rounds 1 \
  --timing-reps 0 --no-scoring-cost 2>&1)
left_lines=$(grep "left in all" <<<"$output")
if grep -q "^re-fit of blend at 0.5 dropped 6/6 .* left in all" <<<"$output" &&
   ! head -n -1 <<<"$left_lines" | grep -q " 0\.0 s left" &&
   tail -n 1 <<<"$left_lines" | grep -q "^comparison sheets 3/3 .* 0\.0 s left in all" &&
   grep -q "^best trade: blend" <<<"$output"; then
  passed=$((passed + 1))
else
  failed=$((failed + 1)); echo "FAILED: sweep --recover progress lines"; echo "$output" | sed 's/^/    /' | tail -n 25
fi
report=$work/sweep_progress/report.html
if grep -q '<p class="note summary">best trade: ' "$report" && grep -q "<td>identical</td>" "$report" &&
   ! grep -q ">inf<" "$report" && grep -q "^blend,0,.*,inf," "$work/sweep_progress/sweep.csv" &&
   [ "$(ls "$work/sweep_progress/sheets" | grep -c '\.jpg$')" -eq 3 ]; then
  passed=$((passed + 1))
else
  failed=$((failed + 1)); echo "FAILED: sweep report: summary, 'identical', CSV inf or JPEG sheets"
fi

# prune --max-mb (issue 30): the file written fits in M x 10^6 bytes in the output's format, SH bands
# traded against Gaussians; a size no model reaches names the smallest, and what --max-mb cannot go
# with is refused before any work.
# The searches measure each candidate's pictures, so the two runs compared start from the small
# scene (0.23 MB as SPZ; 0.05 MB needs both fewer Gaussians and fewer SH bands).
expect prune-max-mb 0 "wrote $work/max.spz" -- "$vksplat" prune "$work/small.ply" --cameras "$work/cameras.json" \
  --method opacity --max-mb 0.05 -o "$work/max.spz"
[ -f "$work/max.spz" ] && [ "$(stat -c %s "$work/max.spz")" -le 50000 ] && passed=$((passed + 1)) ||
  { failed=$((failed + 1)); echo "FAILED: prune --max-mb 0.05 wrote more than 50000 bytes"; }
# The choices' count searches run on threads; which thread finishes first changes nothing written.
"$vksplat" prune "$work/small.ply" --cameras "$work/cameras.json" --method opacity --max-mb 0.05 \
  -o "$work/max_again.spz" >/dev/null 2>&1
cmp -s "$work/max.spz" "$work/max_again.spz" && passed=$((passed + 1)) ||
  { failed=$((failed + 1)); echo "FAILED: two prune --max-mb 0.05 runs wrote different files"; }
expect prune-max-mb-compressed-ply 0 "with 100% of the higher bands dropped per Gaussian" -- "$vksplat" prune \
  "$work/demo/demo.ply" --cameras "$work/cameras.json" --method opacity --max-mb 0.5 -o "$work/max.compressed.ply"
[ -f "$work/max.compressed.ply" ] && [ "$(stat -c %s "$work/max.compressed.ply")" -le 500000 ] &&
  passed=$((passed + 1)) || { failed=$((failed + 1)); echo "FAILED: prune --max-mb 0.5 wrote more than 500000 bytes"; }
# --sh-bits: fewer bits of SPZ's SH byte give a smaller file, and --max-mb measures its candidates so.
expect prune-sh-bits 0 "wrote $work/half65.spz" -- "$vksplat" prune "$work/demo/demo.ply" \
  --cameras "$work/cameras.json" --method opacity --ratio 0.5 --sh-bits 6,5 -o "$work/half65.spz"
expect prune-sh-bits-full 0 "wrote $work/half88.spz" -- "$vksplat" prune "$work/demo/demo.ply" \
  --cameras "$work/cameras.json" --method opacity --ratio 0.5 -o "$work/half88.spz"
[ -f "$work/half65.spz" ] && [ -f "$work/half88.spz" ] &&
  [ "$(stat -c %s "$work/half65.spz")" -lt "$(stat -c %s "$work/half88.spz")" ] && passed=$((passed + 1)) ||
  { failed=$((failed + 1)); echo "FAILED: prune --sh-bits 6,5 wrote no smaller SPZ than full precision"; }
expect prune-max-mb-sh-bits 0 "wrote $work/max65.spz" -- "$vksplat" prune "$work/demo/demo.ply" \
  --cameras "$work/cameras.json" --method opacity --max-mb 0.3 --sh-bits 6,5 -o "$work/max65.spz"
[ -f "$work/max65.spz" ] && [ "$(stat -c %s "$work/max65.spz")" -le 300000 ] && passed=$((passed + 1)) ||
  { failed=$((failed + 1)); echo "FAILED: prune --max-mb 0.3 --sh-bits 6,5 wrote more than 300000 bytes"; }
expect prune-sh-bits-range 2 "--sh-bits 9,5: SH bits must be whole numbers from 1 to 8" -- "$vksplat" prune \
  "$work/demo/demo.ply" --cameras "$work/cameras.json" --method opacity --ratio 0.5 --sh-bits 9,5 -o "$work/bits.spz"
refused_before_work prune-max-mb-too-small "$work/tiny.spz" \
  "--max-mb 1e-05: no model fits in it: the smallest, one Gaussian at SH degree 0, takes" -- "$vksplat" prune \
  "$work/demo/demo.ply" --cameras "$work/cameras.json" --method opacity --max-mb 0.00001 -o "$work/tiny.spz"
expect prune-max-mb-zero any-failure "--max-mb: '0' is not a finite number > 0" -- "$vksplat" prune \
  "$work/demo/demo.ply" --cameras "$work/cameras.json" --method opacity --max-mb 0 -o "$work/zero.spz"
expect prune-max-mb-negative any-failure "--max-mb: '-1' is not a finite number > 0" -- "$vksplat" prune \
  "$work/demo/demo.ply" --cameras "$work/cameras.json" --method opacity --max-mb -1 -o "$work/zero.spz"
for other in "--ratio 0.5" "--keep 5" "--max-psnr-drop 1" "--allow-sh-reduction"; do
  # shellcheck disable=SC2086
  expect "prune-max-mb-with $other" any-failure "excludes" -- "$vksplat" prune "$work/demo/demo.ply" \
    --cameras "$work/cameras.json" --method opacity --max-mb 0.3 $other -o "$work/both.spz"
done
before=$(stat -c %s "$work/max.spz")
expect prune-max-mb-refuses-overwrite 2 "max.spz: already exists" -- "$vksplat" prune "$work/demo/demo.ply" \
  --cameras "$work/cameras.json" --method opacity --max-mb 0.2 -o "$work/max.spz"
[ "$(stat -c %s "$work/max.spz")" = "$before" ] && passed=$((passed + 1)) ||
  { failed=$((failed + 1)); echo "FAILED: prune --max-mb replaced an existing output"; }
# The re-fit reaches the count chosen in prune --recover's rounds, as without a budget: the rounds
# asked for, and by default one per 1,000 iterations up to 5 (so one for these 5).
expect prune-max-mb-recover 0 "round 3: pruned to" -- "$vksplat" prune "$work/small.ply" \
  --cameras "$work/cameras.json" --method opacity --max-mb 0.035 --recover 5 --rounds 3 --images "$work/photos" \
  --background 1,1,1 -o "$work/max_refit.spz"
short_refit=$("$vksplat" prune "$work/small.ply" --cameras "$work/cameras.json" --method opacity --max-mb 0.035 \
  --recover 5 --images "$work/photos" --background 1,1,1 -o "$work/max_refit_short.spz" 2>&1)
grep -q "round 1: pruned to" <<<"$short_refit" && ! grep -q "round 2:" <<<"$short_refit" && passed=$((passed + 1)) ||
  { failed=$((failed + 1)); echo "FAILED: prune --max-mb 0.035 --recover 5 did not run exactly one round"; echo "$short_refit" | tail -n 5; }
[ -f "$work/max_refit.spz" ] && [ "$(stat -c %s "$work/max_refit.spz")" -le 35000 ] && passed=$((passed + 1)) ||
  { failed=$((failed + 1)); echo "FAILED: prune --max-mb 0.035 --recover wrote more than 35000 bytes"; }

echo "cli: $passed passed, $failed failed"
[ $failed -eq 0 ]
