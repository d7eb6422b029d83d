#!/usr/bin/env bash
# Compares two builds of the benchmark on the same frames in one sitting, as ratios: A, B, A, B
# (alternating, so clock and thermal drift fall on both), each round a full `bench` run with the
# given arguments. Prints each round's mean of per-view medians and the ratio B / A of the medians
# of the rounds. Used to keep or drop an optimisation (benchmarks/RESULTS.md records the outcome).
# usage: benchmarks/ab_bench.sh BENCH_A BENCH_B ROUNDS -- BENCH_ARGS...
set -euo pipefail
a=$1 b=$2 rounds=$3
shift 3
[ "$1" = "--" ] && shift
dir=$(mktemp -d)
for ((r = 0; r < rounds; ++r)); do
    for side in a b; do
        bin=$a
        [ $side = b ] && bin=$b
        "$bin" bench "$@" --json "$dir/$side$r.json" >/dev/null
    done
done
python3 - "$dir" "$rounds" <<'PY'
import json, statistics, sys
d, rounds = sys.argv[1], int(sys.argv[2])
ms = {s: [json.load(open(f"{d}/{s}{r}.json"))["mean_of_medians_ms"] for r in range(rounds)] for s in "ab"}
stages = {}
for s in "ab":
    views = json.load(open(f"{d}/{s}0.json"))["views"]
    for v in views:
        for st in v["stages"]:
            stages.setdefault(st["stage"], {}).setdefault(s, []).append(st["median_ms"])
for s in "ab":
    print(f"{s.upper()}: " + " ".join(f"{x:.3f}" for x in ms[s]) + " ms")
ma, mb = statistics.median(ms["a"]), statistics.median(ms["b"])
print(f"B / A = {mb / ma:.3f}  (A {ma:.3f} ms, B {mb:.3f} ms)")
for name, sides in stages.items():
    if "a" in sides and "b" in sides:
        print(f"  {name:14s} A {statistics.mean(sides['a']):.3f}  B {statistics.mean(sides['b']):.3f} ms")
PY
