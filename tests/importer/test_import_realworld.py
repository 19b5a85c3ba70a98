"""gen-robot import on the real-robot corpus (tests/realworld.py), first part: every file whose links and
joints the spec can say is imported, generated again, and comes back as the same robot (tests/importer/test_import.py's
comparison: names, FK at 20 random values, inertia per link, limits, visuals); the others are reported with the
reasons the importer gives, counted here so that a change in either shows."""

from __future__ import annotations

import collections

import xacrokit
from realworld import corpus_or_skip
from test_import import compare
from xacrokit.errors import SpecErrors
from xacrokit.importer.urdf_to_spec import import_robot, spec_yaml
from xacrokit.reader.read_robot import read_robot
from xacrokit.reader.robot_input import RobotInput
from xacrokit.shared.input_files import copied_pieces


def test_the_importable_real_robots_come_back_as_the_same_robots(tmp_path):
    reasons: collections.Counter[str] = collections.Counter()
    done = []
    refused: dict[str, list[str]] = {}
    for index, robot in enumerate(corpus_or_skip()):
        read = read_robot(RobotInput(robot.path, packages=robot.packages))
        imported = import_robot(read)
        if imported.unsupported:
            reasons["importer"] += 1
            refused[robot.key] = imported.unsupported
            continue
        spec = tmp_path / f"s{index}" / "robot.yaml"
        if robot.key == "airo-models/arms/ur5e/ur5e.urdf":  # (two wrist3.obj, shoulder.obj...: one per folder)
            assert {"meshes/visual/wrist3.obj", "meshes/collision/wrist3.obj"} <= set(imported.meshes)
        for relative, source in imported.meshes.items():  # (what gen-robot import -o does)
            (spec.parent / relative).parent.mkdir(parents=True, exist_ok=True)
            (spec.parent / relative).write_bytes(b"".join(copied_pieces(source)))
        spec.parent.mkdir(exist_ok=True)
        spec.write_text(spec_yaml(imported, robot.key), encoding="utf-8")
        try:
            xacrokit.generate(spec, tmp_path / f"pkg{index}")
        except SpecErrors:  # (the spec's own checks: a relative mesh path not next to the spec, an impossible tensor)
            reasons["spec"] += 1
            continue
        (again,) = (tmp_path / f"pkg{index}" / "urdf").glob("*.urdf")
        compare(read.text, again.read_text(encoding="utf-8"))
        done.append(robot.key)
    assert (
        "airo-models/arms/ur5e/ur5e.urdf" in done
        and "airo-models/grippers/robotiq_2f_85/urdf/robotiq_2f_85.urdf" in done
    )
    assert len(done) == 124 and reasons == {"importer": 5}, (len(done), reasons)
    # (each an error of the file itself, said at import with the spec's message: every file that does not come back)
    by_the_spec = {k.rsplit("/", 1)[-1] for k, said in refused.items() if all("the spec refuses" in s for s in said)}
    assert by_the_spec == {
        "alex_psyonic_hands.urdf",  # mimic joints that name no joint of the file
        "ur3.urdf",  # a macro file: no link
        "finger_macro.urdf",
        "trifinger_stage.urdf",  # a joint whose parent is not in the file
        "trifingeredu_stage.urdf",
    }, sorted(by_the_spec)
