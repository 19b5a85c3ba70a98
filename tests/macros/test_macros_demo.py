"""examples/macros/macros_demo.urdf.xacro: expands without ROS and is accepted by check_urdf, pinocchio and yourdfpy."""

from __future__ import annotations

import math
import subprocess
from pathlib import Path

import numpy as np
import pinocchio as pin
import pytest
import xacro
from lxml import etree

import xacrokit
from conftest import MACRO_DEMO, REPO, assert_physical_tensor, check_urdf_binary, dh_product, link_inertial

DEMO = MACRO_DEMO


@pytest.fixture(scope="module")
def demo_urdf(tmp_path_factory) -> Path:
    path = tmp_path_factory.mktemp("demo") / "macros_demo.urdf"
    path.write_text(xacrokit.expand(DEMO), encoding="utf-8")
    return path


def test_demo_passes_check_urdf(demo_urdf):
    result = subprocess.run([check_urdf_binary(), str(demo_urdf)], capture_output=True, text=True, timeout=60)
    assert result.returncode == 0, result.stdout + result.stderr
    assert "Successfully Parsed XML" in result.stdout and "root Link: base_footprint" in result.stdout


def test_demo_loads_in_pinocchio_and_yourdfpy_with_the_written_masses(demo_urdf):
    import yourdfpy

    root = etree.parse(str(demo_urdf)).getroot()
    masses = {
        link.get("name"): float(link.find("inertial/mass").get("value"))
        for link in root.iter("link")
        if link.find("inertial") is not None
    }
    assert sum(masses.values()) == pytest.approx(8.0 + 2 * 0.5 + 0.1 + 1.0 + 0.6 + 0.5 + 0.3 + 0.05 + 0.05 + 0.01)
    for name in masses:
        assert_physical_tensor(link_inertial(root, name)[1])

    # On a fixed base pinocchio folds the root and every link welded to it into the universe and leaves them out of
    # its total; on a free-flyer they form the floating body and count.
    model = pin.buildModelFromUrdf(str(demo_urdf), pin.JointModelFreeFlyer())
    assert pin.computeTotalMass(model) == pytest.approx(sum(masses.values()), rel=1e-12)
    assert {model.names[j] for j in range(1, model.njoints)} == {
        "root_joint",
        "left_wheel_joint",
        "right_wheel_joint",
        "arm_joint_1",
        "arm_joint_2",
        "arm_joint_3",
        "arm_lift_joint",
    }

    robot = yourdfpy.URDF.load(str(demo_urdf), build_scene_graph=False, load_meshes=False)
    assert set(robot.link_map) == {link.get("name") for link in root.iter("link")}
    assert robot.joint_map["left_wheel_joint"].type == "continuous"


def test_demo_arm_follows_its_dh_table(demo_urdf):
    xacro.init_stacks(None)  # (load_yaml outside an expansion: xacro's file stack is set only while it expands)
    rows = xacro.load_yaml(str(REPO / "examples" / "macros" / "macros_demo_arm.yaml"))["joints"]
    rows = [dict(r) for r in rows]
    model = pin.buildModelFromUrdf(str(demo_urdf))
    data = model.createData()
    rng = np.random.default_rng(7)
    for _ in range(5):
        q = pin.neutral(model)
        values = []
        for row in rows:
            jid = model.getJointId(row["name"])
            value = rng.uniform(-1.0, 1.0) * (0.05 if row.get("type") == "prismatic" else math.pi)
            q[model.idx_qs[jid]] = value
            values.append(value)
        pin.framesForwardKinematics(model, data, q)
        got = (data.oMf[model.getFrameId("mast_link")].inverse() * data.oMf[model.getFrameId("tool0")]).homogeneous
        want = dh_product(rows, values, "standard", ((0, 0, 0.3), (0, 0, 0)), ((0, 0, 0), (0, 0, 0)))
        np.testing.assert_allclose(got, want, rtol=0, atol=1e-9)


def test_demo_with_a_prefix_prefixes_every_name():
    root = etree.fromstring(xacrokit.expand(DEMO, {"prefix": "r2_"}).encode())
    names = [e.get("name") for e in root.iter("link", "joint")]
    assert names and all(n.startswith("r2_") for n in names)
    assert all(g.get("reference").startswith("r2_") for g in root.iter("gazebo"))


def test_macro_library_expands_untrusted(tmp_path):
    """Every public macro (the demo calls each, the *_inertial ones through the *_link ones) and a generated package
    calling the library (--macros copy: dh_arm reading its table with xacro.load_yaml) expand as documents from
    elsewhere, guarded and bounded, to exactly what trusted xacro gives: the other macro tests expand trusted."""
    assert xacrokit.expand(DEMO, trust=False) == xacrokit.expand(DEMO, trust=True)
    arm = REPO / "examples" / "robots" / "industrial_arm_std_dh.yaml"
    xacrokit.generate(arm, tmp_path / "pkg", macros="copy")
    entry = tmp_path / "pkg" / "urdf" / "ur5.urdf.xacro"
    paths = {"ur5_description": tmp_path / "pkg"}
    untrusted = xacrokit.expand(entry, package_paths=paths, trust=False)
    assert untrusted == xacrokit.expand(entry, package_paths=paths, trust=True) and "<link" in untrusted
