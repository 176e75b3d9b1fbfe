"""``kinematica view --serve``: the page on a local port, with IK in Python.

A small standard-library server (``asyncio``; nothing to install) serves the
page with its draggable target switched on, and answers ``POST /api/ik`` with
every solution ``robot.ik`` finds for the target (:mod:`kinematica.viz.ik_request`).
It listens on the loopback address only, unless told otherwise.

What it lets in: requests whose ``Host`` is this server's own address
(``127.0.0.1``, ``localhost``, ``[::1]`` or the host it was given, with its
port), so a site that rebinds its DNS name to 127.0.0.1 is refused; an
``Origin``, when there is one, that is the page's own; and on the API, the
run's random token (``X-Kinematica-Token``, embedded in the served page) and a
JSON body. Anything else is a 4xx with a JSON ``{"error": message}``.

What it holds up under: connections are served by one event loop, so an idle
or stalled client costs no thread; each request must arrive whole within
:data:`READ_TIMEOUT` seconds or is dropped; at most :data:`MAX_CONNECTIONS`
are open at once. A connection past the cap closes the oldest one that has waited
:data:`IDLE_GRACE` seconds or more for its request (idle, or sending it slowly) to
make room, so idle clients cannot lock the page out; only when no open connection
has waited that long (every one has sent its request, or has just come) is the
newcomer answered 503. IK runs on :data:`WORKERS` threads;
the listen backlog is :data:`BACKLOG`.
"""

from __future__ import annotations

import asyncio
import contextlib
import hmac
import json
import math
import os
import secrets
import socket
import threading
from concurrent.futures import ThreadPoolExecutor
from http import HTTPStatus
from typing import Any

from numpy.typing import ArrayLike

from kinematica.errors import ArgumentError, KinematicaError
from kinematica.reach import ReachabilityMap
from kinematica.robot import Robot
from kinematica.viz.ik_request import solve_request
from kinematica.viz.page import page_html

__all__ = [
    "BACKLOG",
    "IDLE_GRACE",
    "MAX_CONNECTIONS",
    "MAX_HEADER_BYTES",
    "MAX_REQUEST_BYTES",
    "READ_TIMEOUT",
    "TOKEN_HEADER",
    "WORKERS",
    "PageServer",
    "serve",
    "solve_request",
]

#: Largest request body accepted (a target is 16 numbers).
MAX_REQUEST_BYTES = 64 * 1024
#: Largest request line plus headers accepted.
MAX_HEADER_BYTES = 16 * 1024
#: Seconds a client has to send a whole request (line, headers and body) once connected.
READ_TIMEOUT = 5.0
#: Connections open at once; one more closes the oldest still waiting for its request
#: (for IDLE_GRACE or more), or, when none is, is answered 503 and closed.
MAX_CONNECTIONS = 256
#: Seconds a connection waits for its request before a newcomer past the cap may close
#: it: a client sends its request as it connects (milliseconds on loopback), while the
#: server may not have read a request that has already arrived when the next
#: connection comes; an idle or slow client is past this long before READ_TIMEOUT.
IDLE_GRACE = 0.5
#: Threads that run IK (and nothing else) for the requests.
WORKERS = 4
#: Connections the system queues before the server accepts them.
BACKLOG = 128
#: The header that carries the run's token on every API request.
TOKEN_HEADER = "X-Kinematica-Token"
#: Seconds, and bytes, an answered request's unread body is drained for before closing
#: (closing with unread data resets the connection, and the client may lose the answer).
_LINGER_SECONDS = 1.0
_LINGER_BYTES = 1024 * 1024


class _RefusedError(Exception):
    """A request answered with a 4xx/5xx status and a message."""

    def __init__(self, status: HTTPStatus, message: str) -> None:
        super().__init__(message)
        self.status = status


def _response(status: int, body: bytes, kind: str) -> bytes:
    head = (
        f"HTTP/1.1 {status} {HTTPStatus(status).phrase}\r\n"
        f"Content-Type: {kind}\r\n"
        f"Content-Length: {len(body)}\r\n"
        "Cache-Control: no-store\r\n"
        "X-Content-Type-Options: nosniff\r\n"
        "Connection: close\r\n\r\n"
    )
    return head.encode("latin-1") + body


def _json(status: int, data: dict[str, Any]) -> bytes:
    return _response(status, json.dumps(data, allow_nan=False).encode(), "application/json")


