"""The page's IK server: who it lets in, what it refuses, and how it holds up under load.

Every server here listens on 127.0.0.1 on a free port, and every socket has a
timeout, so no test waits for more than a few seconds whatever the server does.
Requests are made with ``http.client`` (headers exactly as written) or raw sockets.
"""

from __future__ import annotations

import http.client
import json
import select
import socket
import threading
import time
from collections.abc import Iterator
from typing import Any
from urllib.parse import urlsplit

import numpy as np
import pytest

import kinematica as km
from kinematica import viz
from kinematica.viz.server import (
    IDLE_GRACE,
    MAX_CONNECTIONS,
    MAX_REQUEST_BYTES,
    TOKEN_HEADER,
    WORKERS,
)

#: A short read timeout for the tests (s): the server's default is a few seconds.
SHORT_TIMEOUT = 1.0
#: How long a test socket waits for the server (s): well past SHORT_TIMEOUT.
SOCKET_TIMEOUT = 5.0

PUMA = km.load("puma560")
Q = [0.2, -0.5, 0.3, 0.4, 0.8, -0.1]
GOOD = json.dumps({"T": PUMA.fk(Q).tolist()}).encode()


@pytest.fixture(scope="module")
def server() -> Iterator[viz.PageServer]:
    with viz.serve(PUMA, read_timeout=SHORT_TIMEOUT) as s:
        yield s


def address(server: viz.PageServer) -> tuple[str, int]:
    parts = urlsplit(server.url)
    assert parts.hostname == "127.0.0.1" and parts.port is not None
    return parts.hostname, parts.port


def call(
    server: viz.PageServer,
    body: bytes | None = GOOD,
    *,
    method: str = "POST",
    path: str = "/api/ik",
    **headers: str | None,
) -> tuple[int, str, bytes]:
    """``(status, content type, body)`` of one request; headers as the page sends them,
    changed by ``headers`` (``Content_Type=...``; ``None`` leaves a header out)."""
    host, port = address(server)
    sent: dict[str, str | None] = {
        "Host": f"{host}:{port}",
        "Origin": f"http://{host}:{port}",
        "Content-Type": "application/json",
        TOKEN_HEADER: server.token,
    }
    sent.update({k.replace("_", "-"): v for k, v in headers.items()})
    if body is not None and "Content-Length" not in sent:
        sent["Content-Length"] = str(len(body))
    conn = http.client.HTTPConnection(host, port, timeout=SOCKET_TIMEOUT)
    try:
        conn.putrequest(method, path, skip_host=True, skip_accept_encoding=True)
        for name, value in sent.items():
            if value is not None:
                conn.putheader(name, value)
        conn.endheaders(body)
        r = conn.getresponse()
        return r.status, r.getheader("Content-Type", ""), r.read()
    finally:
        conn.close()


def refused(server: viz.PageServer, body: bytes | None = GOOD, **kw: Any) -> tuple[int, str]:
    """``(status, message)`` of a request that must be refused with a JSON message."""
    status, kind, data = call(server, body, **kw)
    assert 400 <= status < 500, (status, data[:200])
    assert kind == "application/json"
    message = json.loads(data)["error"]
    assert isinstance(message, str) and message
    return status, message


# -------------------------------------------------------------- who gets in
def test_the_pages_own_requests_are_answered(server: viz.PageServer) -> None:
    port = address(server)[1]
    status, kind, page = call(server, None, method="GET", path="/", Origin=None)
    assert (status, kind) == (200, "text/html; charset=utf-8")
    assert f'"token": "{server.token}"'.encode() in page  # the page carries the token
    for name in (f"127.0.0.1:{port}", f"localhost:{port}"):
        status, _, data = call(server, Host=name, Origin=f"http://{name}")
        answer = json.loads(data)
        assert (status, answer["status"]) == (200, "ok")
        for q in answer["solutions"]:
            np.testing.assert_allclose(PUMA.fk(q), PUMA.fk(Q), atol=1e-9)
    assert call(server, Origin=None)[0] == 200  # a client that sends no Origin


@pytest.mark.parametrize(
    "origin", ["http://evil.example", "null", "http://127.0.0.1:1", "https://127.0.0.1:{port}"]
)
def test_a_foreign_origin_is_refused(server: viz.PageServer, origin: str) -> None:
    origin = origin.format(port=address(server)[1])
    assert refused(server, Origin=origin) == (403, f"requests from {origin!r} are refused")
    assert refused(server, None, method="GET", path="/", Origin=origin)[0] == 403


