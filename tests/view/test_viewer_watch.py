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
