"""Every example spec generates a package whose URDF is accepted by check_urdf, pinocchio and yourdfpy, and says what
the spec says: names, counts, masses, inertias, and (for DH arms) forward kinematics."""

from __future__ import annotations

import math
import subprocess
from pathlib import Path

import numpy as np
import pinocchio as pin
import pytest
from lxml import etree

import xacrokit
from conftest import REPO, ROBOT_EXAMPLES, assert_physical_tensor, check_urdf_binary, dh_product, link_inertial
from xacrokit.load import load_file
from xacrokit.validate import validate

EXAMPLES = ROBOT_EXAMPLES


def test_the_issue_examples_are_all_here():
    names = {p.stem for p in EXAMPLES}
    assert names >= {
        "two_dof_arm",
        "linkage",
        "planar_2dof",
        "humanoid_upper_body",
        "diff_drive",
        "industrial_arm_std_dh",
        "industrial_arm_mod_dh",
    }


@pytest.fixture(scope="module", params=EXAMPLES, ids=lambda p: p.stem)
def example(request, tmp_path_factory):
    spec_path: Path = request.param
    out = tmp_path_factory.mktemp(spec_path.stem) / "pkg"
    result = xacrokit.generate(spec_path, out)
    urdf_path = out / "urdf" / f"{result.name}.urdf"
    data = validate(load_file(spec_path)).data  # the spec in SI: the reference the URDF is compared with
    return {"spec": data, "result": result, "urdf_path": urdf_path, "root": etree.parse(str(urdf_path)).getroot()}


def test_check_urdf_accepts_it(example):
    result = subprocess.run(
        [check_urdf_binary(), str(example["urdf_path"])], capture_output=True, text=True, timeout=60
    )
    assert result.returncode == 0 and "Successfully Parsed XML" in result.stdout, result.stdout + result.stderr


def body_mass(link: dict) -> float:
    """A spec link's mass (in SI, densities already made masses): its own, or its parts' sum."""
    return math.fsum(part["mass"] for part in link["parts"]) if "parts" in link else link.get("mass", 0.0)


def test_pinocchio_and_yourdfpy_load_it_with_the_spec_mass(example):
    import yourdfpy

    spec = example["spec"]
    expected = sum(body_mass(link) for link in spec["links"].values())
    expected += sum(w["mass"] for w in spec.get("wheels", {}).values())
    expected += sum(f.get("mass", 0.0) for f in spec.get("frames", {}).values())
    expected += sum(row.get("mass", 0.0) for arm in spec.get("arms", {}).values() for row in arm["joints"])
    model = pin.buildModelFromUrdf(str(example["urdf_path"]), pin.JointModelFreeFlyer())
    assert pin.computeTotalMass(model) == pytest.approx(expected, rel=1e-12)
    robot = yourdfpy.URDF.load(str(example["urdf_path"]), build_scene_graph=False, load_meshes=False)
    assert len(robot.link_map) == len(example["root"].findall("link"))


def test_names_and_counts_match_the_spec(example):
    spec, root = example["spec"], example["root"]
    links = set(spec["links"]) | set(spec.get("wheels", {})) | set(spec.get("frames", {}))
    attached = {**spec.get("wheels", {}), **spec.get("frames", {})}
    joints = set(spec.get("joints", {})) | {body.get("joint", f"{n}_joint") for n, body in attached.items()}
    for name, frame in spec.get("frames", {}).items():  # a camera's optical frame (docs/sensors.md)
        sensor = frame.get("sensor", {})
        if sensor.get("type") in ("camera", "depth_camera", "rgbd_camera") or sensor.get("preset") == "d435":
            optical = sensor.get("optical_frame", name.removesuffix("_link") + "_optical_frame")
            links.add(optical)
            joints.add(optical + "_joint")
    for arm_name, arm in spec.get("arms", {}).items():
        tool = arm.get("tool", {}).get("name", "tool0")
        links |= {tool, *(row["link"] for row in arm["joints"])}
        joints |= {arm.get("tool", {}).get("joint", f"{tool}_joint"), *(row["name"] for row in arm["joints"])}
        if arm.get("base", True):  # (base: false: the first joint hangs on parent, no ARM_base)
            links.add(f"{arm_name}_base")
            joints.add(f"{arm_name}_base_joint")
    urdf_links = [e.get("name") for e in root.findall("link")]
    urdf_joints = [e.get("name") for e in root.findall("joint")]
    assert sorted(urdf_links) == sorted(links) and len(urdf_links) == len(set(urdf_links))
    assert sorted(urdf_joints) == sorted(joints) and len(urdf_joints) == len(set(urdf_joints))
    for name, joint in spec.get("joints", {}).items():
        element = root.find(f"joint[@name='{name}']")
        assert element.get("type") == joint["type"]
        assert (element.find("parent").get("link"), element.find("child").get("link")) == (
            joint["parent"],
            joint["child"],
        )
        if "limit" in joint and "lower" in joint["limit"]:
            limit = element.find("limit")
            assert float(limit.get("lower")) == joint["limit"]["lower"]
            assert float(limit.get("upper")) == joint["limit"]["upper"]


def _closed_form(shape: dict, mass: float) -> np.ndarray:
    if "box" in shape:
        x, y, z = shape["box"]["size"]
        return np.diag([mass * (y * y + z * z), mass * (x * x + z * z), mass * (x * x + y * y)]) / 12
    if "cylinder" in shape:
        r, h = shape["cylinder"]["radius"], shape["cylinder"]["length"]
        return np.diag([mass * (3 * r * r + h * h) / 12] * 2 + [mass * r * r / 2])
    return np.eye(3) * 2 * mass * shape["sphere"]["radius"] ** 2 / 5


