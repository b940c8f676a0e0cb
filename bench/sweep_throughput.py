#!/usr/bin/python3
"""Throughput of s2sim.sweep on Dask: the same sweep on a LocalCluster of 1 worker and of 2
(processes, one thread each), in one invocation (docs/python.md, "Sweeps").

    PYTHONPATH=build/python /usr/bin/python3 bench/sweep_throughput.py \\
        [--runs 200] [--duration 0.5] [--workers 1 2] [--csv FILE] [--rows-csv FILE]

Every run is scenes/nxt driven at its own voltages (sample i: right +V, left -V, V from 2 to
8 V) for --duration simulated seconds; it returns the robot's final x, y and heading. Each
cluster is started, warmed up (one untimed run per worker: the workers import s2sim and load
the plugins once), then the sweep of --runs runs is timed, from the sweep() call on the
cluster's address to its last row. Prints runs/s for each cluster and each one's ratio to the
first, with the CPU time per run spent in the workers and in this process (the local
scheduler and the client) and the ratio those CPU times allow on free cores (what the
machine's other load does not change much); --csv writes those figures, --rows-csv every
run's row for every cluster (the same rows whatever the workers: each run is deterministic).
"""

import argparse
import csv
import os
import sys
import time

import s2sim

ROOT = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..")
NXT = os.path.join(ROOT, "scenes", "nxt")
RIGHT, LEFT = "robots/nxt/axes/right/ref_voltage", "robots/nxt/axes/left/ref_voltage"
OUTPUTS = ("robots/nxt/x", "robots/nxt/y", "robots/nxt/yaw")


def samples(runs):
    """The runs' inputs: V from 2 to 8 V on the right wheel, -V on the left (straight ahead)."""
    return [{RIGHT: 2.0 + 6.0 * i / max(1, runs - 1), LEFT: -(2.0 + 6.0 * i / max(1, runs - 1))}
            for i in range(runs)]


def _process_cpu_s():
    """This process's CPU time (run on each worker by client.run)."""
    return time.process_time()


def timed_sweep(scene, workers, runs, duration):
    """Starts a LocalCluster of `workers` single-thread processes, warms it up, times the sweep.
    Returns (seconds to start the cluster, seconds of the timed sweep, CPU seconds the workers
    spent in it, CPU seconds this process (scheduler and client) spent in it, its rows)."""
    from dask.distributed import Client, LocalCluster

    t0 = time.perf_counter()
    cluster = LocalCluster(n_workers=workers, threads_per_worker=1, processes=True,
                           dashboard_address=None)
    try:
        with Client(cluster) as client:
            client.wait_for_workers(workers)
            started_s = time.perf_counter() - t0
            # One run per worker, untimed: the first import of s2sim and its plugins.
            s2sim.sweep(scene, samples(workers), duration=duration, signals=list(OUTPUTS),
                        scheduler=cluster.scheduler_address)
            workers_cpu0 = sum(client.run(_process_cpu_s).values())
            own_cpu0, t1 = time.process_time(), time.perf_counter()
            rows = s2sim.sweep(scene, samples(runs), duration=duration, signals=list(OUTPUTS),
                               scheduler=cluster.scheduler_address)
            swept_s, own_cpu_s = time.perf_counter() - t1, time.process_time() - own_cpu0
            workers_cpu_s = sum(client.run(_process_cpu_s).values()) - workers_cpu0
    finally:
        cluster.close()
    if hasattr(rows, "to_dict"):
        rows = rows.to_dict("records")
    return started_s, swept_s, workers_cpu_s, own_cpu_s, rows


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--scene", default=NXT)
    parser.add_argument("--runs", type=int, default=200)
    parser.add_argument("--duration", type=float, default=0.5,
                        help="simulated seconds per run (default 0.5)")
    parser.add_argument("--workers", type=int, nargs="+", default=[1, 2])
    parser.add_argument("--csv", help="write the throughput figures here")
    parser.add_argument("--rows-csv", help="write every run's row for every cluster here")
    args = parser.parse_args(argv)
    if args.runs < 1 or args.duration <= 0 or any(w < 1 for w in args.workers):
        parser.error("--runs >= 1, --duration > 0 and --workers >= 1")

    load = os.getloadavg()
    print(f"sweep of {args.runs} runs of {args.duration:g} s on {args.scene}; "
          f"load average before: {load[0]:.2f} {load[1]:.2f} {load[2]:.2f}", flush=True)
    figures, all_rows = [], []
    for workers in args.workers:
        started_s, swept_s, workers_cpu_s, own_cpu_s, rows = timed_sweep(
            args.scene, workers, args.runs, args.duration)
        # What the machine's cores allow, whatever else runs: the workers' CPU time per run
        # and this process's (scheduler, client) share the cores.
        run_ms, dask_ms = 1e3 * workers_cpu_s / args.runs, 1e3 * own_cpu_s / args.runs
        figures.append(dict(workers=workers, runs=args.runs, duration_s=args.duration,
                            cluster_start_s=round(started_s, 3), sweep_s=round(swept_s, 3),
                            runs_per_s=round(args.runs / swept_s, 3),
                            worker_cpu_ms_per_run=round(run_ms, 3),
                            scheduler_client_cpu_ms_per_run=round(dask_ms, 3),
                            load_average_1min=round(os.getloadavg()[0], 2)))
        all_rows.append(rows)
        print(f"{workers} worker(s): {args.runs / swept_s:7.2f} runs/s "
              f"({swept_s:.2f} s; cluster started in {started_s:.2f} s); CPU per run: "
              f"{run_ms:.2f} ms in the workers, {dask_ms:.2f} ms in the scheduler and client",
              flush=True)
    for f in figures:
        f["ratio"] = round(f["runs_per_s"] / figures[0]["runs_per_s"], 3)
    for f in figures[1:]:
        # On `cores` free cores the workers and the scheduler share them: at most
        # cores / (worker CPU + scheduler CPU) runs/s, and one worker at most 1 / worker CPU.
        w, d = f["worker_cpu_ms_per_run"], f["scheduler_client_cpu_ms_per_run"]
        w1 = figures[0]["worker_cpu_ms_per_run"]
        cores = min(os.cpu_count() or 1, f["workers"])
        ceiling = min(f["workers"] / w, cores / (w + d)) * w1 if w > 0 else float("nan")
        f["ratio_ceiling_from_cpu"] = round(ceiling, 3)
        print(f"{f['workers']} workers over {figures[0]['workers']}: {f['ratio']:.2f}x "
              f"(the CPU times allow {ceiling:.2f}x on {cores} free cores)")
    figures[0]["ratio_ceiling_from_cpu"] = 1.0
    identical = all(rows == all_rows[0] for rows in all_rows)
    print("rows identical across clusters:", "yes" if identical else "NO")

    if args.csv:
        with open(args.csv, "w", newline="") as out:
            writer = csv.DictWriter(out, fieldnames=list(figures[0]))
            writer.writeheader()
            writer.writerows(figures)
    if args.rows_csv:
        with open(args.rows_csv, "w", newline="") as out:
            names = ["workers"] + list(all_rows[0][0])
            writer = csv.DictWriter(out, fieldnames=names)
            writer.writeheader()
            for workers, rows in zip(args.workers, all_rows):
                for row in rows:
                    writer.writerow(dict(row, workers=workers))
    return 0 if identical else 1


if __name__ == "__main__":
    sys.exit(main())
