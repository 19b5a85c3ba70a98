"""The UR10e sizing example's static worst case (issue 31: its rated payload on UR's effort limits), recomputed
with yourdfpy's forward kinematics, a second reader and walk: at the pose `size` reports, the torque gravity puts on
each joint is the sum over the links beyond it (and the payload) of ((c - o) x m g) . z, which the motor cancels."""

from __future__ import annotations

import io
import json

import numpy as np
import pytest
import yourdfpy

from conftest import REPO, gen_robot
from xacrokit.reader.read_robot import read_robot


def _gravity_torques(urdf, q, payload_frame, payload_mass, payload_com, g):
    """Each moving joint's holding torque at q: minus the moment of gravity about its axis."""
    urdf.update_cfg(q)
    bodies = []  # (link the mass rides on, mass, centre in the root frame)
    for link in urdf.robot.links:
        if link.inertial is not None and link.inertial.mass > 0:
            centre = urdf.get_transform(link.name, urdf.base_link) @ link.inertial.origin
            bodies.append((link.name, link.inertial.mass, centre[:3, 3]))
    at = urdf.get_transform(payload_frame, urdf.base_link) @ np.append(payload_com, 1.0)
    bodies.append((payload_frame, payload_mass, at[:3]))
    weight = np.array([0.0, 0.0, -g])
    torques = {}
    for joint in urdf.robot.joints:
        if joint.type not in ("revolute", "continuous"):
            continue
        frame = urdf.get_transform(joint.child, urdf.base_link)
        origin, axis = frame[:3, 3], frame[:3, :3] @ joint.axis
        below = set(_subtree(urdf, joint.child))
        moment = sum(np.cross(c - origin, m * weight) @ axis for link, m, c in bodies if link in below)
        torques[joint.name] = -moment
    return torques


def _subtree(urdf, link):
    yield link
    for joint in urdf.robot.joints:
        if joint.parent == link:
            yield from _subtree(urdf, joint.child)


def test_the_ur10e_static_worst_case_is_gravity_at_the_reported_pose():
    result = gen_robot(
        "size", "examples/robots/ur10e.yaml", "--sizing", "examples/sizing/ur10e_palletizing.yaml", "--json", cwd=REPO
    )
    report = json.loads(result.stdout)
    text = read_robot(REPO / "examples" / "robots" / "ur10e.yaml").text
    urdf = yourdfpy.URDF.load(io.BytesIO(text.encode("utf-8")), load_meshes=False, build_scene_graph=True)
    (payload,) = report["payloads"]
    assert payload["mass"] == 12.5 and payload["frame"] == "tool0"  # (the UR10e's rated payload)
    checked = 0
    for joint in report["joints"]:
        static = joint["static"]
        torques = _gravity_torques(
            urdf, static["pose"], "tool0", payload["mass"], np.array(payload["com"]), report["gravity"]
        )
        assert torques[joint["name"]] == pytest.approx(static["peak_torque"], rel=1e-9, abs=1e-9), joint["name"]
        checked += abs(static["peak_torque"]) > 1.0
    assert checked == 4  # (the shoulder lift, the elbow and two wrists carry weight; the pan and the last wrist none)
    lift = next(j for j in report["joints"] if j["name"] == "shoulder_lift_joint")
    # stretched out: 12.5 kg at 1.184 m (a2 + a3) plus the wrist offsets, with the arm's own weight, just within 330
    assert 290 < abs(lift["static"]["peak_torque"]) < 330 and lift["effort_limit"] == 330.0