def test_masses_and_inertias_match_the_spec(example):
    spec, root = example["spec"], example["root"]
    # a frame's origin places the frame in its parent; its body sits at the frame origin
    bodies = {**spec["links"], **{n: {**f, "origin": {}} for n, f in spec.get("frames", {}).items()}}
    for name, body in bodies.items():
        if "parts" in body:  # (the exact sum is tested against pinocchio in tests/validate/test_validate_composite.py)
            mass, tensor, _, _ = link_inertial(root, name)
            assert mass == pytest.approx(body_mass(body), rel=1e-14)
            assert_physical_tensor(tensor)
            continue
        if "mass" not in body:
            assert root.find(f"link[@name='{name}']/inertial") is None
            continue
        mass, tensor, com, _ = link_inertial(root, name)
        assert mass == body["mass"]
        if "inertia" in body:
            i = body["inertia"]
            want = np.array(
                [
                    [i["ixx"], i.get("ixy", 0), i.get("ixz", 0)],
                    [i.get("ixy", 0), i["iyy"], i.get("iyz", 0)],
                    [i.get("ixz", 0), i.get("iyz", 0), i["izz"]],
                ]
            )
        else:
            want = _closed_form(body["shape"], body["mass"])
            np.testing.assert_allclose(com, body.get("origin", {}).get("xyz", [0, 0, 0]), atol=1e-15)
        np.testing.assert_allclose(tensor, want, rtol=1e-12)
    for name, wheel in spec.get("wheels", {}).items():
        mass, tensor, _, rot = link_inertial(root, name)
        axle = {"x": 0, "y": 1, "z": 2}[wheel.get("axis", "y")]
        assert mass == wheel["mass"]
        assert (rot @ tensor @ rot.T)[axle, axle] == pytest.approx(wheel["mass"] * wheel["radius"] ** 2 / 2, rel=1e-12)
    for arm in spec.get("arms", {}).values():
        for row in arm["joints"]:
            if "mass" in row:
                mass, tensor, _, _ = link_inertial(root, row["link"])
                assert mass == row["mass"]
                assert_physical_tensor(tensor)


def test_dh_arms_follow_their_tables(example):
    spec = example["spec"]
    if not spec.get("arms"):
        pytest.skip("no DH arm in this example")
    model = pin.buildModelFromUrdf(str(example["urdf_path"]))
    data = model.createData()
    rng = np.random.default_rng(3)
    for arm in spec["arms"].values():
        rows = arm["joints"]
        tool = arm.get("tool", {})
        for _ in range(10):
            q = pin.neutral(model)
            values = []
            for row in rows:
                value = rng.uniform(-math.pi, math.pi) if row.get("type", "revolute") != "fixed" else 0.0
                if row.get("type", "revolute") != "fixed":
                    q[model.idx_qs[model.getJointId(row["name"])]] = value
                values.append(value)
            pin.framesForwardKinematics(model, data, q)
            parent = data.oMf[model.getFrameId(arm["parent"])]
            got = (parent.inverse() * data.oMf[model.getFrameId(tool.get("name", "tool0"))]).homogeneous
            origin = arm.get("origin", {})
            tool_origin = tool.get("origin", {})
            want = dh_product(
                rows,
                values,
                arm.get("convention", "standard"),
                (origin.get("xyz", [0, 0, 0]), origin.get("rpy", [0, 0, 0])),
                (tool_origin.get("xyz", [0, 0, 0]), tool_origin.get("rpy", [0, 0, 0])),
            )
            np.testing.assert_allclose(got, want, rtol=0, atol=1e-9)


def test_ur5_home_pose_matches_the_published_geometry():
    """An independent sanity check of the standard-DH example: UR5 at q = 0 puts tool0 at
    (a2 + a3, -(d4 + d6), d1 - d5) = (-0.81725, -0.19145, -0.005491) m in base_link (UR's published zero pose)."""
    result = xacrokit.generate(
        REPO / "examples" / "robots" / "industrial_arm_std_dh.yaml", dry_run=True, output="/nonexistent"
    )
    urdf = next(f.content for f in result.files if f.path.endswith(".urdf"))
    model = pin.buildModelFromXML(urdf)
    data = model.createData()
    pin.framesForwardKinematics(model, data, pin.neutral(model))
    np.testing.assert_allclose(
        data.oMf[model.getFrameId("tool0")].translation, [-0.81725, -0.19145, -0.005491], atol=1e-12
    )


def test_panda_flange_at_zero_matches_the_published_geometry():
    """Panda at q = 0 (Craig DH): flange at (0.088, 0, 0.333 + 0.316 + 0.384 - 0.107) = (0.088, 0, 0.926) m,
    pointing down (z_flange = -z_base), as Franka's documentation draws it."""
    result = xacrokit.generate(
        REPO / "examples" / "robots" / "industrial_arm_mod_dh.yaml", dry_run=True, output="/nonexistent"
    )
    urdf = next(f.content for f in result.files if f.path.endswith(".urdf"))
    model = pin.buildModelFromXML(urdf)
    data = model.createData()
    pin.framesForwardKinematics(model, data, pin.neutral(model))
    flange = data.oMf[model.getFrameId("panda_link8")]
    np.testing.assert_allclose(flange.translation, [0.088, 0.0, 0.926], atol=1e-12)
    np.testing.assert_allclose(flange.rotation[:, 2], [0.0, 0.0, -1.0], atol=1e-12)