@pytest.mark.parametrize("host", ["evil.example:{port}", "127.0.0.1:1", "127.0.0.1", "", None])
def test_a_foreign_host_is_refused(server: viz.PageServer, host: str | None) -> None:
    # DNS rebinding: a page of evil.example whose name now points at 127.0.0.1
    host = host if host is None else host.format(port=address(server)[1])
    status, message = refused(server, Host=host, Origin=None)
    assert status == 403 and "is not this server's" in message
    assert refused(server, None, method="GET", path="/", Host=host, Origin=None)[0] == 403


@pytest.mark.parametrize("kind", ["text/plain", "application/x-www-form-urlencoded", None])
def test_a_body_that_is_not_json_typed_is_refused(server: viz.PageServer, kind: str) -> None:
    status, message = refused(server, Content_Type=kind)
    assert status == 415 and "application/json" in message
    assert call(server, Content_Type="application/json; charset=utf-8")[0] == 200


def test_the_token_is_required(server: viz.PageServer) -> None:
    for token in (None, "", server.token[:-1], server.token + "x", "é"):
        assert refused(server, **{TOKEN_HEADER: token}) == (403, f"missing or wrong {TOKEN_HEADER}")
    with viz.serve(PUMA) as other:  # a token is one run's
        assert other.token != server.token
        assert refused(other, **{TOKEN_HEADER: server.token})[0] == 403


def test_other_paths_and_methods(server: viz.PageServer) -> None:
    assert refused(server, None, method="GET", path="/../../etc/passwd")[0] == 404
    assert refused(server, None, method="GET", path="/api/ik")[0] == 405
    assert refused(server, method="PUT", path="/")[0] == 405


# ------------------------------------------------------------ what is refused
DEEP = b"[" * 30_000 + b"]" * 30_000
MALFORMED = {
    "400-digit integer": (b'{"position": [' + b"1" * 400 + b", 0, 0]}", 400, "finite"),
    "5,000-digit integer": (b'{"position": [' + b"7" * 5000 + b", 0, 0]}", 400, "finite"),
    "bare 5,000 digits": (b"7" * 5000, 400, "must be a JSON object"),
    "nested 30,000 deep": (DEEP, 400, "nested too deep"),
    "deep in a key": (b'{"T": ' + DEEP + b"}", 400, "nested too deep"),
    "a list": (b"[1, 2, 3]", 400, "must be a JSON object"),
    "null": (b"null", 400, "must be a JSON object"),
    "a position as T": (b'{"T": [0.3, 0.2, 0.1]}', 400, '"T" must be a 4x4 pose'),
    "a pose as position": (b'{"position": ' + GOOD[6:-1] + b"}", 400, '"position" must be 3'),
    "both keys": (b'{"T": [], "position": [0, 0, 0]}', 400, "exactly one of"),
    "another key": (b'{"target": [0, 0, 0]}', 400, "exactly one of"),
    "no key": (b"{}", 400, "exactly one of"),
    "NaN": (b'{"position": [NaN, 0, 0]}', 400, "NaN: every number must be finite"),
    "Infinity": (b'{"position": [0, -Infinity, 0]}', 400, "must be finite"),
    "1e400": (b'{"position": [0, 0, 1e400]}', 400, "finite"),
    "text for a number": (b'{"position": ["1", 0, 0]}', 400, "got a list of 3 (float, str)"),
    "true for a number": (b'{"position": [true, 0, 0]}', 400, "(bool, float)"),
    "ragged T": (b'{"T": [[1, 0, 0, 0], [0, 1, 0], [0, 0, 1, 0], [0, 0, 0, 1]]}', 400, "4x4"),
    "not rigid": (b'{"T": [[2,0,0,0],[0,1,0,0],[0,0,1,0],[0,0,0,1]]}', 400, "rotation"),
    "not UTF-8": (b'{"position": "\xff"}', 400, "not UTF-8"),
    "not JSON": (b"{nope", 400, "not JSON"),
    "empty": (b"", 400, "no body"),
}


@pytest.mark.parametrize("name", list(MALFORMED))
def test_a_malformed_body_gets_a_4xx_with_a_message(
    server: viz.PageServer, name: str, capfd: pytest.CaptureFixture[str]
) -> None:
    body, status, words = MALFORMED[name]
    got, message = refused(server, body)
    assert got == status and words in message, message
    assert capfd.readouterr().err == ""  # nothing on the console, no traceback


