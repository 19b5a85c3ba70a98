"""Shared test helpers: hypothesis profiles, expanding xacro snippets, and reading URDF numbers."""

from __future__ import annotations

import ast
import compileall
import os
import re
import shutil
import subprocess
import sys
import tempfile
from pathlib import Path

import numpy as np
import pytest
import yaml
from hypothesis import HealthCheck, settings
from lxml import etree

import xacrokit

REPO = Path(__file__).resolve().parent.parent
# the examples by kind: robot specs; scene specs (the robots only they use in scenes/robots/); the macro-library demo
ROBOT_EXAMPLES = sorted((REPO / "examples" / "robots").glob("*.yaml"))
SCENE_EXAMPLES = sorted((REPO / "examples" / "scenes").glob("*.yaml"))
MACRO_DEMO = REPO / "examples" / "macros" / "macros_demo.urdf.xacro"
# tests loop over these lists: an empty one (examples moved) would let them pass without looking at anything
assert len(ROBOT_EXAMPLES) >= 9 and len(SCENE_EXAMPLES) >= 3 and MACRO_DEMO.is_file(), "examples moved: update conftest"


def pytest_configure(config):
    """Compile the package's modules once, before any test: the tests start gen-robot, check's consumers and the
    benchmarks as processes (hundreds), and an editable install on a machine that sets
    PYTHONDONTWRITEBYTECODE (as CI's does) would compile every module of xacrokit in each of them (about 0.25 s of
    CPU a process). compileall writes only what is missing or stale; a worker of its own runs it too."""
    compileall.compile_dir(Path(xacrokit.__file__).parent, quiet=1)
    # A cache folder of this run's own, which its workers inherit (unless XACROKIT_CACHE names one): every run starts
    # cold, as CI does, so that no test passes on templates, collision matrices or mesh facts an earlier run kept.
    if "PYTEST_XDIST_WORKER" not in os.environ and "XACROKIT_CACHE" not in os.environ:
        config.xacrokit_cache = tempfile.mkdtemp(prefix="xacrokit-test-cache-")
        os.environ["XACROKIT_CACHE"] = config.xacrokit_cache


# The real-robot corpus's tests that read a robot's meshes with trimesh (export, view, import: one test a file each),
# run side by side robot by robot: xacrokit.reader.mesh_copies keeps the meshes a worker read, and the workers
# (pytest-xdist's worksteal) take the tests in runs of the collection's order, so a robot's three tests share its
# meshes' reads. (check reads its meshes with numpy-stl, and keeps their facts in the run's cache folder.)
SHARED_MESH_MODULES = (
    "export/test_export_realworld.py",
    "view/test_view_realworld.py",
    "importer/test_import_realworld.py",
)


def pytest_collection_modifyitems(config, items):
    """The corpus tests of SHARED_MESH_MODULES ordered by robot, where the first of them was collected; every
    other test keeps its place. (The same order in every worker: xdist requires their collections equal.)"""
    by_robot = [
        item
        for item in items
        if item.nodeid.split("::")[0].endswith(SHARED_MESH_MODULES)
        and hasattr(item, "callspec")
        and "key" in item.callspec.params
    ]
    if not by_robot:
        return
    at = items.index(by_robot[0])
    chosen = set(map(id, by_robot))
    rest = [item for item in items if id(item) not in chosen]
    by_robot.sort(key=lambda item: item.callspec.params["key"])  # (stable: a robot's tests in module order)
    items[:] = rest[:at] + by_robot + rest[at:]


def pytest_unconfigure(config):
    folder = getattr(config, "xacrokit_cache", None)
    if folder is not None:
        shutil.rmtree(folder, ignore_errors=True)
        del os.environ["XACROKIT_CACHE"]


