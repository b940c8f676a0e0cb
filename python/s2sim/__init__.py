"""S2Sim for Python (docs/python.md).

``Simulation`` and the error classes come from the compiled module ``s2sim._s2sim``;
``s2sim.remote`` (the UDP client of the ``remote`` controller), ``s2sim.serial_link`` and
``s2sim.sweeps`` (``s2sim.sweep``) are pure Python. ``s2sim.remote`` does not need the compiled module, so it can be
copied to a machine without S2Sim.
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
    def sweep(*args, **kwargs):
        """Runs many simulations on Dask; see s2sim.sweeps.sweep."""
        from .sweeps import sweep as _sweep  # dask is imported only when sweeping
        return _sweep(*args, **kwargs)