def _parse_head(head: bytes) -> tuple[str, str, dict[str, str]]:
    """``(method, path, headers)`` of a request's head; header names in lower case."""
    lines = head.decode("latin-1").split("\r\n")
    parts = lines[0].split(" ")
    if len(parts) != 3 or not parts[2].startswith("HTTP/1."):
        raise _RefusedError(
            HTTPStatus.BAD_REQUEST, f"not an HTTP/1.x request line: {lines[0][:80]!r}"
        )
    headers: dict[str, str] = {}
    for line in lines[1:]:
        if not line:
            continue
        name, sep, value = line.partition(":")
        name = name.strip().lower()
        if not sep or not name:
            raise _RefusedError(HTTPStatus.BAD_REQUEST, f"malformed header line: {line[:80]!r}")
        if name in headers:
            raise _RefusedError(HTTPStatus.BAD_REQUEST, f"the header {name!r} is given twice")
        headers[name] = value.strip()
    return parts[0], parts[1], headers


def _listening(host: str, port: int) -> socket.socket:
    """A socket listening on the first address ``host`` names (one port, even for localhost)."""
    family, kind, proto, _, address = socket.getaddrinfo(host, port, type=socket.SOCK_STREAM)[0]
    sock = socket.socket(family, kind, proto)
    try:
        sock.setsockopt(socket.SOL_SOCKET, socket.SO_REUSEADDR, 1)
        sock.bind(address)
        sock.listen(BACKLOG)
    except BaseException:
        sock.close()
        raise
    return sock


