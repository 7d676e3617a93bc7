"""Checking a Dask scheduler address before anything depends on it.

``distributed.Client(address, timeout=30)`` bounds only the TCP connect: the comm handshake that
follows waits without a limit (a server that accepts and never speaks — an idle port, a TLS or
SSH endpoint — hangs the client for ever), and the handshake's first 8 bytes are read as a frame
length and allocated (an HTTP server's ``b"HTTP/1.1"`` is a 3.07 EiB ``MemoryError``).

:func:`check_scheduler` bounds every step and refuses with a
:class:`~fpucore.errors.ParameterError` naming the address and the reason:

1. the address is parsed without any traffic: ``tcp://HOST:PORT`` (port in [1, 65535]);
2. a raw TCP connection (``socket.create_connection``) must open, and the peer must send a Dask
   comm handshake — one frame block of at most :data:`MAX_HANDSHAKE` bytes — within the timeout;
3. only then ``distributed``'s own comm asks ``{"op": "identity"}``: the peer must say it is a
   ``Scheduler`` (a worker or nanny also speaks the protocol) and have at least one worker
   (tasks sent to a scheduler without workers wait for ever).

The steps share one deadline and run in a daemon thread joined with it, so even a name lookup
that blocks (``getaddrinfo`` has no timeout) cannot hold the caller longer than ``timeout``.
"""

from __future__ import annotations

import asyncio
import socket
import struct
import threading
import time

from fpucore.errors import ParameterError, import_extra

PROBE_TIMEOUT = 5.0  # s, the whole check; a healthy scheduler on a LAN answers in milliseconds
MAX_HANDSHAKE = 1 << 20  # bytes; Dask's handshake is ~100 bytes of msgpack
VALID = "a Dask scheduler address tcp://HOST:PORT"
REACHABLE = "a Dask scheduler answering at tcp://HOST:PORT"


def parse_scheduler_address(address: str, name: str = "scheduler") -> tuple[str, int]:
    """(host, port) of ``tcp://HOST:PORT`` (IPv6 hosts in brackets), without any traffic."""
    if not isinstance(address, str):
        raise ParameterError(name, address, VALID, "not a string")
    scheme, sep, rest = address.strip().partition("://")
    if not sep or scheme != "tcp":
        raise ParameterError(name, address, VALID, "only the tcp:// protocol is supported")
    host, sep, port_text = rest.rpartition(":")
    if host.startswith("[") and host.endswith("]"):
        host = host[1:-1]
    if not sep or not host or "/" in host or " " in host:
        raise ParameterError(name, address, VALID, "no HOST:PORT after tcp://")
    if not port_text.isdigit() or not 1 <= int(port_text) <= 65535:
        raise ParameterError(name, address, VALID, f"port {port_text!r} is not in [1, 65535]")
    return host, int(port_text)


def _recv_exactly(sock: socket.socket, n: int, deadline: float) -> bytes:
    buf = bytearray()
    while len(buf) < n:
        sock.settimeout(max(deadline - time.monotonic(), 1e-3))
        chunk = sock.recv(min(n - len(buf), 65536))
        if not chunk:
            raise ConnectionError("the peer closed the connection")
        buf += chunk
    return bytes(buf)


def _raw_handshake(host: str, port: int, deadline: float) -> None:
    """Connect and read the peer's first frame block; raises ``_Refused`` with the reason."""
    try:
        sock = socket.create_connection((host, port), timeout=max(deadline - time.monotonic(), 0))
    except OSError as exc:
        raise _Refused(f"cannot connect: {exc.strerror or exc}") from None
    with sock:
        try:
            (n,) = struct.unpack("<Q", _recv_exactly(sock, 8, deadline))
            if not 0 < n <= MAX_HANDSHAKE:
                raise _Refused(
                    f"not a Dask scheduler: its first message announces {n} bytes, "
                    "not a Dask handshake"
                )
            _recv_exactly(sock, n, deadline)
        except TimeoutError:
            raise _Refused("not a Dask scheduler: no handshake within the timeout") from None
        except OSError as exc:
            raise _Refused(
                f"not a Dask scheduler: {exc.strerror or exc} during the handshake"
            ) from None


async def _identity(address: str, deadline: float) -> dict:
    # ~1 s import: only when a scheduler is used
    connect = import_extra("distributed.comm", "atlas", "a Dask scheduler").connect

    comm = await connect(address, timeout=max(deadline - time.monotonic(), 0.1))
    try:
        await comm.write({"op": "identity", "reply": True})
        return await comm.read()
    finally:
        comm.abort()


def _identity_bounded(address: str, deadline: float) -> dict:
    try:
        reply = asyncio.run(
            asyncio.wait_for(_identity(address, deadline), max(deadline - time.monotonic(), 0.1))
        )
    except TimeoutError:
        raise _Refused("not a Dask scheduler: no answer to 'identity' in time") from None
    except Exception as exc:  # noqa: BLE001  (any failure of the protocol is the answer)
        raise _Refused(f"not a Dask scheduler: {type(exc).__name__}: {exc}") from None
    if not isinstance(reply, dict):
        raise _Refused("not a Dask scheduler: its identity is not a mapping")
    return reply


class _Refused(Exception):
    """The reason a probe step failed (turned into the ParameterError by check_scheduler)."""


def check_scheduler(address: str, timeout: float = PROBE_TIMEOUT, name: str = "scheduler") -> dict:
    """Refuse ``address`` unless a Dask scheduler with workers answers there within ``timeout``
    seconds (see the module doc).  Returns the scheduler's identity (``n_workers``, ...)."""
    host, port = parse_scheduler_address(address, name)
    deadline = time.monotonic() + timeout
    outcome: dict = {}

    def probe() -> None:
        try:
            _raw_handshake(host, port, deadline)
            outcome["identity"] = _identity_bounded(address, deadline)
        except _Refused as exc:
            outcome["reason"] = str(exc)
        except BaseException as exc:  # noqa: BLE001  (e.g. MemoryError: reported, not raised)
            outcome["reason"] = f"{type(exc).__name__}: {exc}"

    t = threading.Thread(target=probe, name="fpucore-scheduler-probe", daemon=True)
    t.start()
    t.join(timeout + 0.5)  # the steps bound themselves; this bounds a blocking name lookup
    if t.is_alive():
        outcome.setdefault("reason", f"no answer within {timeout:g} s")
    if "reason" in outcome:
        raise ParameterError(name, address, REACHABLE, outcome["reason"])
    ident = outcome["identity"]
    if ident.get("type") != "Scheduler":
        raise ParameterError(
            name,
            address,
            REACHABLE,
            f"the server there is a Dask {ident.get('type', 'peer')!s}, not a scheduler",
        )
    if not ident.get("n_workers"):
        raise ParameterError(
            name,
            address,
            "a Dask scheduler with at least one worker",
            "it has no workers: start some first (dask worker ADDRESS)",
        )
    return ident
