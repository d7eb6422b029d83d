#!/usr/bin/env bash
# Fuzzes every file reader with libFuzzer (ASan + UBSan), one target after another.
#   tools/fuzz.sh [SECONDS_PER_TARGET=60] [TARGET...]
# Builds with clang in build-fuzz (VKSPLAT_FUZZ_BUILD_DIR), regenerates the seeds from
# tests/fuzz/make_seeds.py (plus the shared format fixtures when ../shared/data is there) into the
# working corpus build-fuzz/corpus/<target>, which keeps growing between runs. A crash, hang
# (-timeout, 10 s) or allocation over -malloc_limit_mb leaves its input in build-fuzz/crashes/<target>/;
# copy it to tests/fuzz/regressions/<target>/ once fixed so the normal suite replays it.
# Prints executions per target; exits non-zero if any target found something.
set -uo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
build=${VKSPLAT_FUZZ_BUILD_DIR:-$root/build-fuzz}
seconds=${1:-60}
shift || true
targets=("$@")
[ ${#targets[@]} -gt 0 ] || targets=(ply cameras_json colmap_binary colmap_text transforms_json npy splat spz
                                     compressed_ply gsplat_pt)

cmake -S "$root" -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCMAKE_C_COMPILER=clang \
  -DCMAKE_CXX_COMPILER=clang++ -DVKSPLAT_FUZZ=ON -DVKSPLAT_BUILD_TESTS=OFF -DVKSPLAT_BUILD_TOOLS=OFF \
  -DVKSPLAT_BUILD_BENCHMARKS=OFF >/dev/null || exit 1
cmake --build "$build" -j"${VKSPLAT_FUZZ_JOBS:-$(nproc)}" --target "${targets[@]/#/fuzz_}" || exit 1

python3 "$root/tests/fuzz/make_seeds.py" "$build/seeds" "$root/../shared/data/formats"
status=0
for target in "${targets[@]}"; do
  corpus=$build/corpus/$target crashes=$build/crashes/$target
  mkdir -p "$corpus" "$crashes"
  log=$build/fuzz_$target.log
  # Seeds from the generator, the committed ones and every regression input.
  inputs=()
  for dir in "$corpus" "$build/seeds/$target" "$root/tests/fuzz/seeds/$target" "$root/tests/fuzz/regressions/$target"; do
    [ -d "$dir" ] && inputs+=("$dir")
  done
  "$build/tests/fuzz/fuzz_$target" -max_total_time="$seconds" -timeout=10 -rss_limit_mb=2048 \
    -malloc_limit_mb=1024 -max_len=16384 -artifact_prefix="$crashes/" -print_final_stats=1 \
    "${inputs[@]}" >"$log" 2>&1
  code=$?
  runs=$(grep -o 'stat::number_of_executed_units: *[0-9]*' "$log" | grep -o '[0-9]*$')
  found=$(find "$crashes" -type f | wc -l)
  echo "$target: ${runs:-?} executions, exit $code, $found inputs in $crashes (log: $log)"
  [ "$code" -eq 0 ] && [ "$found" -eq 0 ] || status=1
done
exit $status
