"""gen-robot import on the real-robot corpus (tests/realworld.py), first part: every file whose links and
joints the spec can say is imported, generated again, and comes back as the same robot (tests/importer/test_import.py's
comparison: names, FK at 20 random values, inertia per link, limits, visuals); the others are reported with the
reasons the importer gives, named here so that a change in either shows. One test a file: they run side by side."""

from __future__ import annotations

import pytest
import yaml

import xacrokit
from realworld import VERDICTS, robots
from test_import import compare
from xacrokit.importer.urdf_to_spec import import_robot, spec_yaml
from xacrokit.reader.read_robot import read_robot
from xacrokit.reader.robot_input import RobotInput
from xacrokit.shared.input_files import copied_pieces

FILES = yaml.safe_load(VERDICTS.read_text(encoding="utf-8"))["files"]
# (each an error of the file itself, said at import with the spec's message: every file that does not come back)
REFUSED_BY_THE_SPEC = {
    "example-robot-data/alex_description/urdf/alex_psyonic_hands.urdf",  # mimic joints that name no joint of the file
    "example-robot-data/ur_description/urdf/ur3.urdf",  # a macro file: no link
    "robot-properties-fingers/finger_macro.urdf",
    "robot-properties-fingers/trifinger_stage.urdf",  # a joint whose parent is not in the file
    "robot-properties-fingers/edu/trifingeredu_stage.urdf",
}


def test_the_corpus_is_124_files_that_come_back_and_5_the_spec_refuses():
    assert sorted(robots()) == sorted(FILES) and len(FILES) == 129
    assert len(REFUSED_BY_THE_SPEC) == 5 and REFUSED_BY_THE_SPEC <= set(FILES)
    came_back = set(FILES) - REFUSED_BY_THE_SPEC
    assert {
        "airo-models/arms/ur5e/ur5e.urdf",
        "airo-models/grippers/robotiq_2f_85/urdf/robotiq_2f_85.urdf",
    } <= came_back


@pytest.mark.parametrize("key", sorted(FILES))
def test_the_importable_real_robots_come_back_as_the_same_robots(key, tmp_path):
    robot = robots()[key]
    read = read_robot(RobotInput(robot.path, packages=robot.packages))
    imported = import_robot(read)
    if key in REFUSED_BY_THE_SPEC:
        assert imported.unsupported and all("the spec refuses" in said for said in imported.unsupported)
        return
    assert not imported.unsupported
    spec = tmp_path / "s" / "robot.yaml"
    if key == "airo-models/arms/ur5e/ur5e.urdf":  # (two wrist3.obj, shoulder.obj...: one per folder)
        assert {"meshes/visual/wrist3.obj", "meshes/collision/wrist3.obj"} <= set(imported.meshes)
    for relative, source in imported.meshes.items():  # (what gen-robot import -o does)
        (spec.parent / relative).parent.mkdir(parents=True, exist_ok=True)
        (spec.parent / relative).write_bytes(b"".join(copied_pieces(source)))
    spec.parent.mkdir(exist_ok=True)
    spec.write_text(spec_yaml(imported, key), encoding="utf-8")
    xacrokit.generate(spec, tmp_path / "pkg")  # (a SpecErrors here, the spec's own checks refusing it, fails)
    (again,) = (tmp_path / "pkg" / "urdf").glob("*.urdf")
    compare(read.text, again.read_text(encoding="utf-8"))
