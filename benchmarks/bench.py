"""xacrokit benchmarks: prints times and ratios measured in this one run (no assertions: machines are noisy).

    python benchmarks/bench.py            # all sections
    python benchmarks/bench.py check      # one section

Sections:
  stages  for chain robots of 10 / 100 / 1,000 / 3,000 links: the time of each stage (load, validate, resolve,
          render, write, emit, xacro expansion of the generated package, check without consumers), full gen-robot
          (all of them but xacro, the check included) and lxml parse+serialize of its URDF; then the ratios
          full / xacro expansion, full / lxml, and t(3,000)/t(1,000) for every stage. Medians of 9 runs (xacro
          once from 1,000 links); each size in a fresh process; 1,000 and 3,000 links in 5 rounds, back to back
          (each round gives a ratio; the median and range are printed). The package is the default one
          (--macros inline); at 1,000 links the --macros copy package is expanded too, for comparison. For
          reference, the ratio of a read-only walk over the loaded spec (no stage does less to the data).
  fleet   the same for gen-robot fleet: 1 / 10 / 100 / 300 copies of a 10-link chain (10 to 3,000 links), the
          stages being scene (load, validate, resolve the scene and its robot), render, write, emit, xacro, check.
  memory  peak resident memory of full gen-robot and gen-robot fleet at each size (each in a fresh process).
  xacro   xacro expansion of our generated 6-axis arm package (UR5), --macros inline (the default) and copy,
          against a hand-written equivalent in plain <link>/<joint> XML.
  check   gen-robot check (our rules, no external consumers) on chains of 10 / 100 / 1,000 / 3,000 links, the
          t(3,000)/t(1,000) ratio (median of back-to-back pairs), the time to report a cycle hanging off the root,
          and the time check_urdf would take to be stopped on it.
  cli     wall time of `gen-robot --help`.
"""

from __future__ import annotations

import gc
import json
import shutil
import statistics
import subprocess
import sys
import tempfile
import time
from collections.abc import Callable
from pathlib import Path

RUNS = 5
SIZES = (10, 100, 1000, 3000)
REPO = Path(__file__).resolve().parent.parent


STAGE_RUNS = 9  # for the stage tables (xacro itself runs once from 1,000 links up: it takes seconds)


def chain_spec(links: int) -> str:
    """A robot spec: a chain of box links on revolute joints."""
    lines = ["robot: chain", "materials: {gray: [0.5, 0.5, 0.5, 1.0]}", "links:"]
    lines += [
        f"  link_{i}: {{shape: {{box: {{size: [0.1, 0.1, 0.1]}}}}, mass: 1.0, material: gray}}" for i in range(links)
    ]
    lines.append("joints:" if links > 1 else "joints: {}")
    lines += [
        f"  joint_{i}: {{type: revolute, parent: link_{i - 1}, child: link_{i}, origin: {{xyz: [0, 0, 0.1]}}, "
        "axis: [0, 0, 1], limit: {lower: -1, upper: 1, effort: 1, velocity: 1}, dynamics: {damping: 0.1}}"
        for i in range(1, links)
    ]
    return "\n".join(lines) + "\n"


def median_time(action: Callable[[], object], runs: int = RUNS, before: Callable[[], None] | None = None) -> float:
    """Median wall time of ``action``. Its result is released after the clock stops: in the pipeline a stage's
    output lives on into the next stage, and a process frees it at exit. Garbage from earlier work is collected before
    the clock starts, and ``before`` (if given) runs then too."""
    times = []
    for _ in range(runs):
        if before is not None:
            before()
        gc.collect()  # garbage left by earlier work (xacro's DOM trees are cyclic) is not this action's cost
        start = time.perf_counter()
        result = action()
        times.append(time.perf_counter() - start)
        del result
    return statistics.median(times)


def chain_urdf(links: int) -> str:
    """A valid serial chain: box links with their inertia, revolute joints with limits and dynamics."""
    parts = ['<?xml version="1.0"?>', '<robot name="chain">']
    inertia = (
        'ixx="0.0016666666666666668" ixy="0" ixz="0" iyy="0.0016666666666666668" iyz="0" izz="0.0016666666666666668"'
    )
    for i in range(links):
        parts.append(
            f'<link name="link_{i}"><visual><geometry><box size="0.1 0.1 0.1"/></geometry></visual>'
            f'<collision><geometry><box size="0.1 0.1 0.1"/></geometry></collision>'
            f'<inertial><mass value="1.0"/><inertia {inertia}/></inertial></link>'
        )
        if i:
            parts.append(
                f'<joint name="joint_{i}" type="revolute"><parent link="link_{i - 1}"/><child link="link_{i}"/>'
                '<origin xyz="0 0 0.1"/><axis xyz="0 0 1"/><limit lower="-1" upper="1" effort="1" velocity="1"/>'
                '<dynamics damping="0.1" friction="0"/></joint>'
            )
    parts.append("</robot>")
    return "\n".join(parts)


