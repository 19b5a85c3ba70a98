"""``gen-robot view PATH --watch``: the page served on 127.0.0.1, made again when a file in PATH's folder (a spec, a
xacro document or URDF, a mesh) changes, and reloaded by the browser.

The page asks ``/version`` twice a second (its Content-Security-Policy allows that one origin in this mode only) and
reloads when the number changes. A change that does not build (a spec with a mistake) serves a page that shows the
error, located, until the next change builds: never a blank page, never the old robot without a word.

The server holds against what a browser or another page may do: it listens on 127.0.0.1 only; it answers only a
request whose ``Host`` is its own address and port (a page of another site whose name is made to resolve to
127.0.0.1, DNS rebinding, sends its own name and gets 403); a connection idle for ``IDLE_TIMEOUT`` seconds is closed;
at most ``MAX_CONNECTIONS`` are served at once (the others are closed at once); a client that goes away mid-answer is
forgotten without a word (no traceback).
"""

from __future__ import annotations

import contextlib
import html
import os
import sys
import threading
import time
from collections.abc import Callable
from http.server import BaseHTTPRequestHandler, ThreadingHTTPServer
from pathlib import Path
from typing import Any

from ..errors import SpecErrors, XacrokitError

WATCHED = (".yaml", ".yml", ".xacro", ".urdf", ".xml", ".stl", ".obj", ".ply", ".dae")
POLL = 0.5  # s, both the files' and the page's
MAX_ENTRIES = 20_000  # files and folders looked at per poll: a folder this large is not a robot's
IDLE_TIMEOUT = 10.0  # s a connection may stay silent (a browser's poll comes every POLL)
MAX_CONNECTIONS = 16  # served at once: one browser tab needs one or two

POLLER = """<script>
const shown = {version};
setInterval(async () => {{
  try {{
    const now = await (await fetch("/version", {{ cache: "no-store" }})).text();
    if (Number(now) !== shown) location.reload();
  }} catch (error) {{}}
}}, {poll});
</script>"""


def error_page(message: str, version: int) -> str:
    """What the browser shows while the files do not build: the error, escaped, and the poller."""
    return (
        "<!DOCTYPE html><html lang='en'><head><meta charset='utf-8'><title>xacrokit viewer: error</title>"
        "<meta http-equiv='Content-Security-Policy' content=\"default-src 'none'; script-src 'unsafe-inline'; "
        "connect-src 'self'; style-src 'unsafe-inline'\"></head><body style='font: 14px sans-serif; margin: 2em'>"
        "<h2>The robot does not build</h2><pre style='white-space: pre-wrap; color: #a00'>"
        + html.escape(message)
        + "</pre><p>Fix the file and save it: this page reloads.</p>"
        + POLLER.format(version=version, poll=int(POLL * 1000))
        + "</body></html>"
    )


def snapshot(folder: Path) -> dict[str, tuple[int, int]]:
    """(mtime, size) of every watched file under ``folder``, looking at no more than MAX_ENTRIES entries (a spec kept
    in a home folder must not make every poll walk the whole disk)."""
    found: dict[str, tuple[int, int]] = {}
    seen = 0
    for where, folders, files in os.walk(folder):
        folders[:] = sorted(f for f in folders if not f.startswith("."))  # (no .git, no caches)
        seen += len(folders) + len(files)
        for name in sorted(files):
            path = Path(where, name)
            if path.suffix.lower() in WATCHED:
                with contextlib.suppress(OSError):  # (a file removed while we look)
                    stat = path.stat()
                    found[str(path)] = (stat.st_mtime_ns, stat.st_size)
        if seen > MAX_ENTRIES:
            break
    return found


