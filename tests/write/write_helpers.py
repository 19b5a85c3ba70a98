"""What the interrupted-write and fault-injection tests share: two robots written into one folder, and their clean
packages to compare with."""

from __future__ import annotations

import xacrokit
from conftest import REPO

SPEC_A = REPO / "examples" / "robots" / "two_dof_arm.yaml"


def contents(root):
    """Every file under ``root``: relative path -> bytes; but the robots' extension files (urdf/NAME_extension.xacro):
    those are the user's once written, kept when another robot is written into the folder (never removed), and
    their own lifecycle is tests/write/test_write_extension.py's."""
    return {
        p.relative_to(root).as_posix(): p.read_bytes()
        for p in root.rglob("*")
        if p.is_file() and not (p.parent.name == "urdf" and p.name.endswith("_extension.xacro"))
    }


def two_specs(folder):
    """({"a": spec, "b": spec}, {"a": clean package, "b": clean package}): robot A (two_dof_arm) and robot B, another
    robot (another name, a mass changed), so that some paths are shared (CMakeLists.txt, ...), some only A's or B's."""
    text = SPEC_A.read_text(encoding="utf-8")
    spec_b = folder / "b.yaml"
    spec_b.write_text(text.replace("robot: two_dof_arm", "robot: arm_b").replace("mass: 0.3", "mass: 0.35"))
    assert spec_b.read_text() != text
    clean = {}
    for name, spec in (("a", SPEC_A), ("b", spec_b)):
        xacrokit.generate(spec, folder / f"clean_{name}")
        clean[name] = contents(folder / f"clean_{name}")
    return {"a": SPEC_A, "b": spec_b}, clean
