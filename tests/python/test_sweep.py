"""s2sim.sweep on Dask: a 2-worker local cluster, an existing scheduler, reproducible rows."""

import os

import pytest

import s2sim
from s2sim.sweeps import run_one

SOURCE = os.environ.get("S2SIM_SOURCE_DIR", os.getcwd())
NXT = os.path.join(SOURCE, "scenes", "nxt")
RIGHT, LEFT = "robots/nxt/axes/right/ref_voltage", "robots/nxt/axes/left/ref_voltage"


def distance_in_half_a_second(sim, params):
    sim.set_input(LEFT, -sim.input(RIGHT))
    sim.run_until(0.5)
    return {"x": sim.signal("robots/nxt/x"), "pid": os.getpid()}


def rows_of(table):
    return table.to_dict("records") if hasattr(table, "to_dict") else table


def test_two_worker_local_sweep_records_seed_and_parameters_and_repeats():
    grid = {"motor_ki": [0.45, 0.4908], RIGHT: [3.0, 6.0]}
    table = rows_of(s2sim.sweep(NXT, grid, run=distance_in_half_a_second, workers=2, seed=10))
    assert len(table) == 4
    assert [r["seed"] for r in table] == [10, 11, 12, 13]
    assert [(r["motor_ki"], r[RIGHT]) for r in table] == [
        (0.45, 3.0), (0.45, 6.0), (0.4908, 3.0), (0.4908, 6.0)]
    assert len({r["pid"] for r in table}) == 2, "not two worker processes"
    assert table[1]["x"] > table[0]["x"] > 0  # more voltage, farther
    assert table[1]["x"] != table[3]["x"]  # the constant reached the motor
    for row in table:  # every row repeats from itself
        params = {k: v for k, v in row.items() if k not in ("x", "pid")}
        again = run_one(NXT, params, distance_in_half_a_second)
        assert again["x"] == row["x"]


def test_samples_on_an_existing_scheduler_with_the_default_run():
    from dask.distributed import LocalCluster

    with LocalCluster(n_workers=1, processes=False, dashboard_address=None) as cluster:
        samples = [{"seed": 5, RIGHT: 6.0}, {"seed": 6, RIGHT: -6.0}]
        table = rows_of(s2sim.sweep(NXT, samples, duration=0.3, signals=["robots/nxt/x"],
                                    scheduler=cluster.scheduler_address))
    assert [r["seed"] for r in table] == [5, 6]
    assert table[0]["robots/nxt/x"] != table[1]["robots/nxt/x"]


def test_bad_arguments():
    with pytest.raises(ValueError):
        s2sim.sweep(NXT, {"motor_ki": [1]})
    with pytest.raises(TypeError):
        s2sim.sweep(NXT, [1, 2], duration=0.1, signals="time")
    for bad in (0, -2, 1.5, True, "3"):
        with pytest.raises(ValueError, match="runs_per_task must be a whole number >= 1"):
            s2sim.sweep(NXT, [{RIGHT: 1.0}], duration=0.1, signals="time", runs_per_task=bad)


def test_runs_are_cut_into_four_tasks_a_worker_thread_unless_told():
    from s2sim.sweeps import tasks_of

    runs = list(range(200))
    assert [len(t) for t in tasks_of(runs, 2)] == [25] * 8
    assert [len(t) for t in tasks_of(runs, 1)] == [50] * 4
    assert [len(t) for t in tasks_of(runs, 0)] == [50] * 4  # no worker yet: as one
    assert [len(t) for t in tasks_of(runs[:7], 2)] == [1] * 7
    assert [len(t) for t in tasks_of(runs[:7], 2, runs_per_task=3)] == [3, 3, 1]
    assert [x for t in tasks_of(runs, 3) for x in t] == runs
    assert tasks_of([], 2) == []


def test_runs_grouped_into_tasks_give_the_same_rows_in_input_order():
    """Seven runs one per task, three per task (the last task holds one) and as sweep() cuts
    them: the same rows, in the samples' order, each run repeating from its row."""
    from dask.distributed import LocalCluster

    samples = [{RIGHT: 1.0 + i} for i in range(7)]
    with LocalCluster(n_workers=2, threads_per_worker=1, processes=True,
                      dashboard_address=None) as cluster:
        tables = [rows_of(s2sim.sweep(NXT, samples, duration=0.1, signals=["robots/nxt/x"],
                                      scheduler=cluster.scheduler_address, runs_per_task=size))
                  for size in (1, 3, None)]
    assert [r[RIGHT] for r in tables[0]] == [1.0 + i for i in range(7)]
    assert [r["seed"] for r in tables[0]] == list(range(1, 8))
    assert tables[1] == tables[0] and tables[2] == tables[0]
    assert len({r["robots/nxt/x"] for r in tables[0]}) == 7
    again = run_one(NXT, {"seed": 7, RIGHT: 7.0}, s2sim.sweeps.final_signals(
        ["robots/nxt/x"], 0.1))
    assert again["robots/nxt/x"] == tables[2][6]["robots/nxt/x"]


def where_and_how_far(sim, params):
    sim.run_until(sim.time + 0.3)
    return {"x": sim.signal("robots/nxt/x"), "cwd": os.getcwd(), "time": sim.time}


