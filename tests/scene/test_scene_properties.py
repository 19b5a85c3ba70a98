"""Properties over random scenes: prefixes reach every name, names are disjoint, each instance's FK is its mount
composed with its robot's own, and the scene checks clean."""

from __future__ import annotations

import numpy as np
import pinocchio as pin
import yaml
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st
from lxml import etree
from scene_helpers import scene_file, urdf_root

import xacrokit
from conftest import mesh_package_at
from xacrokit.check import check
from xacrokit.pipeline import expand_package
from xacrokit.reader.robot_input import RobotInput
from xacrokit.render import render_package
from xacrokit.shared.transforms import origin_transform
from xacrokit.testing import valid_specs


@st.composite
def random_scenes(draw):
    robots = [draw(valid_specs(max_links=3)) for _ in range(draw(st.integers(1, 2)))]
    for index, robot in enumerate(robots):
        robot["robot"] = f"robot_{index}"
    instances = {}
    for index in range(draw(st.integers(1, 3))):
        which = draw(st.integers(0, len(robots) - 1))
        parent = "world"
        if instances and draw(st.booleans()):
            other = draw(st.sampled_from(sorted(instances)))
            parent = f"{other}/{draw(st.sampled_from(sorted(robots[instances[other]['robot']]['links'])))}"
        origin = {"xyz": [draw(st.floats(-2, 2)) for _ in range(3)], "rpy": [draw(st.floats(-3, 3)) for _ in range(3)]}
        instances[f"i{index}"] = {"robot": which, "prefix": f"p{index}_", "parent": parent, "origin": origin}
    return robots, instances


@settings(max_examples=8, suppress_health_check=[HealthCheck.too_slow, HealthCheck.data_too_large])
@given(case=random_scenes(), seed=st.integers(0, 2**16))
def test_random_scenes_prefix_disjoint_fk_and_check(tmp_path_factory, case, seed):
    robots, instances = case
    folder = tmp_path_factory.mktemp("scene")
    for index, robot in enumerate(robots):
        (folder / f"robot_{index}.yaml").write_text(yaml.safe_dump(robot, sort_keys=False), encoding="utf-8")
    entries = {
        name: {"spec": f"robot_{i['robot']}.yaml", "prefix": i["prefix"], "parent": i["parent"], "origin": i["origin"]}
        for name, i in instances.items()
    }
    path = scene_file(folder, entries)
    result = xacrokit.generate(path, folder / "pkg")
    scene, root = result.model, urdf_root(result)

    # every name of an instance carries its prefix; the scene's names are the disjoint union of the instances'
    all_links = [scene.world]
    for instance in scene.instances:
        names = [*instance.links, *instance.joints]
        assert all(n.startswith(instance.prefix) for n in names)
        all_links += instance.links
    assert sorted(e.get("name") for e in root.findall("link")) == sorted(all_links)
    assert len(all_links) == len(set(all_links))
    for element in (*root.findall("gazebo"), *root.findall("ros2_control/joint")):
        name = element.get("reference") or element.get("name")
        assert any(name.startswith(i.prefix) and name in (*i.links, *i.joints) for i in scene.instances), name

    # each instance's FK from the world is its mount pose composed with the single robot's own FK
    model = pin.buildModelFromXML(etree.tostring(root, encoding="unicode"))
    data = model.createData()
    rng = np.random.default_rng(seed)
    q = pin.neutral(model)
    values = {}
    for j in range(1, model.njoints):
        if model.nqs[j] == 1:
            q[model.idx_qs[j]] = values[model.names[j]] = float(rng.uniform(-1, 1))
    pin.framesForwardKinematics(model, data, q)
    for instance in scene.instances:
        robot = instance.robot
        alone = pin.buildModelFromXML(expand_package(robot, render_package(robot)).content)
        alone_data = alone.createData()
        q_alone = pin.neutral(alone)
        for j in range(1, alone.njoints):
            if alone.nqs[j] == 1:
                q_alone[alone.idx_qs[j]] = values[instance.prefix + alone.names[j]]
        pin.framesForwardKinematics(alone, alone_data, q_alone)
        mount = data.oMf[model.getFrameId(instance.parent)].homogeneous @ origin_transform(instance.origin)
        root_alone = alone_data.oMf[alone.getFrameId(robot.root)].homogeneous
        for link in robot.link_names:
            want = mount @ np.linalg.inv(root_alone) @ alone_data.oMf[alone.getFrameId(link)].homogeneous
            got = data.oMf[model.getFrameId(instance.prefix + link)].homogeneous
            np.testing.assert_allclose(got, want, rtol=0, atol=1e-9)

    report = check(
        RobotInput(path, packages={"some_pkg": mesh_package_at(folder)}), consumers=["check_urdf", "pinocchio"]
    )
    assert not report.errors, [str(f) for f in report.errors]
    assert all(c.status == "accepted" for c in report.consumers)
