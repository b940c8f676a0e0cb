"""Client of S2Sim's ``remote`` controller (docs/remote.md), in pure Python.

No compiled code and no dependency beyond the standard library: copy this file to any machine
that can reach the simulation. Protocol version 1: a 16-byte little-endian header (magic
``S2SR``, version, type, sequence number, payload length) and a payload of little-endian doubles.

Lock-step (the simulation waits for each request)::

    with Client(port=9808) as link:
        link.hello()                     # names, units, mode
        t, y = link.observe()            # signals now, without advancing
        t, y = link.step([force])        # inputs applied, one control period later

Real-time (the simulation never waits)::

    link.send([force])                   # applied at the next control period
    t, y = link.receive()                # the newest signals the simulation sent

When the run ends (``--duration``, a closed viewer) the simulation sends END: the waiting call
raises ``RunEnded`` (a ``RemoteError``), so a loop ``while True: link.step(...)`` stops::

    try:
        while True:
            t, y = link.step(controller(y))
    except RunEnded:
        pass
"""

import hashlib
import hmac
import socket
import struct

MAGIC = b"S2SR"
VERSION = 1
HEADER = struct.Struct("<4sHHII")  # magic, version, type, sequence, payload length
HEADER_SIZE = HEADER.size  # 16
DEFAULT_PORT = 9808
MAX_DATAGRAM = 65507

HELLO, DESCRIBE, INPUTS, OBSERVE, SIGNALS, BUSY, BYE, END = 1, 2, 3, 4, 5, 6, 7, 8
TAG_SIZE = 32  # HMAC-SHA256 after the payload, on a link with a key_file
MIN_KEY_BYTES = 16


def read_key(path):
    """The key of a key file as the link reads it: its bytes less one trailing newline."""
    with open(path, "rb") as f:
        key = f.read()
    if key.endswith(b"\n"):
        key = key[:-1]
    if len(key) < MIN_KEY_BYTES:
        raise ValueError("the key file '%s' holds %d bytes; a key needs at least %d" %
                         (path, len(key), MIN_KEY_BYTES))
    return key


def tag(key, data):
    """The HMAC-SHA256 of ``data`` with ``key``: what a keyed link appends to each datagram."""
    return hmac.new(key, data, hashlib.sha256).digest()


class RemoteError(RuntimeError):
    """The simulation did not answer in time, or answered something unexpected."""


class RunEnded(RemoteError):
    """The simulation's run is over (an END datagram): no reply will come. ``time`` is the
    simulated time of the link's last control period [s]."""

    def __init__(self, time, text):
        super().__init__("the simulation ended at t = %.6g s (%s)" % (time, text))
        self.time = time


def pack(msg_type, sequence, payload=b"", key=None):
    """One datagram: the header, then the payload bytes (then their tag, with a key)."""
    datagram = HEADER.pack(MAGIC, VERSION, msg_type, sequence & 0xFFFFFFFF, len(payload)) + payload
    return datagram + tag(key, datagram) if key else datagram


def pack_doubles(values):
    return struct.pack("<%dd" % len(values), *values)


def unpack(datagram, key=None):
    """(type, sequence, payload) of a well-formed datagram (whose tag is right, with a key),
    else None."""
    if key:
        if len(datagram) < TAG_SIZE or not hmac.compare_digest(
                tag(key, datagram[:-TAG_SIZE]), datagram[-TAG_SIZE:]):
            return None
        datagram = datagram[:-TAG_SIZE]
    if len(datagram) < HEADER_SIZE:
        return None
    magic, version, msg_type, sequence, length = HEADER.unpack_from(datagram)
    if magic != MAGIC or version != VERSION or length != len(datagram) - HEADER_SIZE:
        return None
    return msg_type, sequence, datagram[HEADER_SIZE:]


class Description:
    """What a DESCRIBE reply says: the mode, the period and the served names and units."""

    def __init__(self, text):
        self.mode = None
        self.period = None
        self.inputs, self.input_units = [], []
        self.signals, self.signal_units = [], []
        for line in text.splitlines():
            words = line.split(" ")
            if words[0] == "mode":
                self.mode = words[1]
            elif words[0] == "period":
                self.period = None if words[1] == "control" else float(words[1])
            elif words[0] == "input":
                self.inputs.append(words[1])
                self.input_units.append(words[2] if len(words) > 2 else "")
            elif words[0] == "signal":
                self.signals.append(words[1])
                self.signal_units.append(words[2] if len(words) > 2 else "")

    def __repr__(self):
        return "Description(mode=%r, inputs=%r, signals=%r)" % (self.mode, self.inputs, self.signals)


