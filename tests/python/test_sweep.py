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
