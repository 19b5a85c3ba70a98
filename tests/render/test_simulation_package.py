"""The simulation half of every example's package (issue 18, item 2), checked statically against facts read from the
ROS 2 Jazzy sources (tests/render/ros_facts.yaml; no ROS here): the launch files are Python that imports only names the
launch APIs define and runs only executables their packages install, with flags those executables take; package.xml
lists every package they use; each controller's parameters exist in its definition with the right type; every joint
and interface the controllers name is in the URDF's ros2_control block; the bridge file has the keys and type pairs
ros_gz_bridge reads; the Gazebo plugin and hardware names are gz_ros2_control's; world:=true fixes a robot in place."""

from __future__ import annotations

import ast
from functools import cache
from pathlib import Path

import pytest
import yaml
from lxml import etree

import xacrokit
from conftest import ROBOT_EXAMPLES, SCENE_EXAMPLES
from xacrokit.expansion.xacro_expand import expand_file

FACTS = yaml.safe_load((Path(__file__).parent / "ros_facts.yaml").read_text(encoding="utf-8"))
TYPES = {"string_array": list, "double_array": list, "bool": bool, "string": str, "double": float, "int": int}


@cache
def package(example: Path, folder: Path) -> Path:
    out = folder / example.stem
    xacrokit.generate(example, out)
    return out


@pytest.fixture(scope="module")
def folder(tmp_path_factory):
    return tmp_path_factory.mktemp("sim")


def calls(tree: ast.AST, name: str) -> list[ast.Call]:
    return [n for n in ast.walk(tree) if isinstance(n, ast.Call) and getattr(n.func, "id", None) == name]


def literal_strings(node: ast.AST) -> list[str]:
    return [n.value for n in ast.walk(node) if isinstance(n, ast.Constant) and isinstance(n.value, str)]


@pytest.mark.parametrize("example", [*ROBOT_EXAMPLES, *SCENE_EXAMPLES], ids=lambda p: p.stem)
def test_launch_files_use_only_what_the_launch_apis_and_packages_define(example, folder):
    root = package(example, folder)
    manifest = etree.parse(str(root / "package.xml")).getroot()
    depends = {e.text for e in manifest.iter(etree.Element) if e.tag.endswith("depend")}
    name = etree.parse(str(root / "package.xml")).getroot().findtext("name")
    launches = sorted((root / "launch").glob("*.launch.py"))
    assert {p.name for p in launches} >= {"display.launch.py", "gazebo.launch.py"}
    for path in launches:
        tree = ast.parse(path.read_text(encoding="utf-8"))
        for node in ast.walk(tree):
            if isinstance(node, ast.ImportFrom):
                assert node.module in FACTS["launch_api"], (path.name, node.module)
                for alias in node.names:
                    assert alias.name in FACTS["launch_api"][node.module], (path.name, node.module, alias.name)
            elif isinstance(node, ast.Import):
                pytest.fail(f"{path.name}: import {[a.name for a in node.names]}")
        for call in calls(tree, "Node"):
            keywords = {k.arg: k.value for k in call.keywords}
            assert set(keywords) <= set(FACTS["node_keywords"]), (path.name, set(keywords))
            pkg, exe = ast.literal_eval(keywords["package"]), ast.literal_eval(keywords["executable"])
            assert exe in FACTS["executables"][pkg], (path.name, pkg, exe)
            assert pkg in depends, (path.name, pkg)
            flags = [s for s in literal_strings(keywords.get("arguments", ast.List([]))) if s.startswith("-")]
            allowed = {"spawner": FACTS["spawner_flags"], "create": FACTS["create_flags"]}.get(exe, ["-d", "-f"])
            assert set(flags) <= set(allowed), (path.name, exe, flags)
            if exe == "parameter_bridge":
                given = [k.value for d in ast.walk(keywords["parameters"]) if isinstance(d, ast.Dict) for k in d.keys]
                assert set(given) <= set(FACTS["bridge_node_parameters"]) | {"use_sim_time"}
        for call in calls(tree, "FindPackageShare"):
            used = ast.literal_eval(call.args[0])
            assert used == name or used in depends, (path.name, used)
        for call in calls(tree, "IncludeLaunchDescription"):
            arguments = next((k.value for k in call.keywords if k.arg == "launch_arguments"), None)
            if arguments is None:
                continue  # (moveit_demo.launch.py includes the package's own control.launch.py as it is)
            keys = [ast.literal_eval(k) for d in ast.walk(arguments) if isinstance(d, ast.Dict) for k in d.keys]
            assert set(keys) <= set(FACTS["gz_sim_launch_arguments"]), keys