ROOTED_CYCLE = (
    '<robot name="rc"><link name="root"/><link name="a"/><link name="b"/>'
    '<joint name="ra" type="fixed"><parent link="root"/><child link="a"/></joint>'
    '<joint name="ab" type="fixed"><parent link="a"/><child link="b"/></joint>'
    '<joint name="ba" type="fixed"><parent link="b"/><child link="a"/></joint></robot>'
)


def bench_check(folder: Path) -> None:
    from xacrokit.check import check
    from xacrokit.check.consumers import run_consumer

    print("== check (our rules, no external consumers), median of", STAGE_RUNS, "runs")
    paths = {}
    for links in (10, 100, 1000, 3000):
        paths[links] = folder / f"chain_{links}.urdf"
        paths[links].write_text(chain_urdf(links), encoding="utf-8")
        report = check(paths[links], consumers=[])
        assert not report.findings, report.findings[:3]  # the benchmark robot itself must be clean
    times = {links: median_time(lambda path=paths[links]: check(path, consumers=[])) for links in (10, 100)}
    pairs = [  # 1,000 and 3,000 links back to back, so that the machine's drift hits both alike
        (
            median_time(lambda: check(paths[1000], consumers=[]), 1),
            median_time(lambda: check(paths[3000], consumers=[]), 1),
        )
        for _ in range(STAGE_RUNS)
    ]
    times[1000] = statistics.median(a for a, _ in pairs)
    times[3000] = statistics.median(b for _, b in pairs)
    for links, seconds in times.items():
        print(f"  {links:>5} links: {seconds * 1000:8.1f} ms")
    ratios = sorted(b / a for a, b in pairs)
    print(
        f"  ratio t(3000)/t(1000), median of {STAGE_RUNS} back-to-back pairs: {statistics.median(ratios):.2f} "
        f"({ratios[0]:.2f}-{ratios[-1]:.2f})   (target <= 3.5; linear would be 3.0)"
    )
    print(f"  1,000 links: {times[1000]:.3f} s   (target < 1 s)")
    cycle = folder / "rooted_cycle.urdf"
    cycle.write_text(ROOTED_CYCLE, encoding="utf-8")
    report_time = median_time(lambda: check(cycle))
    rules = sorted({f.rule for f in check(cycle).findings})
    print(f"  rooted cycle reported ({', '.join(rules)}) with consumers on: {report_time:.3f} s   (target < 1 s)")
    start = time.perf_counter()
    forced = run_consumer("check_urdf", cycle, timeout=30)
    print(
        f"  check_urdf forced on the rooted cycle: {forced.status} after {time.perf_counter() - start:.3f} s "
        f"({forced.message})"
    )


def full_job(spec: Path, out: Path) -> None:
    """What gen-robot SPEC does (the package, then check's rules on its URDF for the warnings it says), plus the check
    without consumers."""
    from xacrokit.check import check, generation_warnings
    from xacrokit.pipeline import generate

    result = generate(spec, out, force=True)
    generation_warnings(result)
    check(out / "urdf" / f"{result.name}.urdf", consumers=[])


def touch(node: object) -> int:
    """Read every mapping and list of loaded spec data, building nothing: what merely touching the data costs."""
    if type(node) is dict:
        return sum(touch(value) for value in node.values()) + 1
    if type(node) is list:
        return sum(touch(value) for value in node) + 1
    return 0


