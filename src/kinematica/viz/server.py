"""``kinematica view --serve``: the page on a local port, with IK in Python.

A small standard-library HTTP server (``http.server``; nothing to install)
serves the page with its draggable target switched on, and answers
``POST /api/ik`` with every solution ``robot.ik`` finds for the target.
It listens on the loopback address only, unless told otherwise.
"""

from __future__ import annotations

import json
import threading
from http import HTTPStatus
from http.server import BaseHTTPRequestHandler, ThreadingHTTPServer
from typing import Any

import numpy as np
from numpy.typing import ArrayLike

from kinematica.errors import KinematicaError
from kinematica.robot import Robot
from kinematica.viz.page import page_html

__all__ = ["MAX_REQUEST_BYTES", "PageServer", "serve", "solve_request"]

#: Largest request body accepted (a target is 16 numbers).
MAX_REQUEST_BYTES = 64 * 1024


def _finite(a: Any) -> Any:
    """Nested lists with NaN/inf as ``None`` (valid JSON)."""
    return [_finite(v) for v in a] if isinstance(a, list) else (a if np.isfinite(a) else None)


def solve_request(robot: Robot, body: bytes) -> dict[str, Any]:
    """Answer one IK request: ``{"T": 4x4}`` or ``{"position": [x, y, z]}`` (m).

    Returns:
        ``{"status", "method", "message", "solutions" (rad, m), "branches"}``.

    Raises:
        KinematicaError: A malformed request (the message says what is wrong).
    """
    try:
        request = json.loads(body.decode("utf-8"))
    except (UnicodeDecodeError, json.JSONDecodeError) as exc:
        raise KinematicaError(f"the request is not JSON: {exc}") from exc
    if not isinstance(request, dict) or not ({"T", "position"} & request.keys()):
        raise KinematicaError('the request needs "T" (4x4 pose) or "position" (x, y, z)')
    raw = request.get("T", request.get("position"))
    try:
        target = np.array(raw, dtype=float)
    except (TypeError, ValueError) as exc:
        raise KinematicaError(f"the target must be numbers, got {raw!r}") from exc
    if target.shape not in ((4, 4), (3,)) or not np.all(np.isfinite(target)):
        raise KinematicaError(
            f"the target must be a finite 4x4 pose or 3 coordinates, got shape {target.shape}"
        )
    res = robot.ik(target)
    solutions = np.asarray(getattr(res, "solutions", np.empty((0, robot.dof))))
    return {
        "status": str(res.status),
        "method": res.method,
        "message": getattr(res, "message", ""),
        "solutions": _finite(solutions.tolist()),
        "branches": [str(b) for b in getattr(res, "branches", ())],
    }


def _handler(robot: Robot, page: bytes) -> type[BaseHTTPRequestHandler]:
    class Handler(BaseHTTPRequestHandler):
        server_version = "kinematica"

        def log_message(self, format: str, *args: Any) -> None:
            """Quiet: no line per request on stderr."""

        def _send(self, status: int, body: bytes, kind: str) -> None:
            self.send_response(status)
            self.send_header("Content-Type", kind)
            self.send_header("Content-Length", str(len(body)))
            self.send_header("Cache-Control", "no-store")
            self.end_headers()
            self.wfile.write(body)

        def _json(self, status: int, data: dict[str, Any]) -> None:
            self._send(status, json.dumps(data, allow_nan=False).encode(), "application/json")

        def do_GET(self) -> None:
            """The page at ``/`` (and ``/index.html``)."""
            if self.path.split("?")[0].split("#")[0] in ("/", "/index.html"):
                self._send(HTTPStatus.OK, page, "text/html; charset=utf-8")
            else:
                self._json(HTTPStatus.NOT_FOUND, {"error": f"no such page: {self.path}"})

        def do_POST(self) -> None:
            """``/api/ik``: every solution of the posted target."""
            if self.path != "/api/ik":
                self._json(HTTPStatus.NOT_FOUND, {"error": f"no such endpoint: {self.path}"})
                return
            try:
                length = int(self.headers.get("Content-Length", "0"))
            except ValueError:
                length = -1
            if not 0 < length <= MAX_REQUEST_BYTES:
                self._json(HTTPStatus.BAD_REQUEST, {"error": "missing or oversized request body"})
                return
            try:
                answer = solve_request(robot, self.rfile.read(length))
            except KinematicaError as exc:
                self._json(HTTPStatus.BAD_REQUEST, {"error": str(exc)})
                return
            self._json(HTTPStatus.OK, answer)

    return Handler


class PageServer:
    """The page and its IK endpoint on ``host:port`` (see :func:`serve`).

    Attributes:
        url: The page's address, e.g. ``http://127.0.0.1:8765/``.
    """

    def __init__(self, robot: Robot, host: str, port: int, page: str) -> None:
        self._httpd = ThreadingHTTPServer((host, port), _handler(robot, page.encode("utf-8")))
        self._httpd.daemon_threads = True
        self._thread: threading.Thread | None = None
        bound = self._httpd.server_address[1]
        self.url = f"http://{host}:{bound}/"

    def start(self) -> PageServer:
        """Serve in a background thread; returns ``self``."""
        self._thread = threading.Thread(target=self._httpd.serve_forever, daemon=True)
        self._thread.start()
        return self

    def serve_forever(self) -> None:
        """Serve in this thread until :meth:`close` or Ctrl-C."""
        self._httpd.serve_forever()

    def close(self) -> None:
        """Stop serving and free the port."""
        if self._thread is not None:
            self._httpd.shutdown()
            self._thread.join()
            self._thread = None
        self._httpd.server_close()

    def __enter__(self) -> PageServer:
        return self

    def __exit__(self, *exc: object) -> None:
        self.close()


def serve(
    robot: Robot,
    *,
    host: str = "127.0.0.1",
    port: int = 0,
    units: dict[str, str] | None = None,
    q: ArrayLike | None = None,
    euler: str = "ZYZ",
    start: bool = True,
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

    Returns:
        The :class:`PageServer`; ``close()`` it (or use it in a ``with`` block).
    """
    page = page_html(robot, units=units, q=q, euler=euler, serve=True)
    try:
        server = PageServer(robot, host, port, page)
    except OSError as exc:
        raise KinematicaError(f"cannot serve on {host}:{port}: {exc.strerror}") from exc
    return server.start() if start else server
