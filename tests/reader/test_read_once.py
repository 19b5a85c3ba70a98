"""One robot, read once (issue 40): every command that takes a robot parses its URDF text once and builds its pinocchio
model at most once in its own process (check's independent consumers aside: they run in processes of their own), on
a URDF, a xacro document and a spec alike. The counters wrap lxml's parse of any text holding the robot and
pinocchio's URDF reader; the companion test shows they count a second read when there is one."""

from __future__ import annotations

import re
from pathlib import Path

import pinocchio
import pytest
from lxml import etree

from conftest import REPO
from xacrokit.cli import main
from xacrokit.reader.read_robot import read_robot

SPEC = REPO / "examples" / "robots" / "planar_2dof.yaml"
ROBOT_NAME = "planar_2dof"


class Counters:
    """Parses of a text that holds the robot's <robot name=...> element, and pinocchio models built from XML."""

    def __init__(self, monkeypatch: pytest.MonkeyPatch) -> None:
        self.parses = 0
        self.builds = 0
        marker = re.compile(rb"<robot\b[^>]*\bname=[\"']" + ROBOT_NAME.encode())

        def counted(original):
            def parse(data, *args, **kwargs):
                raw = data.encode("utf-8") if isinstance(data, str) else data
                if isinstance(raw, bytes) and marker.search(raw):
                    self.parses += 1
                return original(data, *args, **kwargs)

            return parse

        for name in ("fromstring", "XML"):
            monkeypatch.setattr(etree, name, counted(getattr(etree, name)))
        build = pinocchio.buildModelFromXML

        def built(*args, **kwargs):
            self.builds += 1
            return build(*args, **kwargs)

        monkeypatch.setattr(pinocchio, "buildModelFromXML", built)


@pytest.fixture(scope="module")
def inputs(tmp_path_factory) -> dict[str, Path]:
    """The same robot as a spec, a URDF and a xacro document."""
    folder = tmp_path_factory.mktemp("robots")
    text = read_robot(SPEC).text
    urdf = folder / f"{ROBOT_NAME}.urdf"
    urdf.write_text(text, encoding="utf-8")
    body = text.split("?>", 1)[-1]
    xacro = folder / f"{ROBOT_NAME}.urdf.xacro"
    xacro.write_text(
        body.replace("<robot ", '<robot xmlns:xacro="http://www.ros.org/wiki/xacro" ', 1).replace(
            "</robot>", '<xacro:property name="unused" value="1"/></robot>'
        ),
        encoding="utf-8",
    )
    return {"spec": SPEC, "urdf": urdf, "xacro": xacro}


COMMANDS = {
    "pose": lambda path, out: ["pose", path, "tool_link", "--at", "joint_1=0.3"],
    "jacobian": lambda path, out: ["jacobian", path, "tool_link", "--exerts", "0,0,-1"],
    "ik": lambda path, out: ["ik", path, "tool_link", "--to", "0.5,0.3,0", "--position-only"],
    "ik-targets": lambda path, out: ["ik", path, "tool_link", "--targets", str(_targets(out)), "--position-only"],
    "size": lambda path, out: ["size", path, "--payload", "1kg@tool_link"],
    "view": lambda path, out: ["view", path, "-o", str(out / "page.html")],
    "render": lambda path, out: ["render", path, "-o", str(out / "picture.png"), "--size", "160x120"],
    "export": lambda path, out: ["export", path, "--mjcf", "-o", str(out / "model.xml")],
    "graph": lambda path, out: ["graph", path],
    "import": lambda path, out: ["import", path, "-o", str(out / "spec.yaml")],
    "check": lambda path, out: ["check", path, "--consumers", "none"],
    "report": lambda path, out: ["report", path],
}


def _targets(folder):
    """Three targets a row (ik --targets): one robot read and one model built for all of them."""
    path = folder / "targets.csv"
    path.write_text("x,y,z\n0.5,0.3,0\n0.4,0.2,0\n0.3,-0.4,0\n", encoding="utf-8")
    return path


@pytest.mark.parametrize("kind", ["urdf", "xacro", "spec"])
@pytest.mark.parametrize("command", sorted(COMMANDS))
def test_a_command_reads_its_robot_once(command, kind, inputs, tmp_path, monkeypatch, capsys):
    if command == "import" and kind == "spec":
        pytest.skip("import reads URDF and xacro documents")
    if command == "report" and kind != "spec":
        pytest.skip("the design report is of a robot spec")
    counters = Counters(monkeypatch)
    code = main(COMMANDS[command](str(inputs[kind]), tmp_path))
    said = capsys.readouterr()
    assert code in (0, 1), said.err  # (1: import lists what it did not import; size, a margin below 1)
    assert counters.parses == 1, f"{command} on a {kind}: the robot's text parsed {counters.parses} times"
    assert counters.builds <= 1, f"{command} on a {kind}: {counters.builds} pinocchio models built"


def test_the_counters_see_a_second_read(inputs, monkeypatch):
    """The counters can fail: reading the robot twice, and asking both reads for their model, counts two of each."""
    counters = Counters(monkeypatch)
    for _ in range(2):
        assert read_robot(inputs["urdf"]).kinematics.joints
    assert (counters.parses, counters.builds) == (2, 2)


def test_a_read_robot_builds_its_model_once(inputs, monkeypatch):
    robot = read_robot(inputs["urdf"])
    counters = Counters(monkeypatch)
    assert robot.kinematics is robot.kinematics
    assert read_robot(robot) is robot  # (a read robot handed on is not read again)
    assert counters.builds == 1 and counters.parses == 0