def measure_size(links: int, folder: Path) -> dict[str, float]:
    """Time every stage for a chain robot of ``links`` links."""
    from xacrokit.emit import emit_urdf
    from xacrokit.load import load_file
    from xacrokit.pipeline import emitted_urdf, expand_package
    from xacrokit.render import render_package
    from xacrokit.resolve import resolve
    from xacrokit.validate import validate

    spec = folder / f"chain_{links}.yaml"
    spec.write_text(chain_spec(links), encoding="utf-8")
    raw = load_file(spec)
    valid = validate(raw)
    robot = resolve(valid)
    files = render_package(robot)
    urdf = emit_urdf(robot)
    runs = STAGE_RUNS
    row = {
        "load": median_time(lambda: load_file(spec), runs),
        "validate": median_time(lambda: validate(raw), runs),
        "touch": median_time(lambda: touch(raw.data), runs),  # not a stage: the floor for a walk over the spec
        "resolve": median_time(lambda: resolve(valid), runs),
        "render": median_time(lambda: render_package(robot), runs),
        "emit": median_time(lambda: emit_urdf(robot), runs),
        "xacro": median_time(lambda: expand_package(robot, files), 1 if links >= 1000 else runs),
        **output_rows(
            f"chain_{links}", [*files, emitted_urdf(robot.name, urdf)], urdf, lambda out: full_job(spec, out), folder
        ),
    }
    if links == 1000:  # the package written with --macros copy (library macro calls), for comparison
        copy_files = render_package(robot, macros="copy")
        row["xacro_copy"] = median_time(lambda: expand_package(robot, copy_files), 1)
    return row


def output_rows(tag: str, package: list, urdf: str, full: Callable[[Path], None], folder: Path) -> dict[str, float]:
    """The rows every kind of benchmark robot shares: write, check, full (into a new folder each run) and lxml."""
    from lxml import etree

    from xacrokit.check import check
    from xacrokit.write.package_writer import write

    urdf_path = folder / f"{tag}.urdf"
    urdf_path.write_text(urdf, encoding="utf-8")
    runs = STAGE_RUNS
    return {
        "write": median_time(*into_new_folder(folder / f"{tag}_write", lambda out: write(package, out))),
        "check": median_time(lambda: check(urdf_path, consumers=[]), runs),
        "full": median_time(*into_new_folder(folder / f"{tag}_full", full)),
        "lxml": median_time(lambda: etree.tostring(etree.fromstring(urdf.encode())), runs),
    }


def into_new_folder(base: Path, job: Callable[[Path], object]) -> tuple[Callable[[], object], int, Callable[[], None]]:
    """Arguments for :func:`median_time`: ``job`` into a new folder each run, the previous run's folder deleted
    before the clock starts. A user generates one package; hundreds of MB of earlier runs' files in the page cache
    slow the kernel's writes (at 3,000 links to three times what one write of the same files takes)."""
    folders = (base.with_name(f"{base.name}_{n}") for n in range(10**6))
    current = [next(folders)]

    def clear() -> None:
        shutil.rmtree(current[0], ignore_errors=True)
        current[0] = next(folders)

    return (lambda: job(current[0])), STAGE_RUNS, clear


FLEET_ROBOT_LINKS = 10


def fleet_job(spec: Path, count: int, out: Path) -> None:
    """What gen-robot fleet SPEC --count COUNT does, plus the check without consumers."""
    from xacrokit.check import check
    from xacrokit.pipeline import generate_scene
    from xacrokit.scene import fleet_scene

    scene = fleet_scene(spec, count)
    generate_scene(scene, out, force=True)
    check(out / "urdf" / f"{scene.name}.urdf", consumers=[])


def measure_fleet(links: int, folder: Path) -> dict[str, float]:
    """Time every stage for a fleet of 10-link chain robots with ``links`` links in all."""

    from xacrokit.emit import emit_scene_urdf
    from xacrokit.pipeline import emitted_urdf, expand_package
    from xacrokit.render import render_scene
    from xacrokit.scene import fleet_scene

    count = links // FLEET_ROBOT_LINKS
    spec = folder / "fleet_robot.yaml"
    spec.write_text(chain_spec(FLEET_ROBOT_LINKS), encoding="utf-8")
    scene = fleet_scene(spec, count)
    files = render_scene(scene)
    urdf = emit_scene_urdf(scene)
    runs = STAGE_RUNS
    row = {
        "scene": median_time(lambda: fleet_scene(spec, count), runs),  # load, validate, resolve: scene and robot
        "render": median_time(lambda: render_scene(scene), runs),
        "emit": median_time(lambda: emit_scene_urdf(scene), runs),
        "xacro": median_time(lambda: expand_package(scene, files), 1 if links >= 1000 else runs),
        **output_rows(
            f"fleet_{links}",
            [*files, emitted_urdf(scene.name, urdf)],
            urdf,
            lambda out: fleet_job(spec, count, out),
            folder,
        ),
    }
    if links == 1000:  # the package written with --macros copy (library macro calls), for comparison
        copy_files = render_scene(scene, macros="copy")
        row["xacro_copy"] = median_time(lambda: expand_package(scene, copy_files), 1)
    return row


