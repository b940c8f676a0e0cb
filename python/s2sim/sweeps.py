"""Parameter sweeps on Dask (docs/python.md, "Sweeps").

``sweep(scene, grid_or_samples, run=..., workers=N)`` runs one independent simulation per
parameter set, on a Dask ``LocalCluster`` of ``workers`` processes by default or on an existing
scheduler (``scheduler="tcp://host:8786"``), and returns one row per run: a pandas DataFrame
when pandas is installed, else a list of dicts. Every row records the run's ``seed`` and its
parameters, so that ``run_one(scene, row, run)`` repeats it exactly.

A parameter whose name contains ``/`` is an input, set before ``run`` is called
(``robots/nxt/axes/left/ref_voltage``); any other is a scene constant, as ``--define`` (an
``<arg>`` of the scene or of a robot file).

The scene travels with the tasks: ``scene_bundle`` reads the scene's folder (every file under
it) once, the workers receive it and write it to a temporary folder of their own, so that a
worker needs only the s2sim package, not the scene's path. ``start=snapshot`` starts every run
from a snapshot (``Simulation.save()``, pickled to the workers) instead of t = 0.
"""

import atexit
import hashlib
import itertools
import os
import shutil
import sys
import tempfile

#: The largest scene folder a bundle carries (a larger one is a mistake, e.g. a home folder).
MAX_BUNDLE_BYTES = 64 * 1024 * 1024


def scene_bundle(scene):
    """The scene as data: ``{"name": folder name, "entry": scene file or None, "files":
    {relative path: bytes}}``, every file under the scene's folder (a folder, or the folder of
    a scene file). A file the scene reaches outside its folder is not carried."""
    path = os.path.abspath(os.fspath(scene))
    folder, entry = (path, None) if os.path.isdir(path) else os.path.split(path)
    if not os.path.isdir(folder) or (entry is not None and not os.path.isfile(path)):
        raise FileNotFoundError(f"scene {os.fspath(scene)!r}: no such folder or scene file")
    files, total = {}, 0
    for root, dirs, names in os.walk(folder):
        dirs[:] = sorted(d for d in dirs if not d.startswith("."))
        for name in sorted(names):
            full = os.path.join(root, name)
            if not os.path.isfile(full):
                continue
            with open(full, "rb") as f:
                data = f.read()
            total += len(data)
            if total > MAX_BUNDLE_BYTES:
                raise ValueError(f"scene folder {folder!r} holds more than "
                                 f"{MAX_BUNDLE_BYTES // (1024 * 1024)} MB: pass "
                                 "ship_scene=False and a path every worker can read")
            files[os.path.relpath(full, folder).replace(os.sep, "/")] = data
    return {"name": os.path.basename(folder), "entry": entry, "files": files}


_unpacked = {}  # bundle digest -> the scene path written in this process


def _remove_unpacked(root):
    shutil.rmtree(root, ignore_errors=True)


def scene_path(scene):
    """A path to load: ``scene`` itself (a path), or where this process wrote a bundle (once
    per bundle, in a temporary folder removed when the process ends)."""
    if not isinstance(scene, dict):
        return os.fspath(scene)
    digest = hashlib.sha256(repr((scene["name"], scene["entry"])).encode())
    for rel in sorted(scene["files"]):
        digest.update(rel.encode() + b"\0" + scene["files"][rel] + b"\0")
    key = digest.hexdigest()
    if key in _unpacked:
        return _unpacked[key]
    root = tempfile.mkdtemp(prefix=f"s2sim-{os.getpid()}-scene-")
    atexit.register(_remove_unpacked, root)
    folder = os.path.join(root, scene["name"] or "scene")
    for rel, data in scene["files"].items():
        parts = rel.split("/")
        if rel.startswith("/") or ".." in parts or not all(parts):
            raise ValueError(f"scene bundle: the file path {rel!r} leaves the scene folder")
        target = os.path.join(folder, *parts)
        os.makedirs(os.path.dirname(target), exist_ok=True)
        with open(target, "wb") as f:
            f.write(data)
    os.makedirs(folder, exist_ok=True)
    path = os.path.join(folder, scene["entry"]) if scene["entry"] else folder
    _unpacked[key] = path
    return path


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