@pytest.mark.parametrize("example", ROBOT_EXAMPLES, ids=lambda p: p.stem)
def test_controllers_exist_with_typed_parameters_and_name_what_the_urdf_has(example, folder):
    root = package(example, folder)
    files = [p for p in (root / "config").glob("*_controllers.yaml") if p.name != "moveit_controllers.yaml"]
    if not files:
        assert not (root / "launch" / "control.launch.py").exists()
        return
    (config,) = files
    urdf = expand_file(root / "urdf" / f"{config.name.removesuffix('_controllers.yaml')}.urdf.xacro", {})
    check_controllers(root, config, urdf)


@pytest.mark.parametrize("example", SCENE_EXAMPLES, ids=lambda p: p.stem)
def test_a_simulated_scene_runs_every_robot_under_one_gz_ros2_control_plugin(example, folder):
    """ros2_control:=gazebo: one plugin reading config/SCENE_controllers.yaml (every instance's prefixed
    controllers), each robot's ros2_control block on GazeboSimSystem, no robot's own plugin."""
    root = package(example, folder)
    entry = next((root / "urdf").glob("*.urdf.xacro"))
    name = entry.name.removesuffix(".urdf.xacro")
    config = root / "config" / f"{name}_controllers.yaml"
    manifest = etree.parse(str(root / "package.xml")).getroot().findtext("name")
    urdf = expand_file(entry, {"ros2_control": "gazebo"}, package_paths={manifest: str(root)})
    tree = etree.fromstring(urdf.encode())
    (plugin,) = tree.findall("gazebo/plugin")
    assert plugin.get("filename") == FACTS["gz_ros2_control"]["filename"]
    assert Path(plugin.findtext("parameters")) == root / "config" / f"{name}_controllers.yaml"
    blocks = tree.findall("ros2_control")
    assert len(blocks) >= 2 and {b.findtext("hardware/plugin") for b in blocks} == {
        FACTS["gz_ros2_control"]["hardware"]
    }
    check_controllers(root, config, urdf)


def check_controllers(root: Path, config: Path, urdf: str) -> None:
    data = yaml.safe_load(config.read_text(encoding="utf-8"))
    manager = data["controller_manager"]["ros__parameters"]
    assert isinstance(manager.pop("update_rate"), int)
    types = {name: entry["type"] for name, entry in manager.items()}
    assert set(types.values()) <= set(FACTS["controllers"]), types
    interfaces = {
        j.get("name"): (
            {c.get("name") for c in j.findall("command_interface")},
            {s.get("name") for s in j.findall("state_interface")},
        )
        for j in etree.fromstring(urdf.encode("utf-8")).findall("ros2_control/joint")
    }
    for name, kind in types.items():
        params = data.get(name, {}).get("ros__parameters", {})
        for key, value in params.items():
            assert key in FACTS["controllers"][kind], (name, key)
            assert isinstance(value, TYPES[FACTS["controllers"][kind][key]]), (name, key, value)
        for key in ("joints", "left_wheel_names", "right_wheel_names"):
            for joint in params.get(key, []):
                assert joint in interfaces, (name, joint)
        if kind.endswith("JointTrajectoryController"):
            assert params["command_interfaces"] in FACTS["trajectory_command_interfaces"]
            assert params["state_interfaces"] in FACTS["trajectory_state_interfaces"]
            for joint in params["joints"]:
                assert set(params["command_interfaces"]) <= interfaces[joint][0]
                assert set(params["state_interfaces"]) <= interfaces[joint][1]
        if kind.startswith(("position_", "velocity_", "effort_")):
            for joint in params["joints"]:
                assert kind.split("_", 1)[0] in interfaces[joint][0], (name, joint)
    for path in (root / "launch").glob("*.launch.py"):  # every controller a spawner starts is defined
        tree = ast.parse(path.read_text(encoding="utf-8"))
        spawned = [s for c in calls(tree, "Node") for s in literal_strings(c) if s in types or s.endswith("controller")]
        for node in ast.walk(tree):
            if isinstance(node, ast.List) and all(isinstance(e, ast.Constant) for e in node.elts) and node.elts:
                names = [e.value for e in node.elts]
                if any(str(n).endswith(("_controller", "_broadcaster")) for n in names):
                    assert set(names) <= set(types), (path.name, names)
        assert spawned is not None