@pytest.fixture
def worker_elsewhere(tmp_path):
    """A scheduler in this process and one worker process started in an empty folder, where
    `scenes/nxt` is not (the worker has only the package, through PYTHONPATH)."""
    import subprocess
    import sys

    from dask.distributed import Client, LocalCluster

    elsewhere = tmp_path / "elsewhere"
    elsewhere.mkdir()
    # tcp on the loopback: the worker is another process (an in-process cluster talks inproc).
    cluster = LocalCluster(n_workers=0, processes=False, protocol="tcp", host="127.0.0.1",
                           dashboard_address=None)
    env = dict(os.environ)  # the package only; absolute, since the worker's cwd is elsewhere
    env["PYTHONPATH"] = os.pathsep.join(os.path.abspath(p) for p in
                                        env.get("PYTHONPATH", "").split(os.pathsep) if p)
    worker = subprocess.Popen(
        [sys.executable, "-m", "distributed.cli.dask_worker", cluster.scheduler_address,
         "--nworkers", "1", "--nthreads", "1", "--no-dashboard", "--no-nanny",
         "--local-directory", str(elsewhere)],
        cwd=str(elsewhere), env=env, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    try:
        with Client(cluster.scheduler_address) as client:
            client.wait_for_workers(1, timeout=60)
        yield cluster.scheduler_address, str(elsewhere)
    finally:
        worker.terminate()
        worker.wait(timeout=30)
        cluster.close()


def test_the_scene_and_a_snapshot_travel_to_a_worker_started_in_another_folder(worker_elsewhere):
    address, elsewhere = worker_elsewhere
    relative = os.path.relpath(NXT)  # scenes/nxt from the source tree, where this test runs
    assert not os.path.isabs(relative)
    assert not os.path.exists(os.path.join(elsewhere, relative))
    # The path alone does not reach that worker: the old behaviour, kept as ship_scene=False.
    with pytest.raises(Exception, match="not found|no such|No such|does not exist"):
        s2sim.sweep(relative, [{RIGHT: 3.0}], run=where_and_how_far, scheduler=address,
                    ship_scene=False)
    # A run started here, stopped at 0.4 s, continued there from its snapshot.
    local = s2sim.Simulation(NXT, seed=9)
    local.set_inputs({RIGHT: 6.0, LEFT: -6.0})
    local.run_until(0.4)
    snapshot = local.save()
    local.set_input(RIGHT, 4.0)
    local.run_until(0.7)
    table = rows_of(s2sim.sweep(relative, [{"seed": 9, RIGHT: 4.0}], run=where_and_how_far,
                                scheduler=address, start=snapshot))
    assert table[0]["cwd"] == elsewhere
    assert table[0]["time"] == local.time
    assert table[0]["x"] == local.signal("robots/nxt/x")  # bit for bit


def test_a_scene_bundle_carries_the_folder_and_refuses_paths_that_leave_it(tmp_path):
    from s2sim.sweeps import scene_bundle, scene_path

    bundle = scene_bundle(os.path.join(NXT, "scene.xml"))
    assert bundle["entry"] == "scene.xml" and set(bundle["files"]) == {"scene.xml", "nxt.xml"}
    path = scene_path(bundle)
    assert path.endswith(os.path.join("nxt", "scene.xml")) and os.path.isfile(path)
    assert scene_path(bundle) == path  # written once per process
    assert s2sim.Simulation(path).body_names() == s2sim.Simulation(NXT).body_names()
    with pytest.raises(ValueError, match="leaves the scene folder"):
        scene_path({"name": "x", "entry": None, "files": {"../evil.xml": b""}})
    with pytest.raises(FileNotFoundError, match="no such folder"):
        scene_bundle(tmp_path / "missing")


def test_the_throughput_benchmark_gives_the_same_rows_on_one_worker_and_on_two(tmp_path):
    """bench/sweep_throughput.py: every run's row is the same whichever cluster ran it (its
    timings are the benchmark's business, not checked here)."""
    import csv
    import importlib.util

    import sys

    spec = importlib.util.spec_from_file_location(
        "sweep_throughput", os.path.join(SOURCE, "bench", "sweep_throughput.py"))
    bench = importlib.util.module_from_spec(spec)
    writes_bytecode, sys.dont_write_bytecode = sys.dont_write_bytecode, True  # not in bench/
    try:
        spec.loader.exec_module(bench)
    finally:
        sys.dont_write_bytecode = writes_bytecode
    rows_csv, figures_csv = tmp_path / "rows.csv", tmp_path / "figures.csv"
    assert bench.main(["--runs", "6", "--duration", "0.1", "--workers", "1", "2",
                       "--rows-csv", str(rows_csv), "--csv", str(figures_csv)]) == 0
    with open(rows_csv) as f:
        rows = list(csv.DictReader(f))
    by_workers = {w: [{k: v for k, v in r.items() if k != "workers"} for r in rows
                      if r["workers"] == w] for w in ("1", "2")}
    assert len(by_workers["1"]) == 6
    assert by_workers["1"] == by_workers["2"]
    assert [r["seed"] for r in by_workers["1"]] == [str(s) for s in range(1, 7)]
    assert len({r["robots/nxt/x"] for r in by_workers["1"]}) == 6  # each run its own voltage
    with open(figures_csv) as f:
        assert [r["workers"] for r in csv.DictReader(f)] == ["1", "2"]
