"""Snapshots on disk: ``save_snapshot(snapshot, path)`` and ``load_snapshot(path)``
(docs/python.md, "Snapshots").

The file is a NumPy ``.npz`` archive read with ``allow_pickle=False`` (loading a file runs no
code): ``format`` (1), ``layout`` (the layout id, uint64), ``time`` (s), ``segment_names``,
``segment_sizes`` and ``segment_units`` (the layout, in order) and ``values`` (float64, every
segment one after another). A loaded snapshot restores bit for bit into a simulation of the
same scene with the same options (``Simulation.restore`` names the first segment that differs
otherwise).
"""

import numpy as np

FORMAT = 1


def save_snapshot(snapshot, path):
    """Writes ``snapshot`` to ``path`` (exactly that name: no suffix is added)."""
    segments = snapshot.segments
    values = np.frombuffer(snapshot.value_bytes, dtype=np.float64)
    with open(path, "wb") as file:
        np.savez(file, format=np.int64(FORMAT), layout=np.uint64(snapshot.layout),
                 time=np.float64(snapshot.time),
                 segment_names=np.array([s[0] for s in segments], dtype=str),
                 segment_sizes=np.array([s[1] for s in segments], dtype=np.uint64),
                 segment_units=np.array([s[2] for s in segments], dtype=np.uint64),
                 values=values)


def load_snapshot(path):
    """The snapshot that ``save_snapshot`` wrote to ``path``."""
    from ._s2sim import Snapshot, UsageError

    try:
        with np.load(path, allow_pickle=False) as archive:
            fields = {name: archive[name] for name in archive.files}
    except (OSError, ValueError) as error:
        raise UsageError(f"{path}: not a snapshot file ({error})") from None
    wanted = ("format", "layout", "time", "segment_names", "segment_sizes", "segment_units",
              "values")
    missing = [name for name in wanted if name not in fields]
    if missing:
        raise UsageError(f"{path}: not a snapshot file (no {', '.join(missing)})")
    if int(fields["format"]) != FORMAT:
        raise UsageError(f"{path}: snapshot format {int(fields['format'])}, this version reads "
                         f"format {FORMAT}")
    values = fields["values"]
    if values.dtype != np.float64 or values.ndim != 1:
        raise UsageError(f"{path}: the values must be a 1-D float64 array, got {values.dtype} "
                         f"of shape {values.shape}")
    names, sizes, units = fields["segment_names"], fields["segment_sizes"], fields["segment_units"]
    if not len(names) == len(sizes) == len(units):
        raise UsageError(f"{path}: the segments' names, sizes and units differ in length")
    segments = [(str(n), int(s), int(u)) for n, s, u in zip(names, sizes, units)]
    return Snapshot._from_parts(int(fields["layout"]), segments,
                                np.ascontiguousarray(values).tobytes(), float(fields["time"]))