@pytest.mark.parametrize("example", ROBOT_EXAMPLES, ids=lambda p: p.stem)
def test_the_bridge_and_gazebo_blocks_use_ros_gz_and_gz_ros2_controls_names(example, folder):
    root = package(example, folder)
    (bridge,) = (root / "config").glob("*_bridge.yaml")
    entries = yaml.safe_load(bridge.read_text(encoding="utf-8"))
    assert isinstance(entries, list) and entries[0]["ros_topic_name"] == "clock"
    for entry in entries:
        assert set(entry) <= set(FACTS["bridge_keys"])
        assert entry["direction"] in FACTS["bridge_directions"]
        assert FACTS["bridge_types"][entry["ros_type_name"]] == entry["gz_type_name"]
    name = bridge.name.removesuffix("_bridge.yaml")
    etree.parse(str(root / "worlds" / f"{name}.sdf"))  # (well-formed; its systems are Gazebo's own)
    if not (root / "config" / f"{name}_controllers.yaml").exists():
        return
    urdf = etree.fromstring(expand_file(root / "urdf" / f"{name}.urdf.xacro", {"ros2_control": "gazebo"}).encode())
    (plugin,) = urdf.findall("gazebo/plugin")
    facts = FACTS["gz_ros2_control"]
    assert (plugin.get("filename"), plugin.get("name")) == (facts["filename"], facts["name"])
    assert {child.tag for child in plugin} <= set(facts["elements"])
    assert Path(plugin.findtext("parameters")).name == f"{name}_controllers.yaml"
    assert urdf.findtext("ros2_control/hardware/plugin") == facts["hardware"]
    mock = etree.fromstring(expand_file(root / "urdf" / f"{name}.urdf.xacro", {}).encode())
    assert mock.findtext("ros2_control/hardware/plugin") == FACTS["mock_hardware"]


@pytest.mark.parametrize("example", ROBOT_EXAMPLES, ids=lambda p: p.stem)
def test_a_robot_without_wheels_is_fixed_to_the_world_when_simulated(example, folder):
    """gazebo.launch.py passes world:=true to a robot without wheels (an arm spawned free would fall); the URDF then
    has a link named world and the robot's root as its child, and without it no world at all."""
    root = package(example, folder)
    name = next((root / "config").glob("*_bridge.yaml")).name.removesuffix("_bridge.yaml")
    entry = root / "urdf" / f"{name}.urdf.xacro"
    launch = (root / "launch" / "gazebo.launch.py").read_text(encoding="utf-8")
    spec = yaml.safe_load(example.read_text(encoding="utf-8"))
    fixed = not spec.get("wheels")
    assert ('" world:=true"' in launch) == fixed
    plain = etree.fromstring(expand_file(entry, {}).encode())
    assert plain.find("link[@name='world']") is None
    placed = etree.fromstring(expand_file(entry, {"world": "true"}).encode())
    (joint,) = [j for j in placed.findall("joint") if j.find("parent").get("link") == "world"]
    children = {j.find("child").get("link") for j in plain.findall("joint")}
    (plain_root,) = [link.get("name") for link in plain.findall("link") if link.get("name") not in children]
    assert joint.find("child").get("link") == plain_root and joint.get("type") == "fixed"


