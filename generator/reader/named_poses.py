"""A robot's named poses: a spec's ``poses`` (docs/spec.md#named-poses), ``home`` first; for any robot, ``home`` is
otherwise where its ``<ros2_control>`` blocks start it (each joint's ``initial_value``). The exported MuJoCo model's
keyframes and the view page's sliders start from them."""

from __future__ import annotations

import math
from collections.abc import Mapping
from typing import TYPE_CHECKING

from ..shared.joint_types import HOME_POSE
from ..shared.urdf_view import UrdfView

if TYPE_CHECKING:  # (check reads a URDF's poses without loading the robot model's classes)
    from ..model import Robot


def initial_values(view: UrdfView) -> dict[str, float]:
    """Each joint's ``initial_value`` as the ``<ros2_control>`` blocks give it (a position state interface's param;
    one that is not a finite number is left out: a keyframe or a slider could not hold it)."""
    found: dict[str, float] = {}
    for block in view.ros2_control:
        for joint in block.element.findall("joint"):
            name = joint.get("name")
            for param in joint.findall("state_interface[@name='position']/param[@name='initial_value']"):
                try:
                    value = float((param.text or "").strip())
                except ValueError:
                    continue
                if name and math.isfinite(value):
                    found.setdefault(name, value)
    return found


def spec_poses(robot: Robot | None) -> dict[str, dict[str, float]]:
    """A spec's named poses (``robot``: its model; None for a URDF or xacro document: none)."""
    return {name: dict(values) for name, values in robot.poses} if robot is not None else {}


def named_poses(given: Mapping[str, Mapping[str, float]], view: UrdfView) -> dict[str, Mapping[str, float]]:
    """Pose name -> {joint: value}: ``given`` (:func:`spec_poses`), ``home`` first and always there (the given one,
    else the ros2_control start; a joint it leaves out is at 0, or its limit nearest 0, to the reader)."""
    home = given.get(HOME_POSE)
    return {
        HOME_POSE: home if home is not None else initial_values(view),
        **{n: p for n, p in given.items() if n != HOME_POSE},
    }