@pytest.mark.parametrize(
    ("length", "status", "words"),
    [
        (str(MAX_REQUEST_BYTES + 1), 413, f"over {MAX_REQUEST_BYTES} bytes"),
        ("9" * 30, 413, "over"),
        ("-1", 411, "Content-Length"),
        ("abc", 411, "Content-Length"),
        (None, 411, "Content-Length"),
    ],
)
def test_a_bad_length_is_refused(
    server: viz.PageServer, length: str | None, status: int, words: str
) -> None:
    got, message = refused(server, b"", Content_Length=length)
    assert got == status and words in message


def test_a_body_over_the_limit_is_refused_and_one_at_it_read() -> None:
    # the whole body is sent: the answer still arrives (no reset) and says why
    with viz.serve(PUMA) as server:
        big = b'{"position": [0, 0, 0' + b" " * MAX_REQUEST_BYTES + b"]}"
        assert refused(server, big)[0] == 413
        padded = b'{"position": [0.3, 0.2, 0.1]' + b" " * (MAX_REQUEST_BYTES - 29) + b"}"
        assert len(padded) == MAX_REQUEST_BYTES
        assert call(server, padded)[0] == 200


def test_headers_over_the_limit_are_refused(server: viz.PageServer) -> None:
    assert refused(server, X_Padding="x" * 20_000)[0] == 431


# ---------------------------------------------------------------- under load
def _raw(server: viz.PageServer, body: bytes, *, length: int | None = None) -> socket.socket:
    """A connection that has sent the headers of a POST and ``body`` (of ``length``)."""
    host, port = address(server)
    sock = socket.create_connection((host, port), timeout=SOCKET_TIMEOUT)
    head = (
        f"POST /api/ik HTTP/1.1\r\nHost: {host}:{port}\r\nContent-Type: application/json\r\n"
        f"{TOKEN_HEADER}: {server.token}\r\nContent-Length: {length or len(body)}\r\n\r\n"
    )
    sock.sendall(head.encode() + body)
    return sock


def _status(sock: socket.socket) -> int:
    data = b""
    while b"\r\n" not in data:
        chunk = sock.recv(4096)
        if not chunk:
            break
        data += chunk
    sock.close()
    return int(data.split(b" ")[1]) if data.startswith(b"HTTP/1.1 ") else -1


#: The read timeout of the stalled-clients test (s): a request of another client must
#: be answered within it of the stalls (a few ms on an idle machine), and the test lasts
#: it. A server that serialised its clients would answer only after all 50 stalls.
STALL_TIMEOUT = 3.0
#: How long that test waits for the stalled clients' answers (s): a hang guard only.
STALL_GUARD = 10 * STALL_TIMEOUT
STALLED = 50


def _answered(socks: list[socket.socket]) -> int:
    """How many of ``socks`` the server has answered or closed (readable now)."""
    return len(select.select(socks, [], [], 0)[0])


def test_stalled_clients_are_dropped_and_hold_no_threads() -> None:
    # the property, not a time: a request made after 50 clients stalled mid-body is
    # answered while they are all still held, then every stalled one gets 408 (not
    # before the read timeout); the IK threads are all the threads it takes
    with viz.serve(PUMA, read_timeout=STALL_TIMEOUT) as server:
        call(server)  # the IK threads exist now
        before = threading.active_count()
        start = time.monotonic()
        stalled = [_raw(server, GOOD[:10], length=len(GOOD)) for _ in range(STALLED)]
        assert call(server)[0] == 200  # the page is answered meanwhile ...
        assert _answered(stalled) == 0  # ... before any stalled client is dropped
        assert threading.active_count() <= before + WORKERS
        for sock in stalled:
            sock.settimeout(STALL_GUARD)
        assert [_status(s) for s in stalled] == [408] * STALLED  # dropped, with a word why
        assert time.monotonic() - start >= STALL_TIMEOUT  # not before their time
        assert threading.active_count() <= before + WORKERS


def test_a_slow_client_within_the_timeout_is_answered(server: viz.PageServer) -> None:
    # both sides of the read timeout: the rest of the body at half of it
    sock = _raw(server, GOOD[:10], length=len(GOOD))
    time.sleep(SHORT_TIMEOUT / 2)
    sock.sendall(GOOD[10:])
    assert _status(sock) == 200


def test_a_burst_of_requests_is_answered(server: viz.PageServer) -> None:
    # all sent before any is read: each answered (a read waits at most SOCKET_TIMEOUT);
    # no wall-clock limit on the whole burst, which a loaded machine broke
    socks = [_raw(server, GOOD) for _ in range(100)]
    assert [_status(s) for s in socks] == [200] * 100