# CI keeps example counts modest; HYPOTHESIS_PROFILE=dev (or thorough) raises them locally.
PROFILE_SCALE = {"ci": 1, "dev": 4, "thorough": 40}
PROFILE = os.environ.get("HYPOTHESIS_PROFILE", "ci")
for _name, _scale in PROFILE_SCALE.items():
    settings.register_profile(
        _name, max_examples=25 * _scale, deadline=None, suppress_health_check=[HealthCheck.too_slow]
    )
settings.load_profile(PROFILE)


def budget(examples: int) -> int:
    """A property's own example count in CI (``@settings(max_examples=budget(n))``, its test saying why ``n``: what
    one example costs, what the space holds), raised by the dev and thorough profiles as they raise the default 25."""
    return examples * PROFILE_SCALE.get(PROFILE, 1)


XACRO_HEADER = '<?xml version="1.0"?>\n<robot name="t" xmlns:xacro="http://www.ros.org/wiki/xacro">\n'


def xacro_doc(body: str, includes: tuple[str, ...] = ("inertia",)) -> str:
    """A xacro document including the given public macro files (by stem) through $(find xacrokit)."""
    lines = [f'  <xacro:include filename="$(find xacrokit)/macros/{name}.xacro"/>' for name in includes]
    return XACRO_HEADER + "\n".join(lines) + "\n" + body + "\n</robot>\n"


def expand_text(doc: str, folder: Path, name: str = "doc.urdf.xacro", **kwargs) -> etree._Element:
    """Write ``doc`` to ``folder/name``, expand it with xacrokit.expand, and return the parsed URDF root."""
    path = folder / name
    path.write_text(doc, encoding="utf-8")
    return etree.fromstring(xacrokit.expand(path, **kwargs).encode())


def floats(text: str) -> list[float]:
    return [float(v) for v in text.split()]


def rpy_matrix(roll: float, pitch: float, yaw: float) -> np.ndarray:
    """URDF fixed-axis roll-pitch-yaw: R = Rz(yaw) Ry(pitch) Rx(roll)."""
    cr, sr, cp, sp, cy, sy = np.cos(roll), np.sin(roll), np.cos(pitch), np.sin(pitch), np.cos(yaw), np.sin(yaw)
    rx = np.array([[1, 0, 0], [0, cr, -sr], [0, sr, cr]])
    ry = np.array([[cp, 0, sp], [0, 1, 0], [-sp, 0, cp]])
    rz = np.array([[cy, -sy, 0], [sy, cy, 0], [0, 0, 1]])
    return rz @ ry @ rx


def link_inertial(root: etree._Element, link: str) -> tuple[float, np.ndarray, np.ndarray, np.ndarray]:
    """(mass, 3x3 tensor about the COM in the inertial frame, COM xyz, inertial-frame rotation) of a link."""
    inertial = root.find(f"link[@name='{link}']/inertial")
    assert inertial is not None, f"link {link} has no inertial"
    i = {k: float(v) for k, v in inertial.find("inertia").attrib.items()}
    tensor = np.array([[i["ixx"], i["ixy"], i["ixz"]], [i["ixy"], i["iyy"], i["iyz"]], [i["ixz"], i["iyz"], i["izz"]]])
    origin = inertial.find("origin")
    xyz = np.array(floats(origin.get("xyz", "0 0 0")))
    rot = rpy_matrix(*floats(origin.get("rpy", "0 0 0")))
    return float(inertial.find("mass").get("value")), tensor, xyz, rot


def assert_physical_tensor(tensor: np.ndarray, rel: float = 1e-9) -> None:
    """Positive definite, and principal moments obey the triangle inequality."""
    moments = np.linalg.eigvalsh(tensor)
    assert moments.min() > 0, f"not positive definite: {moments}"
    total = moments.sum()
    for k in range(3):
        assert moments[k] <= total - moments[k] + rel * total, f"triangle inequality violated: {moments}"


