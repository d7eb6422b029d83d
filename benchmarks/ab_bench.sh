#!/usr/bin/env bash
# Compares builds of the benchmark on the same frames in one sitting, as ratios: A, B, [C, ...], A,
# B, ... (alternating, so clock and thermal drift fall on all), each round a full `bench` run with
# the given arguments. Prints each build's rounds (mean of per-view medians), the median of its
# rounds and its ratio to the first build, and the mean over views of each stage's median. Used to
# keep or drop an optimisation (benchmarks/RESULTS.md records the outcome).
# usage: benchmarks/ab_bench.sh BENCH_A BENCH_B [BENCH_C ...] ROUNDS -- BENCH_ARGS...
set -euo pipefail
bins=()
while [ $# -gt 0 ] && [ "$1" != "--" ]; do bins+=("$1"); shift; done
[ $# -gt 0 ] && shift  # the "--"
if [ ${#bins[@]} -lt 3 ]; then
    echo "usage: $0 BENCH_A BENCH_B [BENCH_C ...] ROUNDS -- BENCH_ARGS..." >&2
    exit 2
fi
rounds=${bins[-1]}
unset 'bins[-1]'
dir=$(mktemp -d)
for ((r = 0; r < rounds; ++r)); do
    for i in "${!bins[@]}"; do
        "${bins[$i]}" bench "$@" --json "$dir/$i.$r.json" >/dev/null
    done
done
python3 - "$dir" "$rounds" "${bins[@]}" <<'PY'
import json, statistics, sys
d, rounds, bins = sys.argv[1], int(sys.argv[2]), sys.argv[3:]
first = None
for i, name in enumerate(bins):
    ms = [json.load(open(f"{d}/{i}.{r}.json"))["mean_of_medians_ms"] for r in range(rounds)]
    stages = {}
    for v in json.load(open(f"{d}/{i}.0.json"))["views"]:
        for st in v["stages"]:
            stages.setdefault(st["stage"], []).append(st["median_ms"])
    median = statistics.median(ms)
    first = first or median
    print(f"{name}: " + " ".join(f"{x:.3f}" for x in ms) + f" ms, median {median:.3f}, / first {median / first:.3f}")
    print("    " + ", ".join(f"{k} {statistics.mean(v):.3f}" for k, v in stages.items()))
PY
