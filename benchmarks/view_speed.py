"""How fast gen-robot view's page is in headless Chromium (issue 17, item 7), measured in one run on this machine:

- a fleet of 1,000 links (the diff-drive example, 9 links, x 111, and the world): the time from asking for the page
  to ``window.xacrokit`` being ready with the robot drawn once (target under 2 s);
- a 100+-link robot (the same fleet x 12: 109 links): one ``setJoints`` with every wheel moved, which re-poses every
  link and draws the frame, timed inside the page with performance.now(), median of 50 (target under 16 ms, one
  frame).

Needs Debian's chromium and chromium-driver (and selenium). Usage: python benchmarks/view_speed.py
"""

from __future__ import annotations

import shutil
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

REPO = Path(__file__).resolve().parent.parent


def driver():
    from selenium import webdriver

    options = webdriver.ChromeOptions()
    options.binary_location = shutil.which("chromium") or ""
    for flag in ("--headless=new", "--no-sandbox", "--use-gl=swiftshader", "--enable-unsafe-swiftshader"):
        options.add_argument(flag)
    options.add_argument("--window-size=1000,700")
    return webdriver.Chrome(
        service=webdriver.ChromeService(executable_path=shutil.which("chromedriver")), options=options
    )


def fleet_page(folder: Path, count: int) -> tuple[Path, int]:
    spec = REPO / "examples" / "robots" / "diff_drive.yaml"
    package = folder / f"fleet{count}"
    subprocess.run(
        [sys.executable, "-m", "xacrokit.cli", "fleet", str(spec), "--count", str(count), "-o", str(package)],
        check=True,
        capture_output=True,
    )
    (urdf,) = (package / "urdf").glob("*.urdf")
    html = folder / f"fleet{count}.html"
    subprocess.run(
        [sys.executable, "-m", "xacrokit.cli", "view", str(urdf), "-o", str(html)], check=True, capture_output=True
    )
    return html, urdf.read_text(encoding="utf-8").count("<link ")


def main() -> None:
    if not (shutil.which("chromium") and shutil.which("chromedriver")):
        raise SystemExit("chromium and chromedriver are not installed")
    with tempfile.TemporaryDirectory() as scratch:
        folder = Path(scratch)
        big, big_links = fleet_page(folder, 111)
        small, small_links = fleet_page(folder, 12)
        browser = driver()
        try:
            browser.get("about:blank")
            start = time.perf_counter()
            browser.get(big.as_uri())
            while not browser.execute_script("return !!(window.xacrokit && window.xacrokit.ready)"):
                time.sleep(0.005)
            opened = time.perf_counter() - start
            print(f"{big_links}-link fleet page: open and draw {opened:.2f} s (target < 2 s)")
            browser.get(small.as_uri())
            while not browser.execute_script("return !!(window.xacrokit && window.xacrokit.ready)"):
                time.sleep(0.005)
            times = browser.execute_script(
                """
                const names = window.xacrokit.joints(), out = [];
                for (let k = 0; k < 50; k++) {
                  const values = Object.fromEntries(names.map((n) => [n, Math.sin(k + n.length)]));
                  const start = performance.now();
                  window.xacrokit.setJoints(values);
                  out.push(performance.now() - start);
                }
                return out;
                """
            )
            print(
                f"{small_links}-link robot: a joint move re-poses and draws in {statistics.median(times):.2f} ms "
                "(median of 50; target < 16 ms)"
            )
        finally:
            browser.quit()


if __name__ == "__main__":
    main()