class Client:
    """A UDP client of one ``remote`` controller at ``host``:``port``. ``key`` (bytes, or
    ``read_key(path)``) signs every request and checks every reply, for a link whose scene
    sets ``key_file``."""

    def __init__(self, port=DEFAULT_PORT, host="127.0.0.1", timeout=5.0, key=None):
        self.address = (host, port)
        self.key = key
        self.timeout = timeout
        self.sequence = 0
        self.description = None
        self.socket = socket.socket(socket.AF_INET, socket.SOCK_DGRAM)

    def close(self):
        """Ends the session (BYE: the link serves the next client at once) and the socket."""
        try:
            self._request(BYE)
        except OSError:
            pass
        self.socket.close()

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self.close()

    def _request(self, msg_type, payload=b""):
        self.sequence += 1
        self.socket.sendto(pack(msg_type, self.sequence, payload, self.key), self.address)
        return self.sequence

    def _wait(self, want_type, sequence, timeout):
        self.socket.settimeout(self.timeout if timeout is None else timeout)
        while True:
            try:
                datagram = self.socket.recv(MAX_DATAGRAM + 1)
            except socket.timeout:
                raise RemoteError("no reply from %s:%d within %.3g s" %
                                  (self.address + (self.socket.gettimeout(),))) from None
            message = unpack(datagram, self.key)
            if message is None:
                continue
            msg_type, seq, payload = message
            if msg_type == END:
                self._ended(payload)
            if msg_type == BUSY and (sequence is None or seq == sequence):
                raise RemoteError("%s:%d is busy: %s" % (self.address + (
                    payload.decode(errors="replace"),)))
            if msg_type == want_type and (sequence is None or seq == sequence):
                return seq, payload

    @staticmethod
    def _ended(payload):
        if len(payload) < 8:
            raise RemoteError("a malformed END datagram (%d bytes of payload)" % len(payload))
        raise RunEnded(struct.unpack_from("<d", payload)[0], payload[8:].decode(errors="replace"))

    @staticmethod
    def _signals(payload):
        values = struct.unpack("<%dd" % (len(payload) // 8), payload)
        return values[0], list(values[1:])

    def hello(self, timeout=None):
        """Announces this client; returns the Description (also kept in .description)."""
        seq = self._request(HELLO)
        _, payload = self._wait(DESCRIBE, seq, timeout)
        self.description = Description(payload.decode("utf-8"))
        return self.description

    def observe(self, timeout=None):
        """(time [s], signal values) now, without advancing the simulation."""
        seq = self._request(OBSERVE)
        return self._signals(self._wait(SIGNALS, seq, timeout)[1])

    def send(self, inputs):
        """Sends input values (one per served input, in order); returns the sequence number."""
        return self._request(INPUTS, pack_doubles([float(v) for v in inputs]))

    def step(self, inputs, timeout=None, retries=0):
        """Lock-step: applies the inputs and returns (time, signals) one control period later.
        With retries > 0 a lost request or reply is sent again with the same sequence number
        (the simulation answers it without advancing twice)."""
        payload = pack_doubles([float(v) for v in inputs])
        seq = self._request(INPUTS, payload)
        for attempt in range(retries + 1):
            try:
                return self._signals(self._wait(SIGNALS, seq, timeout)[1])
            except RunEnded:
                raise
            except RemoteError:
                if attempt == retries:
                    raise
                self.socket.sendto(pack(INPUTS, seq, payload, self.key), self.address)

    def receive(self, timeout=None):
        """Real-time: the newest SIGNALS datagram waiting (or the next one to come)."""
        _, payload = self._wait(SIGNALS, None, timeout)
        self.socket.setblocking(False)
        try:  # drain: keep only the newest
            while True:
                message = unpack(self.socket.recv(MAX_DATAGRAM + 1), self.key)
                if message and message[0] == SIGNALS:
                    payload = message[2]
                elif message and message[0] == END:
                    self._ended(message[2])
        except (BlockingIOError, socket.timeout):
            pass
        finally:
            self.socket.setblocking(True)
        return self._signals(payload)