def _closed_by_server(sock: socket.socket) -> bool:
    """True when the server has closed ``sock`` (it reads end of file, or a reset)."""
    sock.settimeout(SOCKET_TIMEOUT)
    try:
        return sock.recv(1) == b""
    except ConnectionResetError:
        return True
    except TimeoutError:
        return False


def test_idle_connections_do_not_lock_the_page_out() -> None:
    # the cap filled with idle connections (and slow senders), none dropped by the read
    # timeout meanwhile: past IDLE_GRACE, each newcomer closes the oldest of them, and
    # a request is answered (it once got 503 until the idle ones timed out)
    with viz.serve(PUMA, read_timeout=10 * SOCKET_TIMEOUT) as server:
        host, port = address(server)
        idle: list[socket.socket] = []
        for k in range(MAX_CONNECTIONS - 10):
            idle.append(socket.create_connection((host, port), timeout=SOCKET_TIMEOUT))
            if k % 50 == 49:
                time.sleep(0.05)  # within the listen backlog: accepted in the order made
        idle += [_raw(server, GOOD[:10], length=len(GOOD)) for _ in range(10)]
        time.sleep(IDLE_GRACE)
        more: list[socket.socket] = []
        try:
            status, _, data = call(server)
            assert (status, json.loads(data)["status"]) == (200, "ok")
            assert call(server, None, method="GET", path="/", Origin=None)[0] == 200
            more = [socket.create_connection((host, port)) for _ in range(20)]
            assert call(server)[0] == 200
            # room was made for the first request, the 19 newcomers past the cap and the
            # last request (the second, if it came before the first had left): 21 or 22
            # closed, the oldest; the newcomers are open
            time.sleep(0.2)
            ready = select.select([*idle, *more], [], [], 0)[0]  # closed, or answered
            closed = sorted(idle.index(sock) for sock in ready if sock in idle)
            assert 21 <= len(closed) <= 22 and max(closed) < 40, closed
            assert all(_closed_by_server(idle[i]) for i in closed)
            assert not any(sock in ready for sock in more)
        finally:
            for sock in (*idle, *more):
                sock.close()


def test_connections_that_just_came_are_not_closed_for_a_newcomer() -> None:
    # both sides of IDLE_GRACE: a request right after the cap is filled is answered 503
    # (a connection of a few ms may have sent a request not read yet); one after the
    # grace closes the oldest idle connection and is answered
    with viz.serve(PUMA, read_timeout=10 * SOCKET_TIMEOUT) as server:
        host, port = address(server)
        start = time.monotonic()
        idle = [socket.create_connection((host, port)) for _ in range(MAX_CONNECTIONS)]
        try:
            early = _status(_raw(server, GOOD))
            if time.monotonic() - start < IDLE_GRACE / 2:  # the machine kept up
                assert early == 503
            time.sleep(IDLE_GRACE)
            assert _status(_raw(server, GOOD)) == 200
        finally:
            for sock in idle:
                sock.close()


def test_connections_past_the_cap_are_answered_503_when_all_have_asked(
    monkeypatch: pytest.MonkeyPatch,
) -> None:
    # every open connection has sent its request and waits for its IK (held here):
    # none can be closed for a newcomer, which is answered 503 at once
    from kinematica.viz import server as server_module

    release = threading.Event()
    real = server_module.solve_request

    def held(robot: km.Robot, body: bytes) -> dict[str, Any]:
        release.wait(timeout=30)
        return real(robot, body)

    monkeypatch.setattr(server_module, "solve_request", held)
    with viz.serve(PUMA, read_timeout=10 * SOCKET_TIMEOUT) as server:
        busy = [_raw(server, GOOD) for _ in range(MAX_CONNECTIONS)]
        try:
            assert _status(_raw(server, GOOD)) == 503
            release.set()
            assert {_status(sock) for sock in busy} == {200}
        finally:
            release.set()
            for sock in busy:
                sock.close()
        assert call(server)[0] == 200


def test_bad_read_timeouts_and_ports_are_refused() -> None:
    for bad in (0, -1.0, float("nan"), float("inf"), "5"):
        with pytest.raises(km.ArgumentError, match="read_timeout must be a positive number"):
            viz.serve(PUMA, read_timeout=bad)  # type: ignore[arg-type]
    for bad in (-1, 65536, 99999, 1.5, True):
        with pytest.raises(km.ArgumentError, match=r"port must be an integer in 0\.\.65535"):
            viz.serve(PUMA, port=bad)  # type: ignore[arg-type]