def test_sensor_blocks_use_only_sdformats_elements_and_the_bridge_only_topics_gazebo_publishes(tmp_path):
    """Every sensor type on one robot (tests/pipeline/test_sensors.py's spec): each element of each <sensor> has only
    children sdformat 1.11 (and gz-sensors, for gz_frame_id) reads there; each bridged topic is one the sensor
    publishes (gz-sensors 8); the world loads the systems that make them publish."""
    spec = tmp_path / "sens.yaml"
    spec.write_text((Path(__file__).parent.parent / "shared" / "sensors.yaml").read_text(encoding="utf-8"))
    xacrokit.generate(spec, tmp_path / "pkg")
    urdf = etree.parse(str(tmp_path / "pkg" / "urdf" / "sens.urdf")).getroot()
    children = FACTS["sensor_children"]
    published = set()
    for gazebo in urdf.findall("gazebo"):
        for sensor in gazebo.findall("sensor"):
            assert sensor.get("type") in FACTS["sensor_types"]
            for element in sensor.iter(etree.Element):
                if element.tag == "noise":
                    allowed = children["noise_attribute" if element.get("type") else "noise_element"]
                elif element.tag in ("x", "y", "z", "angular_velocity", "linear_acceleration"):
                    allowed = ["noise"] if element.tag in "xyz" else ["x", "y", "z"]
                else:
                    allowed = children.get(element.tag, [])
                assert {c.tag for c in element} <= set(allowed), (element.tag, [c.tag for c in element])
            topic = sensor.findtext("topic")
            parent = topic.rpartition("/")[0]
            for pattern in FACTS["sensor_topics"][sensor.get("type")]:
                published.add(pattern.format(topic=topic, parent=f"{parent}/" if parent else ""))
    entries = yaml.safe_load((tmp_path / "pkg" / "config" / "sens_bridge.yaml").read_text(encoding="utf-8"))
    bridged = {e["gz_topic_name"] for e in entries} - {"clock"}
    assert bridged <= published and len(bridged) == 9, (
        bridged - published,
        bridged,
    )  # (lidar 1, 3D 1, rgbd 4, camera 2, imu 1)
    world = etree.parse(str(tmp_path / "pkg" / "worlds" / "sens.sdf")).getroot()
    systems = {p.get("filename"): p.get("name") for p in world.iter("plugin")}
    assert systems == FACTS["world_systems"]


@pytest.mark.parametrize("example", ROBOT_EXAMPLES, ids=lambda p: p.stem)
def test_a_package_with_meshes_exports_the_model_path_gazebo_finds_them_on(example, tmp_path):
    """sdformat turns package://PKG/x into model://PKG/x, which Gazebo looks for in each GZ_SIM_RESOURCE_PATH entry;
    ros_gz_sim's gz_sim.launch.py puts there every package's <gazebo_ros gazebo_model_path>, ${prefix} replaced by
    the package's share folder (gazebosim/ros_gz, ros_gz_sim/launch/gz_sim.launch.py.in). Installed as share/PKG,
    every mesh the URDF names is found that way."""
    result = xacrokit.generate(example, tmp_path / "share" / "pkg")
    package = result.model.package
    share = tmp_path / "share" / package
    (tmp_path / "share" / "pkg").rename(share)
    manifest = etree.parse(str(share / "package.xml")).getroot()
    exported = [e.get("gazebo_model_path") for e in manifest.iterfind("export/gazebo_ros")]
    urdf = etree.parse(str(share / "urdf" / f"{result.model.name}.urdf")).getroot()
    meshes = [m.get("filename") for m in urdf.iter("mesh")]
    if not meshes:
        assert exported == []  # (nothing to find: no export)
        return
    (model_path,) = exported
    root = Path(model_path.replace("${prefix}", str(share)))
    for uri in meshes:
        assert uri.startswith(f"package://{package}/"), uri
        assert (root / uri.removeprefix("package://")).resolve().is_file(), uri


@pytest.mark.parametrize("example", ROBOT_EXAMPLES, ids=lambda p: p.stem)
def test_joint_limits_yaml_is_the_urdfs_limits_in_moveits_layout(example, tmp_path):
    """config/joint_limits.yaml (MoveIt's and UR's layout): every moving joint the URDF has, except mimic joints,
    with the URDF's own numbers, read back from the URDF text here."""
    result = xacrokit.generate(example, tmp_path / "pkg")
    limits = yaml.safe_load((tmp_path / "pkg" / "config" / "joint_limits.yaml").read_text(encoding="utf-8"))
    urdf = etree.parse(str(tmp_path / "pkg" / "urdf" / f"{result.model.name}.urdf")).getroot()
    moving = [
        j
        for j in urdf.iterfind("joint")
        if j.get("type") in ("revolute", "continuous", "prismatic") and j.find("mimic") is None
    ]
    assert sorted(limits["joint_limits"]) == sorted(j.get("name") for j in moving)
    for joint in moving:
        entry, limit = limits["joint_limits"][joint.get("name")], joint.find("limit")
        assert entry["max_velocity"] == float(limit.get("velocity")) and entry["max_effort"] == float(
            limit.get("effort")
        )
        assert entry["has_velocity_limits"] and entry["has_effort_limits"] and not entry["has_acceleration_limits"]
        if joint.get("type") == "continuous":
            assert entry["has_position_limits"] is False and "min_position" not in entry
        else:
            assert entry["has_position_limits"] is True
            assert (entry["min_position"], entry["max_position"]) == (
                float(limit.get("lower")),
                float(limit.get("upper")),
            )


