"""Tacta net device client in pure Python (standard library only): bridge a real haptic device to
a Tacta simulation's `net` device over UDP. The wire format is tacta_net_protocol.h (version 1);
docs/DEVICES.md describes it. Python's loop rarely holds 1 kHz: use it for trackers, slow
devices and tests; bridge a 1 kHz arm with the C client (tacta_net_device.h).

    dev = NetDevice("127.0.0.1", 18950, Capabilities(peak_force=3.3))
    every tick:
        dev.send_state(position, velocity)
        dev.poll()
        force = dev.passivity.filter(position, velocity, dt, dev.remote_budget(), dev.force(), 3.3)
    dev.close()
"""
import math
import os
import socket
import struct
import time
from dataclasses import dataclass, field

MAGIC, VERSION = 0x54454E54, 1
HELLO, STATE, FORCE, BYE = 1, 2, 3, 4
DEFAULT_PORT = 18950
_HEADER = struct.Struct("<IHHIIQQII")  # magic, version, type, session, sequence, sender, echo, hold, size
_HELLO = struct.Struct("<10d2I")
_STATE = struct.Struct("<10d2I")
_FORCE = struct.Struct("<8diI")
_PAYLOAD = {HELLO: _HELLO.size, STATE: _STATE.size, FORCE: _FORCE.size, BYE: 0}


def now_ns():
    return time.monotonic_ns()  # CLOCK_MONOTONIC on Linux, as the C client and the plugin


@dataclass
class Capabilities:
    workspace_min: tuple = (-0.08, 0.06, -0.035)  # m
    workspace_max: tuple = (0.08, 0.18, 0.105)  # m
    peak_force: float = 3.3  # N
    continuous_force: float = 0.88  # N
    usable_stiffness: float = 1000.0  # N/m
    nominal_rate: float = 1000.0  # Hz
    dof_in: int = 6
    dof_out: int = 3


def _dot(a, b):
    return sum(x * y for x, y in zip(a, b))


def _limit(f, peak):
    """f scaled down to peak (N); a non-finite force becomes zero."""
    magnitude = math.sqrt(_dot(f, f))
    if magnitude <= peak:
        return f
    return [x * peak / magnitude for x in f] if math.isfinite(magnitude) else [0.0, 0.0, 0.0]


@dataclass
class Passivity:
    """Time-domain passivity on the delayed two-port with an exact zero-order-hold ledger, as
    tacta_net_passivity_filter in C (its comment explains the reserve)."""
    energy_in: float = 0.0  # J, exact work the hand did against the held forces
    energy_out: float = 0.0  # J, exact work the held forces did on the hand
    dissipated: float = 0.0  # J, sampled work the controller removed
    link_out: float = 0.0  # J, returned to the hand in sampled power (two-port bound)
    use_remote: bool = True
    miss: float = 0.0  # m, recent largest miss of the displacement prediction, decaying
    last: tuple = None  # (position, force, predicted displacement, v dt) of the previous tick
    curvature: tuple = (0.0, 0.0, 0.0)  # m, the previous tick's actual minus v dt

    def ledger(self):
        return self.energy_in - self.energy_out

    def filter(self, position, velocity, dt, remote_budget, desired, peak):
        if not all(math.isfinite(x) for x in position):
            self.last = None  # no position, no ledger: render nothing, restart the hold
            return [0.0, 0.0, 0.0]
        if self.last is not None:
            last_position, last_force, predicted, step = self.last
            moved = [x - y for x, y in zip(position, last_position)]
            work = _dot(last_force, moved)
            if work > 0:
                self.energy_out += work
            else:
                self.energy_in -= work
            self.miss = max(math.dist(moved, predicted), self.miss * 0.998)
            self.curvature = tuple(m - s for m, s in zip(moved, step))
        f = list(desired)
        speed2 = _dot(velocity, velocity)
        sampled = _dot(f, velocity) * dt if dt > 0 and math.isfinite(speed2) else 0.0
        if self.use_remote and sampled > remote_budget - self.link_out:  # two-port, sampled power
            excess = sampled - (remote_budget - self.link_out)
            f = [fi - excess / (speed2 * dt) * vi for fi, vi in zip(f, velocity)] if speed2 > 1e-18 else [0.0] * 3
        f = _limit(f, peak)
        step = [v * dt if dt > 0 and math.isfinite(v) else 0.0 for v in velocity]
        predicted = [s + (c if self.last is not None else 0.0) for s, c in zip(step, self.curvature)]
        own = self.ledger() if self.last is not None else -1.0  # first tick: no miss measured yet
        worst = _dot(f, predicted) + math.sqrt(_dot(f, f)) * (2.0 * self.miss + 1e-12) + 1e-15
        if worst > own:  # one-port, exact: scale down (never worse)
            f = [x * (own / worst if own > 0 else 0.0) for x in f]
        sampled = _dot(f, velocity) * dt if dt > 0 and math.isfinite(speed2) else 0.0
        self.link_out += max(sampled, 0.0)
        removed = _dot(desired, velocity) * dt - sampled
        if math.isfinite(removed) and removed > 0:
            self.dissipated += removed
        self.last = (tuple(position), tuple(f), predicted, step)
        return f


