#!/usr/bin/env bash
# The parallel step against the machine's own two-thread ceiling, run after run
# (docs/benchmarks-peers.md#the-parallel-step, "The parallel step"): each run is one `s2sim-peers`
# call on robots_16 and robots_64 with the serial step, the parallel step (running ahead and
# tick by tick) and two serial copies at once (the ceiling), five rounds each. A table row per
# run gives each parallel engine's speed-up over the serial run in wall time, the ceiling, the
# parallel step as a share of it, the serial step's and the parallel step's wall µs, and the
# largest share of a vCPU the hypervisor took (median round). Then, RUNS times, the serial step
# on robots_16 pinned to each vCPU at once (taskset): each vCPU's own speed at that moment,
# which on a shared host differ (bench/peers/results/history.md, "What the host gives two
# threads").
#   scripts/parallel-series.sh [RUNS (10)] [OUT_DIR (a new temporary folder)]
# Every run's CSVs stay in OUT_DIR (series-rounds.csv: all rounds, a column for the run); needs
# build/bin/s2sim-peers and two hardware threads.
set -euo pipefail
cd "$(dirname "$0")/.."
runs=${1:-10}
out=${2:-$(mktemp -d /tmp/s2sim-parallel-series.XXXXXX)}
[[ "$runs" =~ ^[1-9][0-9]*$ ]] || { echo "parallel-series: RUNS must be a whole number of at least 1, got '$runs'" >&2; exit 2; }
peers=build/bin/s2sim-peers
[ -x "$peers" ] || { echo "parallel-series: $peers not built (cmake --build build --target s2sim-peers)" >&2; exit 2; }
[ "$(nproc)" -ge 2 ] || { echo "parallel-series: one hardware thread: nothing to run in parallel" >&2; exit 2; }
mkdir -p "$out"
for ((k = 1; k <= runs; ++k)); do
  "$peers" --scenes robots_16,robots_64 --duration 1 --warmup 0.2 --rounds 5 \
    --engines s2sim,s2sim-par2,s2sim-par2-lockstep,s2sim-copies2 \
    --csv "$out/run-$k.csv" --rounds-csv "$out/run-$k-rounds.csv" > "$out/run-$k.md" 2> /dev/null
done
{
  echo "run,$(head -1 "$out/run-1-rounds.csv")"
  for ((k = 1; k <= runs; ++k)); do tail -n +2 "$out/run-$k-rounds.csv" | sed "s/^/$k,/"; done
} > "$out/series-rounds.csv"
if command -v taskset > /dev/null; then
  for ((k = 1; k <= runs; ++k)); do
    for cpu in 0 1; do
      taskset -c "$cpu" "$peers" --scenes robots_16 --duration 1 --warmup 0.2 --rounds 5 \
        --engines s2sim --csv "$out/vcpu$cpu-$k.csv" > /dev/null 2>&1 &
    done
    wait
  done
fi
python3 - "$out" "$runs" <<'EOF'
import csv, statistics, sys
out, runs = sys.argv[1], int(sys.argv[2])
rows = {}
for k in range(1, runs + 1):
    with open(f"{out}/run-{k}.csv") as f:
        for r in csv.DictReader(f):
            rows[(k, r["scene"], r["engine"])] = r
def value(k, scene, engine, column):
    r = rows.get((k, scene, engine))
    return float(r[column]) if r and r[column] not in ("", "nan") else float("nan")
for scene in ("robots_16", "robots_64"):
    print(f"\n{scene}\n")
    print("| run | par2 | lockstep | ceiling (copies2) | par2 / ceiling | serial / par2 wall µs | steal % par2 / copies2 |")
    print("|---:|---:|---:|---:|---:|---:|---:|")
    par, share, reached, near, low_ceiling = [], [], 0, 0, 0
    for k in range(1, runs + 1):
        p = value(k, scene, "s2sim-par2", "s2sim_speedup")
        l = value(k, scene, "s2sim-par2-lockstep", "s2sim_speedup")
        c = value(k, scene, "s2sim-copies2", "s2sim_speedup")
        w = value(k, scene, "s2sim", "wall_us_median")
        wp = value(k, scene, "s2sim-par2", "wall_us_median")
        sp = value(k, scene, "s2sim-par2", "largest_vcpu_steal_pct_median")
        sc = value(k, scene, "s2sim-copies2", "largest_vcpu_steal_pct_median")
        par.append(p); share.append(p / c)
        reached += p >= 1.6; near += p / c >= 0.9; low_ceiling += c < 1.6
        print(f"| {k} | {p:.2f}× | {l:.2f}× | {c:.2f}× | {p / c:.3f} | {w:.1f} / {wp:.1f} | {sp:.1f} / {sc:.1f} |")
    print(f"\nmedian par2 {statistics.median(par):.2f}×, {reached} of {runs} runs at 1.6× or more;"
          f" par2 / ceiling median {statistics.median(share):.3f}, {near} of {runs} at 0.9 or more;"
          f" the host's own ceiling below 1.6× in {low_ceiling} of {runs} (no parallel step reaches"
          f" 1.6× there)")
import os
if os.path.exists(f"{out}/vcpu0-1.csv"):
    print("\nrobots_16 serial, pinned to each vCPU at once (wall µs a step, median of five rounds)\n")
    print("| run | vCPU 0 | vCPU 1 | slower / faster |")
    print("|---:|---:|---:|---:|")
    for k in range(1, runs + 1):
        t = []
        for cpu in (0, 1):
            with open(f"{out}/vcpu{cpu}-{k}.csv") as f:
                t.append(float(next(csv.DictReader(f))["wall_us_median"]))
        print(f"| {k} | {t[0]:.1f} | {t[1]:.1f} | {max(t) / min(t):.2f} |")
print(f"\nCSVs: {out}")
EOF