class Watcher:
    """Builds the page with ``build(version)`` now and after every change under ``folder``; serves the newest."""

    def __init__(self, build: Callable[[int], str], folder: Path) -> None:
        self.build = build
        self.folder = folder
        self.version = 0
        self.page = ""
        self.lock = threading.Lock()
        self.seen = snapshot(folder)
        self.rebuild()

    def rebuild(self) -> None:
        version = self.version + 1
        try:
            text = self.build(version)
        except SpecErrors as exc:
            text = error_page(str(exc), version)
        except XacrokitError as exc:
            text = error_page(str(exc), version)
        with self.lock:
            self.version, self.page = version, text

    def poll(self) -> bool:
        """Rebuild if a watched file changed since the last look; whether it did."""
        now = snapshot(self.folder)
        if now == self.seen:
            return False
        self.seen = now
        self.rebuild()
        return True

    def serve(self, port: int, *, announce: Callable[[str], None], stop: threading.Event | None = None) -> None:
        """Serve on 127.0.0.1:``port`` (0: any free one) until ``stop`` is set (or forever)."""
        server = _Server(("127.0.0.1", port), _handler(self))
        thread = threading.Thread(target=server.serve_forever, daemon=True)
        thread.start()
        announce(f"serving http://127.0.0.1:{server.server_address[1]}/ ; watching {self.folder} (Ctrl-C stops)")
        try:
            while stop is None or not stop.is_set():
                time.sleep(POLL)
                if self.poll():
                    announce(f"rebuilt (version {self.version})")
        finally:
            server.shutdown()
            server.server_close()


class _Server(ThreadingHTTPServer):
    """At most MAX_CONNECTIONS at once; a client gone mid-answer is no error to print."""

    daemon_threads = True
    # connections the kernel keeps waiting to be accepted (socketserver's 5 dropped a burst's SYNs, and each client
    # dropped waited TCP's one-second retry: 30 s for 200 connections made one after another)
    request_queue_size = 128

    def __init__(self, address: tuple[str, int], handler: type[BaseHTTPRequestHandler]) -> None:
        super().__init__(address, handler)
        self.slots = threading.BoundedSemaphore(MAX_CONNECTIONS)

    def process_request(self, request: Any, client_address: Any) -> None:
        if not self.slots.acquire(blocking=False):
            self.shutdown_request(request)  # (too many at once: closed, the browser retries)
            return
        super().process_request(request, client_address)

    def process_request_thread(self, request: Any, client_address: Any) -> None:
        try:
            super().process_request_thread(request, client_address)
        finally:
            self.slots.release()

    def handle_error(self, request: Any, client_address: Any) -> None:
        error = sys.exc_info()[1]
        if isinstance(error, (ConnectionError, TimeoutError)):
            return  # (the browser closed the tab, or went silent: nothing to say)
        print(f"gen-robot view: a request failed: {type(error).__name__}: {error}", file=sys.stderr)


def _handler(watcher: Watcher) -> type[BaseHTTPRequestHandler]:
    """The request handler: the page at /, its version at /version, for this server's own Host only."""

    class Handler(BaseHTTPRequestHandler):
        timeout = IDLE_TIMEOUT  # (socketserver: the connection's timeout, read and write)

        def do_GET(self) -> None:  # noqa: N802  (http.server's name)
            port = self.connection.getsockname()[1]  # (the port this request came in on: the server's own)
            if self.headers.get("Host", "") not in (f"127.0.0.1:{port}", f"localhost:{port}"):
                self.send_error(403, "the Host header names another site")  # (DNS rebinding)
                return
            with watcher.lock:
                body = {"/": watcher.page, "/version": str(watcher.version)}.get(self.path.split("?")[0])
            if body is None:
                self.send_error(404)
                return
            data = body.encode("utf-8")
            self.send_response(200)
            self.send_header("Content-Type", "text/html; charset=utf-8" if self.path == "/" else "text/plain")
            self.send_header("Cache-Control", "no-store")
            self.send_header("Content-Length", str(len(data)))
            self.end_headers()
            self.wfile.write(data)

        def log_message(self, format: str, *args: object) -> None:  # noqa: A002  (quiet: the terminal is the user's)
            return

    return Handler
