"""`tehl study --scheduler` checks the scheduler's handshake before Dask connects (scheduler_probe.py,
docs/guarantees.md): a server that accepts and never answers, one that answers in another protocol and an HTTP
server each exit 2 within the handshake timeout, naming --scheduler; a real Dask scheduler passes."""

from __future__ import annotations

from contextlib import contextmanager
import http.server
import socket
import threading
import time

from click.testing import CliRunner
import pytest

from facegear_tehl import scheduler_probe
from facegear_tehl.cli import tehl
from facegear_tehl.scheduler_probe import probe
from facegear_tehl.schema import CaseError

import synthetic

TIMEOUT = 1.0  # s, the handshake timeout of these tests


@contextmanager
def _server(answer: bytes | None):
    """A TCP server on a free local port: accepts, then sends `answer` (None: nothing) and holds the connection."""
    listener = socket.create_server(("127.0.0.1", 0))
    held: list[socket.socket] = []
    stop = threading.Event()

    def serve() -> None:
        listener.settimeout(0.1)
        while not stop.is_set():
            try:
                connection, _ = listener.accept()
            except TimeoutError:
                continue
            held.append(connection)
            if answer is not None:
                connection.sendall(answer)

    thread = threading.Thread(target=serve, daemon=True)
    thread.start()
    try:
        yield f"tcp://127.0.0.1:{listener.getsockname()[1]}"
    finally:
        stop.set()
        thread.join()
        for connection in held:
            connection.close()
        listener.close()


@contextmanager
def _http_server():
    server = http.server.HTTPServer(("127.0.0.1", 0), http.server.BaseHTTPRequestHandler)
    thread = threading.Thread(target=server.serve_forever, daemon=True)
    thread.start()
    try:
        yield f"tcp://127.0.0.1:{server.server_address[1]}"
    finally:
        server.shutdown()
        server.server_close()


@pytest.mark.parametrize(("answer", "expected"), [
    (None, f"no Dask handshake within {TIMEOUT:g} s"),
    (b"SSH-2.0-OpenSSH_9.6\r\n", "not as a Dask scheduler"),
    (b"HTTP/1.0 400 Bad request\r\n\r\n", "not as a Dask scheduler"),
    (b"\x10\x00\x00\x00\x00\x00\x00\x00short", "no Dask handshake"),  # 16 bytes announced, 5 sent
])
def test_a_server_that_is_not_a_dask_scheduler_is_refused_in_time(answer, expected):
    with _server(answer) as address:
        started = time.monotonic()
        with pytest.raises(CaseError) as error:
            probe(address, TIMEOUT)
    assert time.monotonic() - started < TIMEOUT + 2.0
    assert error.value.key == "--scheduler" and expected in error.value.expected


def test_an_http_server_is_refused_in_time():
    with _http_server() as address:
        started = time.monotonic()
        with pytest.raises(CaseError, match="no Dask handshake"):
            probe(address, TIMEOUT)
    assert time.monotonic() - started < TIMEOUT + 2.0


def test_a_dask_scheduler_passes():
    distributed = pytest.importorskip("distributed")
    with distributed.LocalCluster(n_workers=0, processes=False, dashboard_address=None) as cluster:
        probe(cluster.scheduler_address, 10.0)


def test_tehl_study_exits_2_on_a_silent_scheduler(tmp_path, monkeypatch):
    monkeypatch.setattr(scheduler_probe, "HANDSHAKE_TIMEOUT", TIMEOUT)
    study = tmp_path / "study.yaml"
    study.write_text(f"base: {synthetic.BALL_ON_DISC}\nvary:\n  contact.load: [4.0]\n", encoding="utf-8")
    with _server(None) as address:
        started = time.monotonic()
        result = CliRunner().invoke(tehl, ["study", str(study), "--scheduler", address, "-o", str(tmp_path / "out")])
    assert time.monotonic() - started < TIMEOUT + 10.0
    assert result.exit_code == 2, result.output
    assert result.stderr.strip().splitlines()[-1].startswith(f"error: --scheduler: got '{address}'; expected the "
                                                             "address of a running Dask scheduler")
    assert not (tmp_path / "out").exists()