@dataclass
class NetDevice:
    host: str
    port: int = DEFAULT_PORT
    capabilities: Capabilities = field(default_factory=Capabilities)
    watchdog_s: float = 0.05

    def __post_init__(self):
        self.session = (now_ns() ^ (os.getpid() << 16)) & 0xFFFFFFFF | 1
        self.sequence = 0
        self.sock = socket.socket(socket.AF_INET6 if ":" in self.host else socket.AF_INET, socket.SOCK_DGRAM)
        self.sock.setblocking(False)
        self.peer = (self.host, self.port)
        self.passivity = Passivity()
        self.sent = self.received = self.dropped = self.malformed = 0
        self.round_trip_s = -1.0
        self._force = None  # (force, energy_returned, state)
        self._force_sequence = 0
        self._force_sender_ns = 0
        self._force_received_ns = 0
        self._last_hello_ns = 0
        self._send(HELLO, _HELLO.pack(*self.capabilities.workspace_min, *self.capabilities.workspace_max,
                                      self.capabilities.peak_force, self.capabilities.continuous_force,
                                      self.capabilities.usable_stiffness, self.capabilities.nominal_rate,
                                      self.capabilities.dof_in, self.capabilities.dof_out))

    def _send(self, kind, payload=b""):
        now = now_ns()
        self.sequence = (self.sequence + 1) & 0xFFFFFFFF
        echo, hold = 0, 0
        if self._force is not None:
            echo, hold = self._force_sender_ns, min(now - self._force_received_ns, 0xFFFFFFFF)
        header = _HEADER.pack(MAGIC, VERSION, kind, self.session, self.sequence, now, echo, hold, len(payload))
        self.sock.sendto(header + payload, self.peer)
        self.sent += 1
        if kind == HELLO:
            self._hello = payload
            self._last_hello_ns = now

    def send_state(self, position, velocity=(0.0, 0.0, 0.0), orientation=(1.0, 0.0, 0.0, 0.0), buttons=0):
        if now_ns() - self._last_hello_ns > 1_000_000_000:
            self._send(HELLO, self._hello)  # once a second, for a simulation started later
        self._send(STATE, _STATE.pack(*position, *orientation, *velocity, buttons, 0))

    def accept(self, data, now=None):
        """Handles one datagram; True when it was a new force. For tests that delay datagrams."""
        now = now_ns() if now is None else now
        if len(data) < _HEADER.size:
            self.malformed += 1
            return False
        magic, version, kind, session, sequence, sender, echo, hold, size = _HEADER.unpack_from(data)
        if (magic != MAGIC or version != VERSION or kind != FORCE or size != _FORCE.size
                or len(data) < _HEADER.size + size or session != self.session):
            self.malformed += 1
            return False
        values = _FORCE.unpack_from(data, _HEADER.size)
        if not all(math.isfinite(v) for v in values[:8]):
            self.malformed += 1
            return False
        ahead = (sequence - self._force_sequence) & 0xFFFFFFFF
        if self._force is not None and (ahead == 0 or ahead >= 0x80000000):
            self.dropped += 1  # duplicate or older
            return False
        self._force = (values[0:3], values[6], values[8])
        self._force_sequence, self._force_sender_ns, self._force_received_ns = sequence, sender, now
        if echo and now > echo + hold:
            self.round_trip_s = (now - echo - hold) * 1e-9
        self.received += 1
        return True

    def poll(self):
        accepted = 0
        while True:
            try:
                data = self.sock.recv(512)
            except BlockingIOError:
                return accepted
            accepted += self.accept(data)

    def live(self):
        return (self._force is not None and self._force[2] == 0
                and (now_ns() - self._force_received_ns) * 1e-9 <= self.watchdog_s)

    def force(self):
        """N: the newest force, or zero when the simulation is silent or not answering."""
        return list(self._force[0]) if self.live() else [0.0, 0.0, 0.0]

    def remote_budget(self):
        return self._force[1] if self._force is not None else 0.0

    def close(self):
        self._send(BYE)
        self.sock.close()