class PageServer:
    """The page and its IK endpoint on ``host:port`` (see :func:`serve`).

    Attributes:
        url: The page's address, e.g. ``http://127.0.0.1:8765/``.
        token: This run's secret: API requests carry it in :data:`TOKEN_HEADER`.
    """

    def __init__(
        self,
        robot: Robot,
        host: str,
        port: int,
        page: str,
        token: str,
        *,
        read_timeout: float = READ_TIMEOUT,
    ) -> None:
        # Bound and listening here, so the port is known (and its errors raised) now;
        # the loop takes it over in the serving thread, where it runs (the caller's
        # thread may run an event loop of its own: a notebook, playwright).
        self._sock = _listening(host, port)
        self._robot = robot
        self._page = page.encode("utf-8")
        self.token = token
        self._read_timeout = read_timeout
        self._pool = ThreadPoolExecutor(max_workers=WORKERS, thread_name_prefix="kinematica-ik")
        self._loop = asyncio.new_event_loop()
        self._loop.set_default_executor(self._pool)  # name look-ups too: no other threads
        self._loop.set_exception_handler(lambda loop, context: None)  # no tracebacks
        self._tasks: set[asyncio.Task[None]] = set()
        # the connections still reading their request, oldest first (a dict keeps order),
        # with the loop's time each came at
        self._waiting: dict[asyncio.Task[None], float] = {}
        # those closed to make room, until their tasks end: no longer counted as open
        self._evicted: set[asyncio.Task[None]] = set()
        self._server: asyncio.Server | None = None
        bound = self._sock.getsockname()[1]
        shown = (f"[{host}]" if ":" in host else host).lower()
        self.url = f"http://{shown}:{bound}/"
        self._hosts = {f"{h}:{bound}" for h in ("127.0.0.1", "localhost", "[::1]", shown)}
        self._origins = {f"http://{h}" for h in self._hosts}
        self._stop: asyncio.Future[None] = self._loop.create_future()
        self._thread: threading.Thread | None = None
        self._closed = False
        self._closing = threading.Lock()  # the serving thread and close() may both shut

    # ------------------------------------------------------------ running
    def start(self) -> PageServer:
        """Serve in a background thread; returns ``self``."""
        self._thread = threading.Thread(target=self.serve_forever, daemon=True)
        self._thread.start()
        return self

    def serve_forever(self) -> None:
        """Serve in this thread until :meth:`close` (from another thread) or Ctrl-C."""
        try:
            self._server = self._loop.run_until_complete(
                asyncio.start_server(
                    self._connected, sock=self._sock, backlog=BACKLOG, limit=MAX_HEADER_BYTES
                )
            )
            self._loop.run_until_complete(self._stop)
        finally:
            self._shut()

    def close(self) -> None:
        """Stop serving and free the port."""
        if self._thread is not None or self._loop.is_running():
            # queued for the loop even if its thread has not started it yet; a
            # RuntimeError: the loop is closed already
            with contextlib.suppress(RuntimeError):
                self._loop.call_soon_threadsafe(self._stopping)
        if self._thread is not None:
            self._thread.join()
            self._thread = None
        if not self._loop.is_running():
            self._shut()

    def _stopping(self) -> None:
        if not self._stop.done():
            self._stop.set_result(None)

    def _shut(self) -> None:
        with self._closing:
            if self._closed:
                return
            self._closed = True
            if self._server is not None:
                self._server.close()
            self._sock.close()
            pending = list(self._tasks)  # each task leaves the set as it ends
            for task in pending:
                task.cancel()
            if pending:
                self._loop.run_until_complete(asyncio.wait(pending))
            self._loop.close()
            self._pool.shutdown(wait=True, cancel_futures=True)

    def __enter__(self) -> PageServer:
        return self

    def __exit__(self, *exc: object) -> None:
        self.close()

    # ------------------------------------------------------- one connection
    async def _connected(self, reader: asyncio.StreamReader, writer: asyncio.StreamWriter) -> None:
        task = asyncio.current_task()
        assert task is not None  # a connection's callback runs as a task
        self._tasks.add(task)
        try:
            crowded = len(self._tasks) - len(self._evicted) > MAX_CONNECTIONS
            if crowded and not self._make_room():
                status: int = HTTPStatus.SERVICE_UNAVAILABLE
                answer = _json(status, {"error": "too many connections"})
            else:
                self._waiting[task] = self._loop.time()
                status, answer = await self._answer(reader, task)
            async with asyncio.timeout(self._read_timeout):  # a client that reads nothing
                writer.write(answer)
                await writer.drain()
            if status != HTTPStatus.OK:  # the body may be unread
                await self._linger(reader, writer)
        except (ConnectionError, OSError):
            pass  # the client went away, or stopped reading: nobody to answer
        finally:
            self._tasks.discard(task)
            self._waiting.pop(task, None)
            self._evicted.discard(task)
            writer.close()

    def _make_room(self) -> bool:
        """Close the oldest connection waiting IDLE_GRACE or more; False if there is none."""
        oldest = next(iter(self._waiting), None)
        if oldest is None or self._loop.time() - self._waiting[oldest] < IDLE_GRACE:
            return False
        del self._waiting[oldest]
        self._evicted.add(oldest)
        oldest.cancel()  # its reading stops; it closes its socket as it ends
        return True

    async def _answer(
        self, reader: asyncio.StreamReader, task: asyncio.Task[None]
    ) -> tuple[int, bytes]:
        try:
            try:
                async with asyncio.timeout(self._read_timeout):
                    body = await self._request(reader)
                self._waiting.pop(task, None)  # the request is in: no longer idle
            except TimeoutError:
                raise _RefusedError(
                    HTTPStatus.REQUEST_TIMEOUT,
                    f"the request did not arrive within {self._read_timeout:g} s",
                ) from None
            except asyncio.LimitOverrunError:
                raise _RefusedError(
                    HTTPStatus.REQUEST_HEADER_FIELDS_TOO_LARGE,
                    f"the request's headers are over {MAX_HEADER_BYTES} bytes",
                ) from None
            except asyncio.IncompleteReadError:
                raise _RefusedError(HTTPStatus.BAD_REQUEST, "the request ended early") from None
            if body is None:
                return HTTPStatus.OK, _response(
                    HTTPStatus.OK, self._page, "text/html; charset=utf-8"
                )
            try:  # the time IK takes is not the client's: outside the read timeout
                answer = await asyncio.get_running_loop().run_in_executor(
                    None, solve_request, self._robot, body
                )
            except KinematicaError as exc:
                raise _RefusedError(HTTPStatus.BAD_REQUEST, str(exc)) from None
            return HTTPStatus.OK, _json(HTTPStatus.OK, answer)
        except _RefusedError as exc:
            return exc.status, _json(exc.status, {"error": str(exc)})
        except Exception as exc:  # anything else: an answer, never a traceback
            status = HTTPStatus.INTERNAL_SERVER_ERROR
            return status, _json(status, {"error": f"internal error: {type(exc).__name__}: {exc}"})

    async def _request(self, reader: asyncio.StreamReader) -> bytes | None:
        """The IK request's body, or ``None`` for the page; refused as :class:`_RefusedError`."""
        method, path, headers = _parse_head(await reader.readuntil(b"\r\n\r\n"))
        self._check_sender(headers)
        route = path.split("?")[0].split("#")[0]
        takes = {"/": "GET", "/index.html": "GET", "/api/ik": "POST"}.get(route)
        if takes is None:
            raise _RefusedError(HTTPStatus.NOT_FOUND, f"no such page: {path[:200]}")
        if method != takes:
            raise _RefusedError(
                HTTPStatus.METHOD_NOT_ALLOWED, f"{route} takes {takes}, not {method[:20]}"
            )
        return None if takes == "GET" else await self._body(reader, headers)

    def _check_sender(self, headers: dict[str, str]) -> None:
        host = headers.get("host", "").lower()
        if host not in self._hosts:
            raise _RefusedError(
                HTTPStatus.FORBIDDEN,
                f"Host {host[:200]!r} is not this server's (one of {sorted(self._hosts)})",
            )
        origin = headers.get("origin")
        if origin is not None and origin.lower() not in self._origins:
            raise _RefusedError(HTTPStatus.FORBIDDEN, f"requests from {origin[:200]!r} are refused")

    async def _body(self, reader: asyncio.StreamReader, headers: dict[str, str]) -> bytes:
        given = headers.get(TOKEN_HEADER.lower(), "")
        if not hmac.compare_digest(given.encode("latin-1"), self.token.encode("latin-1")):
            raise _RefusedError(HTTPStatus.FORBIDDEN, f"missing or wrong {TOKEN_HEADER}")
        kind = headers.get("content-type", "").split(";")[0].strip().lower()
        if kind != "application/json":
            raise _RefusedError(
                HTTPStatus.UNSUPPORTED_MEDIA_TYPE,
                f"the body must be Content-Type: application/json, got {kind[:100]!r}",
            )
        if "transfer-encoding" in headers:
            raise _RefusedError(HTTPStatus.LENGTH_REQUIRED, "send the body with a Content-Length")
        text = headers.get("content-length", "")
        if not (text.isascii() and text.isdigit()):
            raise _RefusedError(HTTPStatus.LENGTH_REQUIRED, "the request needs a Content-Length")
        if len(text) > 9 or int(text) > MAX_REQUEST_BYTES:
            raise _RefusedError(
                HTTPStatus.REQUEST_ENTITY_TOO_LARGE,
                f"the body is over {MAX_REQUEST_BYTES} bytes",
            )
        if int(text) == 0:
            raise _RefusedError(HTTPStatus.BAD_REQUEST, "the request has no body")
        return await reader.readexactly(int(text))

    async def _linger(self, reader: asyncio.StreamReader, writer: asyncio.StreamWriter) -> None:
        """Read what the client still sends for a while, so it receives the answer."""
        if writer.can_write_eof():
            writer.write_eof()
        read = 0
        try:
            async with asyncio.timeout(_LINGER_SECONDS):
                while read < _LINGER_BYTES:
                    chunk = await reader.read(64 * 1024)
                    if not chunk:
                        return
                    read += len(chunk)
        except TimeoutError:
            pass


