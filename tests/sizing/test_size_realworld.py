"""gen-robot size on real robots of example-robot-data (the test extra installs it): every arm sizes without a
traceback, the search finds at least what 2,000 random poses of its own give, and its torques are pinocchio's
generalized gravity at the pose it reports (independently rebuilt from the file)."""

from __future__ import annotations

import sys
from pathlib import Path

import numpy as np
import pinocchio as pin
import pytest

from conftest import gen_robot
from xacrokit.sizing import Payload, size

ARMS = {  # file inside example-robot-data's robots folder -> the frame a payload goes on
    "ur_description/urdf/ur5_robot.urdf": "tool0",
    "panda_description/urdf/panda.urdf": "panda_link8",
    "kinova_description/robots/kinova.urdf": "j2s6s200_end_effector",
    "z1_description/urdf/z1.urdf": "link06",
    "so_arm_description/urdf/so101.urdf": "gripper_link",
}


def robots_folder() -> Path:
    for entry in sys.path:
        folder = Path(entry, "cmeel.prefix", "share", "example-robot-data", "robots")
        if folder.is_dir():
            return folder
    pytest.skip("example-robot-data is not installed (pip install -e '.[test]')")


@pytest.mark.parametrize(("relative", "frame"), sorted(ARMS.items()))
def test_real_arms_size_and_agree_with_pinocchio_and_random_poses(relative, frame):
    path = robots_folder() / relative
    report = size(path, payloads=[Payload(frame, 1.0)])
    model = pin.buildModelFromUrdf(str(path))
    model.gravity = pin.Motion(np.array([0, 0, -9.80665, 0, 0, 0]))
    carrier = model.frames[model.getFrameId(frame)]
    model.appendBodyToJoint(carrier.parentJoint, pin.Inertia(1.0, np.zeros(3), np.zeros((3, 3))), carrier.placement)
    data = model.createData()
    names = [p.joint for p in report.peaks]
    ids = [model.getJointId(name) for name in names]
    sampled = np.zeros(len(names))
    for _ in range(2000):
        q = pin.randomConfiguration(model)
        sampled = np.maximum(
            sampled, np.abs(pin.computeGeneralizedGravity(model, data, q)[[model.idx_vs[i] for i in ids]])
        )
    for index, peak in enumerate(report.peaks):
        assert abs(peak.torque) >= sampled[index] * (1 - 1e-9) - 1e-9, (peak.joint, peak.torque, sampled[index])
        q = pin.neutral(model)
        for name, value in peak.pose.items():
            joint = model.joints[model.getJointId(name)]
            if joint.nq == 2:
                q[joint.idx_q], q[joint.idx_q + 1] = np.cos(value), np.sin(value)
            else:
                q[joint.idx_q] = value
        tau = pin.computeGeneralizedGravity(model, data, q)[model.idx_vs[ids[index]]]
        assert peak.torque == pytest.approx(tau, abs=1e-9 * max(1.0, abs(tau)))


def test_the_command_line_on_a_real_arm_prints_every_joint():
    path = robots_folder() / "panda_description" / "urdf" / "panda.urdf"
    result = gen_robot("size", path, "--payload", "3 kg@panda_link8")
    assert result.returncode in (0, 1), result.stderr
    for joint in range(1, 8):
        assert f"panda_joint{joint} " in result.stdout
