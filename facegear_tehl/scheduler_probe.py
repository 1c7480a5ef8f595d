"""The handshake with a Dask scheduler given by `tehl study --scheduler`, checked before Dask connects
(docs/guarantees.md).

Dask's client waits for the scheduler's first message without a deadline, and reads its first 8 bytes as the
length of what follows: a server that accepts the connection and never answers hangs the study, and a server that
is not Dask's (an HTTP responder answering "HTTP/1.0 400") makes it allocate exabytes. A Dask scheduler writes its
handshake as soon as it accepts a connection (distributed.comm.core.Listener.on_connection): over TCP one block,
prefixed by its length in bytes (a native-endian unsigned 64-bit integer, distributed.comm.tcp.TCP.read), that
starts with its count of frames (distributed.protocol.utils.unpack_frames). `probe` connects, reads that block
within HANDSHAKE_TIMEOUT, with bounded sizes, and raises CaseError under --scheduler if it does not come or is not
framed so; it sends nothing, so the scheduler only sees a connection opened and closed.
"""

from __future__ import annotations

import socket
import struct
import time
from urllib.parse import urlsplit

from facegear_tehl.schema import CaseError

HANDSHAKE_TIMEOUT = 10.0  # s: a scheduler answers at once; as long as Dask's connect timeout (study.CONNECT_TIMEOUT)
MAX_HANDSHAKE = 1 << 20  # bytes: Dask's handshake (its versions and options) is a few hundred bytes
MAX_FRAMES = 64  # frames in the handshake block: Dask writes a handful
_LENGTH = struct.Struct("=Q")  # native-endian unsigned 64-bit, as Dask's struct format "Q"


def probe(address: str, timeout: float | None = None) -> None:
    """CaseError under --scheduler unless a Dask scheduler answers at `address` (tcp://host:port or host:port)
    within `timeout` seconds (default HANDSHAKE_TIMEOUT); other schemes (tls://, ucx://) are left to Dask."""
    parts = urlsplit(address if "://" in address else f"tcp://{address}")
    if parts.scheme != "tcp":
        return
    deadline = time.monotonic() + (HANDSHAKE_TIMEOUT if timeout is None else timeout)
    try:
        host, port = parts.hostname, parts.port
        if host is None or port is None:
            raise _refused(address, "no host:port in it")
        with socket.create_connection((host, port), timeout=_left(deadline)) as connection:
            size = _LENGTH.unpack(_read(connection, _LENGTH.size, deadline))[0]
            if not _LENGTH.size <= size <= MAX_HANDSHAKE:
                raise _refused(address, f"it answered, but not as a Dask scheduler (a first block of {size} bytes)")
            frames = _LENGTH.unpack(_read(connection, size, deadline)[:_LENGTH.size])[0]
            if not 1 <= frames <= MAX_FRAMES:
                raise _refused(address, f"it answered, but not as a Dask scheduler ({frames} frames)")
    except TimeoutError:
        raise _refused(address, f"no Dask handshake within {_seconds(timeout)} s (the server accepted the "
                                "connection but did not answer)") from None
    except (OSError, ValueError) as exc:  # refused, unreachable, unknown host, a port out of range
        raise _refused(address, f"{type(exc).__name__}: {exc}") from None


def _refused(address: str, why: str) -> CaseError:
    return CaseError("--scheduler", address, f"the address of a running Dask scheduler, e.g. tcp://host:8786 ({why})")


def _seconds(timeout: float | None) -> str:
    return f"{HANDSHAKE_TIMEOUT if timeout is None else timeout:g}"


def _left(deadline: float) -> float:
    left = deadline - time.monotonic()
    if left <= 0:
        raise TimeoutError
    return left


def _read(connection: socket.socket, size: int, deadline: float) -> bytes:
    """Exactly `size` bytes before `deadline` (TimeoutError), or ConnectionError if the server closes first."""
    data = bytearray()
    while len(data) < size:
        connection.settimeout(_left(deadline))
        chunk = connection.recv(size - len(data))
        if not chunk:
            raise ConnectionError("the server closed the connection before its handshake")
        data += chunk
    return bytes(data)