def serve(
    robot: Robot,
    *,
    host: str = "127.0.0.1",
    port: int = 0,
    units: dict[str, str] | None = None,
    q: ArrayLike | None = None,
    euler: str = "ZYZ",
    start: bool = True,
    read_timeout: float = READ_TIMEOUT,
    reach: ReachabilityMap | str | os.PathLike[str] | None = None,
) -> PageServer:
    """Serve the page with a draggable IK target on ``http://host:port/``.

    Args:
        robot: The robot.
        host: Address to listen on (the loopback address by default).
        port: Port; 0 picks a free one (see ``PageServer.url``).
        units: Slider units, as :func:`kinematica.viz.page_html`.
        q: Start configuration (rad, m).
        euler: Euler sequence shown first.
        start: Start serving in a background thread (else call ``serve_forever``).
        read_timeout: Seconds a client has to send a whole request.
        reach: A reachability map the page shows, as :func:`kinematica.viz.page_html`.

    Returns:
        The :class:`PageServer`; ``close()`` it (or use it in a ``with`` block).
    """
    if isinstance(read_timeout, bool) or not (
        isinstance(read_timeout, int | float) and 0 < read_timeout < math.inf
    ):
        raise ArgumentError(
            f"read_timeout must be a positive number of seconds, got {read_timeout!r}",
            arg="read_timeout",
        )
    if isinstance(port, bool) or not isinstance(port, int) or not 0 <= port <= 65535:
        raise ArgumentError(
            f"port must be an integer in 0..65535 (0: a free one), got {port!r}", arg="port"
        )
    token = secrets.token_urlsafe(32)
    page = page_html(robot, units=units, q=q, euler=euler, serve=True, token=token, reach=reach)
    try:
        server = PageServer(robot, host, port, page, token, read_timeout=read_timeout)
    except OSError as exc:
        raise KinematicaError(f"cannot serve on {host}:{port}: {exc.strerror or exc}") from exc
    return server.start() if start else server
