#!/usr/bin/env bash
# One GPU session's measurements in one go (device time is scarce): every case of the speed
# issue's table with the floor, tiled 5x5 in float and half SH, the golden check of both
# storages, and the scaling charts. Run from the repository root on the GPU host, with `.gl/`
# (Debian's libvulkan1) and DATA (a stripped vksplat_bench beside lego/ and/or snowmiku/, each
# with point_cloud.ply, cameras.json, golden/) carried. Writes OUT/log.txt and OUT/results.tar.gz.
# BENCH overrides the binary (default DATA/vksplat_bench). lego's goldens are rendered on white,
# snowmiku's on black (../shared/data/README.md), so the golden check passes each its background.
# usage: benchmarks/gpu_session.sh DATA OUT
set -uo pipefail
data=$1 out=$2
. benchmarks/device_env.sh >/dev/null
bench=${BENCH:-$data/vksplat_bench} results=$(mktemp -d)
exec >"$out/log.txt" 2>&1
nvidia-smi --query-gpu=name,driver_version,clocks.max.sm,memory.total --format=csv,noheader
run() { echo "### ${*:2}"; "$@"; }
headline() { grep -v "^    [a-z]"; }  # per-view lines without the stage breakdown
golden() {  # scene background storage-flag...
    local scene=$1 background=$2 dir; shift 2
    dir=$(mktemp -d)
    "$bench" bench "$data/$scene/point_cloud.ply" --cameras "$data/$scene/cameras.json" --views 0-3 --reps 1 \
        --warmup 0 --background "$background" --save-npy "$dir" "$@" >/dev/null
    echo "### golden $scene $*"
    python3 benchmarks/compare_golden.py "$dir" "$data/$scene/golden" 0 1 2 3
}
if [ -d "$data/lego" ]; then
    L=$data/lego
    run "$bench" bench $L/point_cloud.ply --cameras $L/cameras.json --views 0-12 --floor --json $results/lego13.json | headline
    run "$bench" bench $L/point_cloud.ply --cameras $L/cameras.json --views 0 --width 1920 --height 1080 --floor --json $results/lego1080.json
    run "$bench" bench $L/point_cloud.ply --cameras $L/cameras.json --views 0 --width 3840 --height 2160 --floor --json $results/lego4k.json
    run "$bench" bench $L/point_cloud.ply --tiled 5x5 --floor --json $results/tiled.json
    run "$bench" bench $L/point_cloud.ply --tiled 5x5 --half-sh --floor --json $results/tiled_half.json
    run "$bench" bench $L/point_cloud.ply --cameras $L/cameras.json --views 0-12 --half-sh --json $results/lego13_half.json | headline
    run "$bench" bench $L/point_cloud.ply --cameras $L/cameras.json --views 0-12 --stats --json $results/lego13_stats.json | headline
    golden lego 1,1,1
    golden lego 1,1,1 --half-sh
    run "$bench" bench $L/point_cloud.ply --cameras $L/cameras.json --views 0 --reps 30 --floor --scaling \
        --charts $results/charts --json $results/scaling.json | grep -E "scaling|measured|wrote"
fi
if [ -d "$data/snowmiku" ]; then
    S=$data/snowmiku
    run "$bench" bench $S/point_cloud.ply --cameras $S/cameras.json --views 0-12 --floor --json $results/snowmiku13.json | headline
    run "$bench" bench $S/point_cloud.ply --cameras $S/cameras.json --views 0-12 --half-sh --json $results/snowmiku13_half.json | headline
    run "$bench" bench $S/point_cloud.ply --cameras $S/cameras.json --views 0-12 --stats --json $results/snowmiku13_stats.json | headline
    golden snowmiku 0,0,0
    golden snowmiku 0,0,0 --half-sh
fi
tar czf "$out/results.tar.gz" -C "$results" .