def measured_apart(kind: str, links: int, folder: Path) -> dict[str, float]:
    """One size's row, measured in a fresh interpreter: the heap an earlier size leaves behind (xacro's DOM trees run
    to hundreds of MB) would otherwise slow the next size's stages and skew t(3,000)/t(1,000)."""
    out = subprocess.run(
        [sys.executable, str(Path(__file__).resolve()), "_row", kind, str(links), str(folder)],
        capture_output=True,
        text=True,
        check=True,
    )
    return json.loads(out.stdout.splitlines()[-1])


ROUNDS = 5  # the two largest sizes are measured this many times, alternately (see print_table)


def print_table(title: str, names: tuple[str, ...], kind: str, folder: Path) -> None:
    """The stage table. 1,000 and 3,000 links are measured in ROUNDS rounds, one of each size back to back per round:
    the machine is shared and its speed drifts over minutes, so each round's t(3,000)/t(1,000) pairs measurements
    taken close together. The table shows the medians over the rounds; the ratios are the medians of the rounds'
    ratios, with their range."""
    print(title)
    print("  " + f"{'links':>6}" + "".join(f"{n:>10}" for n in names))
    small = {links: measured_apart(kind, links, folder) for links in SIZES[:2]}
    rounds = [{links: measured_apart(kind, links, folder) for links in (1000, 3000)} for _ in range(ROUNDS)]
    table = {
        **small,
        **{
            links: {n: statistics.median(r[links][n] for r in rounds) for n in rounds[0][links]}
            for links in (1000, 3000)
        },
    }
    for links in SIZES:
        print("  " + f"{links:>6}" + "".join(f"{table[links][n]:>10.4f}" for n in names))
    big = table[1000]
    target = "target" if kind == "fleet" else "the fleet's target"  # issue 6 sets these two for the fleet
    print(f"  full / xacro expansion at 1,000 links: {big['full'] / big['xacro']:.3f}   ({target} <= 0.5)")
    print(
        f"  (xacro expansion of the --macros copy package at 1,000 links: {big['xacro_copy']:.2f} s; "
        f"full / that: {big['full'] / big['xacro_copy']:.3f})"
    )
    print(f"  full / lxml parse+serialize at 1,000 links: {big['full'] / big['lxml']:.1f}   ({target} <= 30)")
    print(
        f"  t(3,000)/t(1,000), median of {ROUNDS} rounds (range):   (target <= 3.5 for our stages; xacro is not ours)"
    )
    for n in names:
        each = sorted(r[3000][n] / r[1000][n] for r in rounds)
        print(f"    {n:<9} {statistics.median(each):.2f}  ({each[0]:.2f}-{each[-1]:.2f})")
    if "touch" in rounds[0][1000]:
        each = sorted(r[3000]["touch"] / r[1000]["touch"] for r in rounds)
        print(
            f"    (not a stage: a read-only walk over the loaded spec, building nothing: {statistics.median(each):.2f} "
            f"({each[0]:.2f}-{each[-1]:.2f}); what this machine's caches make of 3x the data)"
        )


def bench_fleet(folder: Path) -> None:
    names = ("scene", "render", "write", "emit", "xacro", "check", "full", "lxml")
    title = (
        f"== fleet stages: gen-robot fleet of {FLEET_ROBOT_LINKS}-link chains, the links in all "
        f"(seconds; median of 9 runs, from 1,000 links of {ROUNDS} rounds; xacro once a round from 1,000 links)"
    )
    print_table(title, names, "fleet", folder)


def bench_stages(folder: Path) -> None:
    names = ("load", "validate", "resolve", "render", "write", "emit", "xacro", "check", "full", "lxml")
    title = (
        f"== stages: one chain robot (seconds; median of 9 runs, from 1,000 links of {ROUNDS} rounds; "
        "xacro once a round from 1,000)"
    )
    print_table(title, names, "stages", folder)


