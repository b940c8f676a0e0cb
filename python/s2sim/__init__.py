"""S2Sim for Python (docs/python.md).

``Simulation``, ``Snapshot`` and the error classes come from the compiled module
``s2sim._s2sim``; ``s2sim.remote`` (the client of the ``remote`` controller), ``s2sim.sweeps``
(behind ``s2sim.sweep``), ``s2sim.snapshots`` (snapshot files) and ``s2sim.envs`` (gymnasium
environments) are pure Python. ``s2sim.remote`` needs neither the compiled module nor
anything outside the standard library, so it can be copied to a machine without S2Sim.
"""

try:
    from ._s2sim import (  # noqa: F401
        Error,
        PluginError,
        SceneError,
        Simulation,
        SimulationError,
        Snapshot,
        UsageError,
        sdk_version,
    )
except ImportError as _error:  # the remote client alone still works
    _native_error = _error

    def __getattr__(name):
        if name == "sweep":
            from .sweeps import sweep as _sweep
            return _sweep
        raise ImportError(f"s2sim.{name} needs the compiled module s2sim._s2sim: {_native_error}")
else:
    def _plugin_dirs():
        import os
        here = os.path.dirname(os.path.abspath(__file__))
        candidates = [os.path.join(here, "..", "..", "plugins"),               # build/python/s2sim
                      os.path.join(here, "..", "..", "..", "s2sim", "plugins")]  # lib/python3/...
        return [os.path.normpath(c) for c in candidates if os.path.isdir(c)]

    from ._s2sim import _set_package_plugin_dirs
    _set_package_plugin_dirs(_plugin_dirs())

    from .snapshots import load_snapshot, save_snapshot  # noqa: F401

    # snapshot.save(path) and Snapshot.load(path): the file format is s2sim/snapshots.py's.
    Snapshot.save = save_snapshot
    Snapshot.load = staticmethod(load_snapshot)

    def sweep(*args, **kwargs):
        """Runs many simulations on Dask; see s2sim.sweeps.sweep."""
        from .sweeps import sweep as _sweep  # dask is imported only when sweeping
        return _sweep(*args, **kwargs)