@pytest.fixture(scope="session")
def expand(tmp_path_factory):
    """expand(doc_text, **kwargs) -> URDF root. Session-wide (hypothesis-safe): each call rewrites one file.

    The documents are the tests' own, calling the macro library: trusted unless ``trust=False`` is given, so they
    expand in-process (an untrusted expansion forks a bounded child, 15 to 50 ms in a process as large as pytest's,
    thousands of times here). The untrusted path has tests of its own (tests/expand: the guard and the bounds), and
    test_macro_library_expands_untrusted expands every public macro untrusted."""
    folder = tmp_path_factory.mktemp("expand")

    def run(doc: str, **kwargs):
        kwargs.setdefault("trust", True)
        return expand_text(doc, folder, **kwargs)

    return run


def tetrahedron_stl(lift: float = 0.0) -> bytes:
    """A closed tetrahedron of 0.1 m as binary STL (MuJoCo reads only binary STL), raised by ``lift`` metres."""
    import struct

    corners = [(0.0, 0.0, lift), (0.1, 0.0, lift), (0.0, 0.1, lift), (0.0, 0.0, lift + 0.1)]
    faces = ((0, 2, 1), (0, 1, 3), (0, 3, 2), (1, 2, 3))
    data = bytearray(b"xacrokit test tetrahedron".ljust(80, b" ")) + struct.pack("<I", len(faces))
    for face in faces:
        data += struct.pack("<3f", 0.0, 0.0, 0.0)
        for index in face:
            data += struct.pack("<3f", *corners[index])
        data += struct.pack("<H", 0)
    return bytes(data)


def mesh_package_at(folder: Path) -> Path:
    """A package folder holding a binary-STL mesh under every name xacrokit.testing's specs use."""
    from xacrokit.testing import MESH_NAMES

    (folder / "meshes").mkdir(parents=True, exist_ok=True)
    for name in MESH_NAMES:
        (folder / "meshes" / f"{name}.stl").write_bytes(tetrahedron_stl())
    return folder


def assert_refused(code: int, err: str, words: str) -> None:
    """A refusal of bad input: exit 2 with a message holding ``words``, never a traceback nor the internal-error exit.
    ``words`` must say something of this refusal (not just "error", which every message holds), so that a changed
    or wrong message fails the test."""
    assert words.strip() and words.strip().lower() not in ("error", "gen-robot: error"), "say the refusal's words"
    assert code == 2 and words in err, (code, err)
    assert "internal error" not in err and "Traceback" not in err, err


def gen_robot(*args, cwd=None) -> subprocess.CompletedProcess:
    """Run the gen-robot command line as ``python -m xacrokit.cli ARGS`` would, in this process (tests/in_process.py:
    its exit code, its output as text, file descriptors and all, in a working folder, environment, warning filters
    and logging a new process would have). A process of its own costs 0.5 to 1.5 s, most of it starting; a test
    that proves something of the process (a signal, a kill, its imports, the console script, a closed output) uses
    :func:`gen_robot_process`."""
    from in_process import run_main  # (start-up: the command line's modules, imported by the first call)

    return run_main([str(a) for a in args], cwd=cwd)


def gen_robot_process(*args, cwd=None) -> subprocess.CompletedProcess:
    """Run the gen-robot command line in a process of its own with this interpreter; text output captured."""
    command = [sys.executable, "-m", "xacrokit.cli", *map(str, args)]
    return subprocess.run(command, capture_output=True, text=True, cwd=cwd, timeout=300)


def snapshot(root: Path) -> dict[str, tuple[bytes, int]]:
    """Every file under ``root``: relative path -> (content, modification time), to tell that nothing was touched."""
    return {
        p.relative_to(root).as_posix(): (p.read_bytes(), p.stat().st_mtime_ns) for p in root.rglob("*") if p.is_file()
    }


# ------------------------------------------------------------------ independent oracles: textbook DH, check_urdf
def transform(rot: np.ndarray, xyz) -> np.ndarray:
    t = np.eye(4)
    t[:3, :3], t[:3, 3] = rot, xyz
    return t