@pytest.mark.parametrize(
    "example", [p for p in ROBOT_EXAMPLES if p.stem in ("diff_drive", "rover")], ids=lambda p: p.stem
)
def test_the_diff_drive_tracks_its_base_frame_within_its_limits(example, tmp_path):
    """diff_drive_controller's odometry is of the axle midpoint, published as base_frame_id: that frame sits above
    it. Its speed limits are the wheels' velocity limit at the rim (v = w r, turning on the spot 2 v / separation),
    its acceleration at most what the wheels' efforts give the robot's mass and mu g; commands come from /cmd_vel."""
    import math

    import yourdfpy

    result = xacrokit.generate(example, tmp_path / "pkg")
    config = yaml.safe_load((tmp_path / "pkg" / "config" / f"{result.model.name}_controllers.yaml").read_text())
    if "diff_drive_controller" not in config:
        pytest.skip("no differential drive")
    drive = config["diff_drive_controller"]["ros__parameters"]
    urdf = yourdfpy.URDF.load(str(tmp_path / "pkg" / "urdf" / f"{result.model.name}.urdf"), load_meshes=False)
    wheels = [*drive["left_wheel_names"], *drive["right_wheel_names"]]
    centres = [urdf.get_transform(urdf.joint_map[w].child, drive["base_frame_id"])[:3, 3] for w in wheels]
    middle = sum(centres) / len(centres)
    assert abs(middle[0]) < 1e-9 and abs(middle[1]) < 1e-9, middle
    omega = min(urdf.joint_map[w].limit.velocity for w in wheels)
    speed = omega * drive["wheel_radius"]
    assert drive["linear.x.max_velocity"] == pytest.approx(speed, rel=1e-12) == -drive["linear.x.min_velocity"]
    assert drive["angular.z.max_velocity"] == pytest.approx(2 * speed / drive["wheel_separation"], rel=1e-12)
    mass = sum(link.inertial.mass for link in urdf.robot.links if link.inertial is not None)
    efforts = sum(urdf.joint_map[w].limit.effort for w in wheels)
    bound = min(efforts / drive["wheel_radius"] / mass, 1.0 * 9.80665)  # (the wheels' mu1: 1.0)
    assert drive["linear.x.max_acceleration"] == pytest.approx(bound, rel=1e-12) == -drive["linear.x.max_deceleration"]
    assert math.isfinite(drive["angular.z.max_acceleration"])
    launch = (tmp_path / "pkg" / "launch" / "control.launch.py").read_text()
    assert 'remappings=[("/diff_drive_controller/cmd_vel", LaunchConfiguration("cmd_vel"))]' in launch
    gazebo = expand_file(tmp_path / "pkg" / "urdf" / f"{result.model.name}.urdf.xacro", {"ros2_control": "gazebo"})
    remap = etree.fromstring(gazebo.encode()).find("gazebo/plugin/ros/remapping")
    assert remap.text == "/diff_drive_controller/cmd_vel:=/cmd_vel"


def test_a_drive_whose_base_frame_is_off_the_axle_is_warned_at_its_wheel(tmp_path):
    """The odometry is the axle midpoint's: a base frame 5 cm behind it (the diff-drive example as it was) is said,
    located at the first wheel, with the offset; the example now has none."""
    example = next(p for p in ROBOT_EXAMPLES if p.stem == "diff_drive")
    assert not [w for w in xacrokit.generate(example, tmp_path / "now").warnings if "axle" in str(w)]
    text = example.read_text(encoding="utf-8").replace(
        "origin: {xyz: [0, 0.18, -0.055]}", "origin: {xyz: [0.05, 0.18, -0.055]}"
    )
    text = text.replace("origin: {xyz: [0, -0.18, -0.055]}", "origin: {xyz: [0.05, -0.18, -0.055]}")
    spec = tmp_path / "diff_drive.yaml"
    spec.write_text(text, encoding="utf-8")
    (said,) = [w for w in xacrokit.generate(spec, tmp_path / "then").warnings if "axle" in str(w)]
    assert said.line == text.splitlines().index("  left_wheel:") + 1
    assert "x = 0.05, y = 0 m from base_footprint" in str(said)
