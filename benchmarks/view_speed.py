"""How fast and how small gen-robot view's page is (issue 17, item 7; issue 33, item 5), measured in one run on this
machine, in headless Chromium:

- a fleet of 1,000 links (the diff-drive example, 9 links, x 111, and the world): the time from asking for the page
  to ``window.xacrokit`` being ready with the robot drawn once (target under 1 s; issue 17's was 2 s);
- a 100+-link robot (the same fleet x 12: 109 links): one ``setJoints`` with every wheel moved, which re-poses every
  link and draws the frame, timed inside the page with performance.now(), median of 50 (target under 16 ms, one
  frame);
- example-robot-data's Panda and Go1 (from the test extra; left out when it is not installed): the page's size
  (targets under 3 MB and 8 MB), the time ``gen-robot view`` takes to make it, as a process, and the time the page
  takes to open (no target).

Needs Debian's chromium and chromium-driver (and selenium). Usage:

    python benchmarks/view_speed.py [--fleets BIG SMALL] [--moves N] [--real NAME ...]

``--fleets`` the robots of the two fleets (default 111 12: 1,000 and 109 links), ``--moves`` the joint moves timed
(default 50), ``--real`` the real robots (default Panda Go1; none: ``--real``). Smaller ones measure less but run
the same steps (tests/test_benchmarks.py runs it so).
"""

from __future__ import annotations

import argparse
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


REAL = (("Panda", "panda_description/urdf/panda.urdf", 3.0), ("Go1", "go1_description/urdf/go1.urdf", 8.0))


def real_pages(folder: Path, names: list[str]) -> list[tuple[str, Path, float, float]]:
    """example-robot-data's pages of the robots ``names`` of REAL: (name, page, seconds gen-robot view took, target
    in MB); none when example-robot-data is not installed."""
    shares = [Path(entry, "cmeel.prefix", "share", "example-robot-data") for entry in sys.path]
    share = next((candidate for candidate in shares if candidate.is_dir()), None)
    if share is None:
        print("example-robot-data is not installed: no Panda or Go1 page (pip install -e '.[test]')")
        return []
    found = []
    for name, urdf, target in (row for row in REAL if row[0] in names):
        html = folder / f"{name}.html"
        command = [sys.executable, "-m", "xacrokit.cli", "view", str(share / "robots" / urdf), "-o", str(html)]
        start = time.perf_counter()
        subprocess.run([*command, "--package", f"example-robot-data={share}"], check=True, capture_output=True)
        found.append((name, html, time.perf_counter() - start, target))
    return found


def opened(browser, html: Path) -> float:
    """Seconds from asking for the page to its robot drawn and ``window.xacrokit`` ready."""
    browser.get("about:blank")
    start = time.perf_counter()
    browser.get(html.as_uri())
    while not browser.execute_script("return !!(window.xacrokit && window.xacrokit.ready)"):
        time.sleep(0.005)
    return time.perf_counter() - start


def arguments() -> argparse.Namespace:
    parser = argparse.ArgumentParser(description="gen-robot view's pages timed in headless Chromium")
    parser.add_argument("--fleets", type=int, nargs=2, default=[111, 12], metavar=("BIG", "SMALL"))
    parser.add_argument("--moves", type=int, default=50, help="joint moves timed (their median printed)")
    parser.add_argument("--real", nargs="*", default=[name for name, _, _ in REAL], choices=[n for n, _, _ in REAL])
    return parser.parse_args()


def main() -> None:
    if not (shutil.which("chromium") and shutil.which("chromedriver")):
        raise SystemExit("chromium and chromedriver are not installed")
    asked = arguments()
    with tempfile.TemporaryDirectory() as scratch:
        folder = Path(scratch)
        big, big_links = fleet_page(folder, asked.fleets[0])
        small, small_links = fleet_page(folder, asked.fleets[1])
        real = real_pages(folder, asked.real)
        browser = driver()
        try:
            print(f"{big_links}-link fleet page: open and draw {opened(browser, big):.2f} s (target < 1 s)")
            opened(browser, small)
            times = browser.execute_script(
                """
                const names = window.xacrokit.joints(), out = [];
                for (let k = 0; k < arguments[0]; k++) {
                  const values = Object.fromEntries(names.map((n) => [n, Math.sin(k + n.length)]));
                  const start = performance.now();
                  window.xacrokit.setJoints(values);
                  out.push(performance.now() - start);
                }
                return out;
                """,
                asked.moves,
            )
            print(
                f"{small_links}-link robot: a joint move re-poses and draws in {statistics.median(times):.2f} ms "
                f"(median of {asked.moves}; target < 16 ms)"
            )
            for name, html, made, target in real:
                size = html.stat().st_size / 1e6
                print(
                    f"{name} page: {size:.2f} MB (target < {target:.0f} MB), made in {made:.2f} s, "
                    f"open and draw {opened(browser, html):.2f} s"
                )
        finally:
            browser.quit()


if __name__ == "__main__":
    main()
