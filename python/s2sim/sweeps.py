"""Parameter sweeps on Dask (docs/python.md, "Sweeps").

``sweep(scene, grid_or_samples, run=..., workers=N)`` runs one independent simulation per
parameter set, on a Dask ``LocalCluster`` of ``workers`` processes by default or on an existing
scheduler (``scheduler="tcp://host:8786"``), and returns one row per run: a pandas DataFrame
when pandas is installed, else a list of dicts. Every row records the run's ``seed`` and its
parameters, so that ``run_one(scene, row, run)`` repeats it exactly.

A parameter whose name contains ``/`` is an input, set before ``run`` is called
(``robots/nxt/axes/left/ref_voltage``); any other is a scene constant, as ``--define`` (an
``<arg>`` of the scene or of a robot file).
"""

import itertools
import sys


def _rows(grid_or_samples):
    """The runs' parameter sets, each with its seed."""
    if isinstance(grid_or_samples, dict):  # a grid: every combination, last name fastest
        names = list(grid_or_samples)
        for values in itertools.product(*(list(grid_or_samples[n]) for n in names)):
            yield dict(zip(names, values))
    else:  # samples: one dict per run
        for sample in grid_or_samples:
            if not isinstance(sample, dict):
                raise TypeError("a sample must be a dict of parameter values, got %r" % (sample,))
            yield dict(sample)


def final_signals(patterns, duration):
    """A ``run`` that steps ``duration`` seconds and returns the signals matching ``patterns``
    (glob or name, one string or a list) by name."""
    if isinstance(patterns, str):
        patterns = [patterns]

    def run(sim, params):
        sim.run_until(duration)
        out = {}
        for pattern in patterns:
            out.update(zip(sim.signal_names(pattern), sim.signals(pattern).tolist()))
        return out

    return run


def run_one(scene, row, run, physics_step=None, plugin_path=()):
    """Repeats the run of one row: the same seed, inputs and constants, then ``run``. Returns
    the row with ``run``'s results (a dict; a plain number becomes ``result``)."""
    from ._s2sim import Simulation  # imported in the worker

    params = {k: v for k, v in row.items() if k != "seed"}
    defines = {k: float(v) for k, v in params.items() if "/" not in k}
    sim = Simulation(scene, seed=int(row["seed"]), physics_step=physics_step,
                     defines=defines, plugin_path=list(plugin_path))
    for name, value in params.items():
        if "/" in name:
            sim.set_input(name, float(value))
    result = run(sim, dict(params))
    if not isinstance(result, dict):
        result = {"result": result}
    clash = set(result) & set(row)
    if clash:
        raise ValueError("run() returned keys that are parameters: %s" % sorted(clash))
    out = dict(row)
    out.update(result)
    return out


def sweep(scene, grid_or_samples, run=None, workers=2, scheduler=None, seed=1,
          duration=None, signals=None, physics_step=None, plugin_path=()):
    """Runs one simulation of ``scene`` per parameter set and returns the table of results.

    grid_or_samples: a dict name -> values (the grid of every combination) or a list of dicts
        (samples, e.g. Monte-Carlo draws). A ``seed`` key sets a run's seed; otherwise run i
        gets ``seed + i``.
    run: ``run(sim, params) -> dict`` (or a number), called on the loaded simulation with its
        inputs set; default: step ``duration`` seconds and return the ``signals`` patterns.
    workers: processes of the local cluster (ignored with ``scheduler``).
    scheduler: the address of a running Dask scheduler, to run across machines (each worker
        needs S2Sim's package and the scene path).
    """
    if run is None:
        if duration is None or signals is None:
            raise ValueError("sweep(): give run=..., or duration= and signals=")
        run = final_signals(signals, duration)
    rows = []
    for i, params in enumerate(_rows(grid_or_samples)):
        row = {"seed": int(params.pop("seed", seed + i))}
        row.update(params)
        rows.append(row)

    import cloudpickle
    from dask.distributed import Client, LocalCluster

    # Workers import what they run by name; a function of a script or test module that they
    # cannot import travels by value instead.
    module = sys.modules.get(getattr(run, "__module__", ""), None)
    if module is not None and module.__name__ not in ("__main__", __name__) and \
            not module.__name__.startswith("s2sim."):
        cloudpickle.register_pickle_by_value(module)

    if scheduler is None:
        cluster = LocalCluster(n_workers=workers, threads_per_worker=1, processes=True,
                               dashboard_address=None)
        client = Client(cluster)
    else:
        cluster, client = None, Client(scheduler)
    try:
        futures = client.map(run_one, [str(scene)] * len(rows), rows, [run] * len(rows),
                             [physics_step] * len(rows), [tuple(plugin_path)] * len(rows),
                             pure=False)
        results = client.gather(futures)
    finally:
        client.close()
        if cluster is not None:
            cluster.close()
    try:
        import pandas
    except ImportError:
        return results
    return pandas.DataFrame(results)