def rot_x(a):
    return transform(rpy_matrix(a, 0, 0), [0, 0, 0])


def rot_z(a):
    return transform(rpy_matrix(0, 0, a), [0, 0, 0])


def trans(x, y, z):
    return transform(np.eye(3), [x, y, z])


def dh_product(rows, q, convention, origin, tool):
    """The DH chain written out from the textbook definitions, independent of the macro's algebra."""
    total = transform(rpy_matrix(*origin[1]), origin[0])
    for row, value in zip(rows, q, strict=False):
        theta, d = row.get("theta", 0.0), row["d"]
        kind = row.get("type", "revolute")
        if kind in ("revolute", "continuous"):
            theta += value
        elif kind == "prismatic":
            d += value
        if convention == "standard":
            step = rot_z(theta) @ trans(0, 0, d) @ trans(row["a"], 0, 0) @ rot_x(row["alpha"])
        else:
            step = rot_x(row["alpha"]) @ trans(row["a"], 0, 0) @ rot_z(theta) @ trans(0, 0, d)
        total = total @ step
    return total @ transform(rpy_matrix(*tool[1]), tool[0])


def check_urdf_binary() -> str:
    """urdfdom's check_urdf, as pin installs it beside this Python (or on PATH)."""
    found = shutil.which("check_urdf", path=str(Path(sys.executable).parent)) or shutil.which("check_urdf")
    assert found, "check_urdf comes with pin (cmeel-urdfdom); is pin installed?"
    return found


def cmake_commands(text: str) -> list[str]:
    """CMake's command invocations with comments (line and bracket) removed: what cmake would run."""
    text = re.sub(r"#\[(=*)\[.*?\]\1\]", "", text, flags=re.S)  # bracket comments
    text = re.sub(r"#[^\n]*", "", text)  # line comments (our files quote no #)
    return re.findall(r"(?m)^\s*([A-Za-z_][A-Za-z0-9_]*)\s*\(", text)


def parse_generated(path: str, content: str) -> object:
    """The file read by its own parser, with the parts a spec's name may fill (comments, the README) left out."""
    if path.endswith(".py"):
        return ast.dump(ast.parse(content))  # (comments are not in the tree)
    if path.endswith("CMakeLists.txt"):
        return cmake_commands(content)
    if path.endswith((".xml", ".xacro", ".urdf", ".sdf", ".srdf")):
        parser = etree.XMLParser(remove_comments=True, resolve_entities=False, no_network=True)
        return etree.tostring(etree.fromstring(content.encode("utf-8"), parser))
    if path.endswith((".yaml", ".rviz")):  # (libyaml's safe reader where PyYAML has it: ten times the pure Python's)
        return yaml.load(content, Loader=getattr(yaml, "CSafeLoader", yaml.SafeLoader))  # noqa: S506  (a safe one)
    if path.endswith((".obj", ".stl")):  # a mesh made (a tube's) or copied: a closed surface
        import io

        import trimesh

        kind = path.rsplit(".", 1)[1]
        data = io.BytesIO(content if isinstance(content, bytes) else content.encode("utf-8"))
        mesh = trimesh.load(data, file_type=kind, force="mesh")
        assert mesh.is_watertight and mesh.volume > 0, path
        return mesh.vertices.round(12).tolist()
    assert path.endswith(".md"), path
    return None  # Markdown: anything parses


@pytest.fixture(scope="session")
def browser():
    """One headless chromium for the session (tests/browser.py); skips the test when chromium, its driver or
    selenium is missing."""
    pytest.importorskip("selenium.webdriver")
    from browser import CHROMIUM, DRIVER, start_browser

    if not (CHROMIUM and DRIVER):
        pytest.skip("chromium and chromedriver are not installed")
    driver = start_browser()
    yield driver
    driver.quit()
