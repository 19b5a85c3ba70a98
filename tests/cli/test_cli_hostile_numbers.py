"""Numbers a URDF may hold that no robot has (1e308, 1e-320, 0, negative sizes), through every command that reads a
URDF (issue 28): no exit 70, no traceback; export writes only a model MuJoCo loads, else exit 2 naming the element
and attribute; size never passes a result that is not a finite number."""

from __future__ import annotations

import contextlib
import io
import re

import mujoco
import pytest

import xacrokit.cli.app

URDF = """<robot name="r">
<material name="m"><color rgba="@RGBA@ 0.5 0.5 1"/></material>
<link name="base_link"><inertial><mass value="1"/><inertia ixx="0.01" iyy="0.01" izz="0.01"/></inertial>
<visual><geometry><box size="@B@ 0.1 0.1"/></geometry><material name="m"/></visual>
<collision><geometry><cylinder radius="@R@" length="0.1"/></geometry></collision></link>
<joint name="j" type="revolute"><parent link="base_link"/><child link="arm"/><origin xyz="0 0 @Z@"/>
<axis xyz="@AX@ 1 0"/><limit lower="-1" upper="1" effort="10" velocity="1"/></joint>
<link name="arm"><inertial><mass value="@M@"/><inertia ixx="0.001" iyy="0.001" izz="0.001"/></inertial>
<visual><geometry><sphere radius="0.05"/></geometry></visual></link>
</robot>"""
GOOD = {"RGBA": "0.5", "B": "0.2", "R": "0.05", "Z": "0.1", "AX": "0", "M": "0.5"}
# each once ended in exit 70 (render, check) or in a model MuJoCo refuses (export), found by a sweep of 225 files
CASES = [
    ("RGBA", "1e308"),
    ("M", "1e-320"),
    ("B", "1e308"),
    ("B", "-1e308"),
    ("B", "0"),
    ("R", "1e300"),
    ("R", "-1"),
    ("Z", "1e308"),
    ("AX", "1e308"),
]
COMMANDS = {
    "export": ["export", "{urdf}", "--mjcf", "-o", "{out}/m.xml"],
    "render": ["render", "{urdf}", "--size", "64x48", "-o", "{out}/r.png"],
    "view": ["view", "{urdf}", "-o", "{out}/v.html"],
    "import": ["import", "{urdf}", "-o", "{out}/r.yaml"],
    "check": ["check", "{urdf}"],
    "size": ["size", "{urdf}"],
}


def run(argv: list[str]) -> tuple[int, str, str]:
    err, out = io.StringIO(), io.StringIO()
    with contextlib.redirect_stderr(err), contextlib.redirect_stdout(out):
        try:
            code = xacrokit.cli.app.main(argv)
        except SystemExit as exc:
            code = exc.code if isinstance(exc.code, int) else 2
    return code, err.getvalue(), out.getvalue()


@pytest.mark.parametrize(("key", "value"), CASES)
def test_a_number_no_robot_has_gets_an_honest_exit_from_every_command(tmp_path, key, value):
    text = URDF
    for name, good in GOOD.items():
        text = text.replace(f"@{name}@", value if name == key else good)
    urdf = tmp_path / "r.urdf"
    urdf.write_text(text, encoding="utf-8")
    for command, words in COMMANDS.items():
        out = tmp_path / command
        code, err, printed = run([w.replace("{urdf}", str(urdf)).replace("{out}", str(out)) for w in words])
        assert code in (0, 1, 2) and "Traceback" not in err and "internal error" not in err, (command, code, err)
        if command == "export" and code == 0:
            mujoco.MjModel.from_xml_path(str(out / "m.xml"))  # (raises for a model MuJoCo refuses)
        if command == "export" and code == 2:
            assert re.search(r"(link|joint) '\w+'", err), err
        if command == "size" and code == 0:
            assert not re.search(r"\b(nan|inf)\b", printed), printed
        if code == 2:
            assert not out.exists() or not any(out.iterdir()), command