class _Pickled:
    """A function carried as cloudpickle's bytes. Dask pickles a task's arguments with pickle,
    which names a function by its module: a worker that cannot import the module (a script, a
    test file) could not run it. cloudpickle carries such a function by value."""

    def __init__(self, function):
        import cloudpickle
        self.data = cloudpickle.dumps(function)

    def __call__(self, *args):
        import cloudpickle
        return cloudpickle.loads(self.data)(*args)


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


def run_one(scene, row, run, physics_step=None, plugin_path=(), start=None):
    """Repeats the run of one row: the same seed, inputs and constants (and the same
    snapshot ``start``, restored first), then ``run``. ``scene``: a path or a
    ``scene_bundle``. Returns the row with ``run``'s results (a dict; a plain number becomes
    ``result``)."""
    from ._s2sim import Simulation  # imported in the worker

    params = {k: v for k, v in row.items() if k != "seed"}
    defines = {k: float(v) for k, v in params.items() if "/" not in k}
    sim = Simulation(scene_path(scene), seed=int(row["seed"]), physics_step=physics_step,
                     defines=defines, plugin_path=list(plugin_path))
    if start is not None:
        sim.restore(start)  # then the row's inputs, over the snapshot's
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


#: Tasks per worker thread that ``sweep`` cuts its runs into by default: few enough that Dask's
#: own CPU time per task (about a millisecond in the client and the scheduler, as much as a
#: tenth of a short run) is shared by many runs, enough that the threads finish together.
TASKS_PER_THREAD = 4


def run_chunk(scene, rows, run, physics_step=None, plugin_path=(), start=None):
    """``run_one`` for each of ``rows`` in order, in one task: their rows with results."""
    return [run_one(scene, row, run, physics_step, plugin_path, start) for row in rows]


def tasks_of(rows, threads, runs_per_task=None):
    """The runs cut into tasks, in order: ``runs_per_task`` a task, or (None) about
    ``TASKS_PER_THREAD`` tasks for each of ``threads`` worker threads (at least one)."""
    size = runs_per_task
    if size is None:
        size = max(1, -(-len(rows) // (TASKS_PER_THREAD * max(1, threads))))
    return [rows[i:i + size] for i in range(0, len(rows), size)]


def sweep(scene, grid_or_samples, run=None, workers=2, scheduler=None, seed=1,
          duration=None, signals=None, physics_step=None, plugin_path=(), ship_scene=True,
          start=None, runs_per_task=None):
    """Runs one simulation of ``scene`` per parameter set and returns the table of results.

    grid_or_samples: a dict name -> values (the grid of every combination) or a list of dicts
        (samples, e.g. Monte-Carlo draws). A ``seed`` key sets a run's seed; otherwise run i
        gets ``seed + i``.
    run: ``run(sim, params) -> dict`` (or a number), called on the loaded simulation with its
        inputs set; default: step ``duration`` seconds and return the ``signals`` patterns.
    workers: processes of the local cluster (ignored with ``scheduler``).
    scheduler: the address of a running Dask scheduler, to run across machines (each worker
        needs S2Sim's package and the plugins the scene names).
    ship_scene: send the scene folder with the tasks (``scene_bundle``; default), or only
        its path (False: every worker must read it there).
    start: a Snapshot of this scene that every run starts from (then its row's inputs).
    runs_per_task: runs a Dask task holds, in order; default: the runs cut into about
        ``TASKS_PER_THREAD`` tasks per worker thread present when the sweep starts (1 gives
        every run its own task, so that uneven runs balance best). The rows are the same.
    """
    if runs_per_task is not None and (isinstance(runs_per_task, bool) or
                                      not isinstance(runs_per_task, int) or runs_per_task < 1):
        raise ValueError(f"sweep(): runs_per_task must be a whole number >= 1, got "
                         f"{runs_per_task!r}")
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
        # Sent once to every worker, not once per task.
        shipped = client.scatter([scene_bundle(scene)], broadcast=True)[0] if ship_scene \
            else os.fspath(scene)
        chunks = tasks_of(rows, sum(client.nthreads().values()), runs_per_task)
        k = len(chunks)
        carried = _Pickled(run)
        futures = client.map(run_chunk, [shipped] * k, chunks, [carried] * k,
                             [physics_step] * k, [tuple(plugin_path)] * k, [start] * k,
                             pure=False)
        results = [row for chunk in client.gather(futures) for row in chunk]
    finally:
        client.close()
        if cluster is not None:
            cluster.close()
    try:
        import pandas
    except ImportError:
        return results
    return pandas.DataFrame(results)
