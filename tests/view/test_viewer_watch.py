"""gen-robot view --watch: the page served on 127.0.0.1, made again when the spec changes (its version moves, the new
robot is in it), a spec with a mistake served as a page that shows the located error, and in a real browser the page
reloads by itself."""

from __future__ import annotations

import subprocess
import sys
import time
import urllib.request

import pytest

from conftest import REPO

SPEC = """robot: watched
links:
  base_link: {shape: {box: {size: [0.2, 0.2, 0.1]}}, mass: 1.0}
"""


def get(url: str) -> str:
    with urllib.request.urlopen(url, timeout=10) as response:
        return response.read().decode("utf-8")


def wait_for(url: str, version: str) -> None:
    for _ in range(100):
        if get(url + "version") == version:
            return
        time.sleep(0.1)
    raise AssertionError(f"the page never reached version {version}")


@pytest.fixture
def served(tmp_path):
    spec = tmp_path / "watched.yaml"
    spec.write_text(SPEC, encoding="utf-8")
    command = [sys.executable, "-m", "xacrokit.cli", "view", str(spec), "--watch", "--port", "0"]
    process = subprocess.Popen(command, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    line = process.stdout.readline()
    assert line.startswith("gen-robot view: serving http://127.0.0.1:"), (line, process.stderr.read())
    url = line.split("serving ", 1)[1].split(" ", 1)[0]
    yield spec, url
    process.terminate()
    process.wait(timeout=10)


def test_a_saved_change_is_served_and_a_mistake_shows_its_error(served):
    spec, url = served
    assert get(url + "version") == "1" and '"base_link"' in get(url)
    time.sleep(0.05)
    spec.write_text(
        SPEC + "  arm_link: {shape: {sphere: {radius: 0.05}}, mass: 0.5}\njoints:\n"
        "  j: {type: fixed, parent: base_link, child: arm_link}\n",
        encoding="utf-8",
    )
    wait_for(url, "2")
    assert '"arm_link"' in get(url)
    spec.write_text(SPEC.replace("mass: 1.0", "mass: -1.0"), encoding="utf-8")
    wait_for(url, "3")
    page = get(url)
    assert "The robot does not build" in page and "watched.yaml:3" in page and "mass must be &gt; 0 kg" in page
    assert get(url + "version") == "3"
    with pytest.raises(urllib.error.HTTPError):
        get(url + "anything_else")


def test_the_browser_reloads_the_page_by_itself(served, browser):
    try:
        spec, url = served
        browser.get(url)
        for _ in range(100):
            if browser.execute_script("return !!(window.xacrokit && window.xacrokit.ready)"):
                break
            time.sleep(0.05)
        assert browser.execute_script("return window.xacrokit.links()") == ["base_link"]
        spec.write_text(SPEC + "  extra: {}\njoints:\n  j: {type: fixed, parent: base_link, child: extra}\n")
        for _ in range(100):
            links = browser.execute_script("return window.xacrokit && window.xacrokit.ready && window.xacrokit.links()")
            if links == ["base_link", "extra"]:
                break
            time.sleep(0.1)
        assert links == ["base_link", "extra"]
    finally:
        browser.get("about:blank")  # (the session's browser: leave it on no page of this server)


def test_view_without_output_or_watch_is_a_usage_error(tmp_path):
    result = subprocess.run(
        [sys.executable, "-m", "xacrokit.cli", "view", str(REPO / "examples" / "robots" / "rover.yaml")],
        capture_output=True,
        text=True,
        timeout=120,
    )
    assert result.returncode == 2 and "needs -o PAGE.html" in result.stderr


def raw_request(url: str, request: bytes, *, read: bool = True) -> bytes:
    """Send ``request`` as it is on a socket to the server of ``url``; what came back (nothing when not ``read``)."""
    import socket

    host, port = url.split("//", 1)[1].rstrip("/").split(":")
    with socket.create_connection((host, int(port)), timeout=10) as connection:
        connection.sendall(request)
        if not read:
            return b""
        chunks = []
        while chunk := connection.recv(65536):
            chunks.append(chunk)
        return b"".join(chunks)


def test_a_request_for_another_host_is_refused(served):
    """DNS rebinding: a page of evil.example whose name resolves to 127.0.0.1 sends Host: evil.example."""
    _, url = served
    port = url.rstrip("/").rsplit(":", 1)[1]
    refused = raw_request(
        url, b"GET / HTTP/1.1\r\nHost: evil.example:" + port.encode() + b"\r\nConnection: close\r\n\r\n"
    )
    assert refused.startswith(b"HTTP/1.0 403") and b"base_link" not in refused
    assert raw_request(url, b"GET / HTTP/1.1\r\nConnection: close\r\n\r\n").startswith(b"HTTP/1.0 403")  # (no Host)
    served_page = raw_request(url, f"GET / HTTP/1.1\r\nHost: localhost:{port}\r\nConnection: close\r\n\r\n".encode())
    assert served_page.startswith(b"HTTP/1.0 200") and b"base_link" in served_page


def test_clients_that_go_away_or_stay_silent_leave_no_traceback(tmp_path, monkeypatch, capfd):
    """Many clients that disconnect before the answer, and more open connections than the bound: the server keeps
    serving, says nothing on stderr, and closes a silent connection after its idle timeout (1 s here)."""
    import socket
    import threading

    from xacrokit.view import watch_server

    monkeypatch.setattr(watch_server, "IDLE_TIMEOUT", 1.0)
    watcher = watch_server.Watcher(lambda version: f"<html>base_link {version}</html>", tmp_path)
    said: list[str] = []
    stop = threading.Event()
    thread = threading.Thread(target=watcher.serve, args=(0,), kwargs={"announce": said.append, "stop": stop})
    thread.start()
    try:
        for _ in range(100):
            if said:
                break
            time.sleep(0.05)
        url = said[0].split("serving ", 1)[1].split(" ", 1)[0]
        port = int(url.rstrip("/").rsplit(":", 1)[1])
        host = f"Host: 127.0.0.1:{port}\r\n".encode()
        for _ in range(200):  # (each asks for the page and resets at once: the answer meets a closed socket)
            with socket.create_connection(("127.0.0.1", port), timeout=5) as early:
                early.setsockopt(socket.SOL_SOCKET, socket.SO_LINGER, b"\x01\x00\x00\x00\x00\x00\x00\x00")
                early.sendall(b"GET / HTTP/1.1\r\n" + host + b"\r\n")
        time.sleep(0.5)  # (their handlers done: every slot free again)
        bound = watch_server.MAX_CONNECTIONS
        silent = [socket.create_connection(("127.0.0.1", port), timeout=30) for _ in range(bound)]
        time.sleep(0.2)
        extra = socket.create_connection(("127.0.0.1", port), timeout=5)
        assert extra.recv(1) == b""  # (over the bound: closed at once)
        extra.close()
        started = time.monotonic()
        assert silent[0].recv(1) == b""  # (closed by the idle timeout)
        assert time.monotonic() - started < 5
        for connection in silent:
            connection.close()
        time.sleep(0.2)
        assert "base_link" in get(url)
    finally:
        stop.set()
        thread.join(timeout=10)
    err = capfd.readouterr().err
    assert "Traceback" not in err and "BrokenPipe" not in err and "ConnectionReset" not in err, err
