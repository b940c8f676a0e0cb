"""Reads a recording of ``s2sim-run --record FILE`` into numpy arrays (docs/recording.md).

Pure Python with numpy: no compiled module, so it reads recordings on any machine::

    from s2sim import recording
    rec = recording.read("run.s2rec")
    rec.time                     # (n,) s
    rec.position                 # (n, bodies, 3) m, world frame
    rec.quaternion               # (n, bodies, 4) w, x, y, z
    rec.angular_velocity, rec.linear_velocity   # (n, bodies, 3)
    rec.values                   # (n, signals), in rec.signals order
    rec.signal("robots/nxt/x")   # (n,)
    rec.state[k]                 # frame k's snapshot values (Simulation.save() of the run)

Errors name the file and what is wrong: ``RecordingError`` (a ``ValueError``).
"""

import struct
from urllib.parse import unquote

import numpy as np

MAGIC = b"S2SIMREC"
VERSION = 1
FRAME = b"FRME"
END = b"ENDR"
POSE_NUMBERS, TWIST_NUMBERS = 7, 6


class RecordingError(ValueError):
    """A file that is not a readable recording: the message names it and what is wrong."""


class Recording:
    """A recording in memory: header fields and one row per frame in every array."""

    def __init__(self, path, header, ticks, times, values, poses, twists, states):
        self.path = path
        self.header = header                      # every header line: key -> list of values
        self.version = int(header["s2sim-recording"][0][0])
        self.s2sim_version = header.get("s2sim", [[""]])[0][0]
        self.scene = header["scene"][0][0]
        self.tick_s = float(header["tick_s"][0][0])
        self.period_ticks = int(header["period_ticks"][0][0])
        self.bodies = [v[0] for v in header.get("body", [])]
        self.signals = [v[0] for v in header.get("signal", [])]
        self.units = [v[1] if len(v) > 1 else "" for v in header.get("signal", [])]
        self.segments = [(v[0], None if v[1] == "variable" else int(v[1]), int(v[2]))
                         for v in header.get("segment", [])]
        self.tick = ticks                         # (n,) physics steps since the start
        self.time = times                         # (n,) s
        self.values = values
        self.position = poses[:, :, 0:3]
        self.quaternion = poses[:, :, 3:7]
        self.angular_velocity = twists[:, :, 0:3]
        self.linear_velocity = twists[:, :, 3:6]
        self.state = states                       # per frame: the snapshot's numbers

    def __len__(self):
        return len(self.tick)

    def signal(self, name):
        """The values of one signal, one per frame."""
        try:
            return self.values[:, self.signals.index(name)]
        except ValueError:
            raise KeyError("%s: no signal %r was recorded" % (self.path, name)) from None

    def body(self, name):
        """The index of a body by name (robots/<robot>/solids/<id> or things/<id>)."""
        try:
            return self.bodies.index(name)
        except ValueError:
            raise KeyError("%s: no body %r was recorded" % (self.path, name)) from None

    def __repr__(self):
        return "Recording(%r, %d frames, %d bodies, %d signals)" % (
            self.path, len(self), len(self.bodies), len(self.signals))


def _fail(path, what):
    raise RecordingError("%s: %s" % (path, what))


def _parse_header(path, text):
    header = {}
    for number, line in enumerate(text.splitlines(), 1):
        words = [unquote(w) for w in line.split()]
        if not words:
            continue
        if number == 1 and words != ["s2sim-recording", str(VERSION)]:
            _fail(path, "header line 1 (%r): expected 's2sim-recording %d'" % (line, VERSION))
        header.setdefault(words[0], []).append(words[1:])
    for key in ("scene", "tick_s", "period_ticks", "layout"):
        if key not in header:
            _fail(path, "the header lacks '%s'" % key)
    if header.get("numbers", [["binary64-le"]])[0] != ["binary64-le"]:
        _fail(path, "numbers other than binary64-le are not read")
    return header


def read(path):
    """Reads the recording at ``path``; raises RecordingError naming it and the fault."""
    path = str(path)
    with open(path, "rb") as f:
        data = f.read()
    if len(data) < 16 or data[:8] != MAGIC:
        _fail(path, "not an S2Sim recording (it does not start with 'S2SIMREC'; "
                    "s2sim-run --record writes one)")
    version, text_size = struct.unpack_from("<II", data, 8)
    if version != VERSION:
        _fail(path, "recording format version %d; this reader reads version %d" %
              (version, VERSION))
    if 16 + text_size > len(data):
        _fail(path, "truncated: the header says %d bytes of text, the file ends after %d" %
              (text_size, len(data) - 16))
    header = _parse_header(path, data[16:16 + text_size].decode("utf-8"))
    nb, ns = len(header.get("body", [])), len(header.get("signal", []))
    fixed_numbers = nb * (POSE_NUMBERS + TWIST_NUMBERS) + ns
    fixed = 24 + 8 * fixed_numbers

    ticks, times, rows, states = [], [], [], []
    at, ended = 16 + text_size, False
    while at < len(data):
        frame = len(ticks)
        if len(data) - at < 16:
            _fail(path, "truncated: %d bytes after %d frames, at byte %d (a frame or the end "
                        "record needs 16 or more)" % (len(data) - at, frame, at))
        marker = data[at:at + 4]
        if marker == END:
            (count,) = struct.unpack_from("<Q", data, at + 8)
            if count != frame:
                _fail(path, "the end record counts %d frames, the file holds %d" % (count, frame))
            at += 16
            ended = True
            break
        if marker != FRAME:
            _fail(path, "byte %d: frame %d does not start with 'FRME' (a damaged file)" %
                  (at, frame))
        (state_count,) = struct.unpack_from("<I", data, at + 4)
        need = fixed + 8 * state_count
        if len(data) - at < need:
            _fail(path, "truncated: frame %d at byte %d needs %d bytes, the file ends after %d" %
                  (frame, at, need, len(data) - at))
        tick, time = struct.unpack_from("<qd", data, at + 8)
        ticks.append(tick)
        times.append(time)
        rows.append(np.frombuffer(data, dtype="<f8", count=fixed_numbers, offset=at + 24))
        states.append(np.frombuffer(data, dtype="<f8", count=state_count, offset=at + fixed))
        at += need
    if not ended:
        _fail(path, "truncated: the end record is missing after %d frames (the recording run "
                    "did not finish writing it)" % len(ticks))
    if at != len(data):
        _fail(path, "%d bytes after the end record" % (len(data) - at))
    if not ticks:
        _fail(path, "the recording holds no frame")

    table = np.array(rows, dtype=np.float64).reshape(len(ticks), fixed_numbers)
    poses = table[:, :nb * POSE_NUMBERS].reshape(len(ticks), nb, POSE_NUMBERS)
    twists = table[:, nb * POSE_NUMBERS:nb * (POSE_NUMBERS + TWIST_NUMBERS)].reshape(
        len(ticks), nb, TWIST_NUMBERS)
    values = table[:, nb * (POSE_NUMBERS + TWIST_NUMBERS):]
    return Recording(path, header, np.array(ticks, dtype=np.int64),
                     np.array(times, dtype=np.float64), values, poses, twists,
                     [s.copy() for s in states])