def peak_memory_mb(call: str = "pass") -> float:
    """Peak resident memory (MB) of a fresh interpreter that imports xacrokit and runs ``call`` (Python, with
    ``bench`` and ``Path`` in scope)."""
    # VmHWM belongs to the new process image; ru_maxrss would also count the parent's pages from before exec
    script = (
        "import sys; sys.path.insert(0, sys.argv[1]); import bench; from pathlib import Path; "
        f"import xacrokit.pipeline, xacrokit.check; {call}; "
        "print([l.split()[1] for l in open('/proc/self/status') if l.startswith('VmHWM')][0])"
    )
    out = subprocess.run(
        [sys.executable, "-c", script, str(REPO / "benchmarks")], capture_output=True, text=True, check=True
    )
    return int(out.stdout.split()[-1]) / 1024


def bench_memory(folder: Path) -> None:
    print("== memory: peak resident memory of full gen-robot / gen-robot fleet, each in a fresh process (MB)")
    print(f"  the interpreter with xacrokit imported, no work: {peak_memory_mb():.0f}")
    robot = folder / "fleet_robot_memory.yaml"
    robot.write_text(chain_spec(FLEET_ROBOT_LINKS), encoding="utf-8")
    print(f"  {'links':>6}{'robot':>8}{'fleet':>8}")
    for links in SIZES:
        spec = folder / f"chain_{links}_memory.yaml"
        spec.write_text(chain_spec(links), encoding="utf-8")
        one = peak_memory_mb(f"bench.full_job(Path({str(spec)!r}), Path({str(folder / f'mem_robot_{links}')!r}))")
        many = peak_memory_mb(
            f"bench.fleet_job(Path({str(robot)!r}), {links // FLEET_ROBOT_LINKS}, "
            f"Path({str(folder / f'mem_fleet_{links}')!r}))"
        )
        print(f"  {links:>6}{one:>8.0f}{many:>8.0f}")
    print("  target at 3,000 links: <= 300 MB")


def bench_xacro_cost(folder: Path) -> None:
    from xacrokit.emit import emit_urdf
    from xacrokit.expansion.xacro_expand import expand_file
    from xacrokit.pipeline import build_robot, generate

    print("== xacro cost of the generated package (6-axis arm, UR5), median of 7 expansions")
    spec = REPO / "examples" / "robots" / "industrial_arm_std_dh.yaml"
    plain = folder / "ur5_plain.urdf.xacro"  # the same robot written by hand as plain <link>/<joint> XML
    urdf = emit_urdf(build_robot(spec)).replace(
        '<robot name="ur5">', '<robot name="ur5" xmlns:xacro="http://www.ros.org/wiki/xacro">'
    )
    plain.write_text(urdf, encoding="utf-8")
    hand = median_time(lambda: expand_file(plain), 7)
    print(f"  hand-written plain XML: {hand:.4f} s")
    # the entry is the arguments and one call of the robot macro (issue 12): xacro copies the macro's body once more
    for mode in ("inline", "copy"):  # inline is the default
        generate(spec, folder / f"ur5_{mode}", force=True, macros=mode)
        entry = folder / f"ur5_{mode}" / "urdf" / "ur5.urdf.xacro"
        ours = median_time(lambda entry=entry: expand_file(entry), 7)
        target = "   (target <= 2)" if mode == "inline" else "   (no target: the library's own macros at work)"
        print(f"  generated package, --macros {mode}: {ours:.4f} s; ratio {ours / hand:.2f}{target}")


def bench_cli() -> None:
    print("== cli")
    command = [sys.executable, "-m", "xacrokit.cli", "--help"]
    wall = median_time(lambda: subprocess.run(command, capture_output=True, check=True))
    print(f"  gen-robot --help: {wall:.3f} s   (target <= 0.15 s)")


def main(argv: list[str]) -> int:
    if argv[:1] == ["_row"]:  # (the child process of measured_apart)
        kind, links, folder = argv[1], int(argv[2]), Path(argv[3])
        measure = measure_size if kind == "stages" else measure_fleet
        print(json.dumps(measure(links, folder)))
        return 0
    sections = set(argv) or {"stages", "fleet", "memory", "xacro", "check", "cli"}
    print(f"python {sys.version.split()[0]} on {sys.platform}; {time.strftime('%Y-%m-%d %H:%M:%S')}")
    with tempfile.TemporaryDirectory(prefix="xacrokit-bench-") as folder:
        if "stages" in sections:
            bench_stages(Path(folder))
        if "fleet" in sections:
            bench_fleet(Path(folder))
        if "memory" in sections:
            bench_memory(Path(folder))
        if "xacro" in sections:
            bench_xacro_cost(Path(folder))
        if "check" in sections:
            bench_check(Path(folder))
        if "cli" in sections:
            bench_cli()
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
