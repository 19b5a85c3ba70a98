"""The render stage for a robot: the model becomes the files of a ROS 2 description package, in memory.

The robot is written once, in ``urdf/NAME_macro.xacro`` (the macro ``NAME``); the entry ``urdf/NAME.urdf.xacro`` is
its arguments and one call of that macro, as Universal Robots' entry files are. Plain ``<link>``/``<joint>`` XML comes
from the direct emitter (:mod:`xacrokit.emit`), written with the literal prefix ``${prefix}``: the whole robot in the
``inline`` mode, the links no library macro makes and the spec's joints in the ``copy``/``find`` modes, which call the
library's box_link/cylinder_link/sphere_link, dh_arm and wheel macros for the rest.
"""

from __future__ import annotations

import posixpath
import shlex
from collections.abc import Iterable
from pathlib import PurePosixPath
from typing import Any

import yaml
from lxml import etree
from markupsafe import Markup

from .. import __version__
from ..emit import joint_element, link_element, robot_elements
from ..model import MOVING, Box, Cylinder, Limit, Link, Mesh, Robot, Sphere, material_name
from ..shared.gc_pause import collector_paused
from ..shared.package_data import macros_dir
from ..shared.sim_sensors import XACRO_NAMESPACE, bridge_entries, sensor_element
from ..shared.value_text import command_text, comment_text, xacro_text
from ..shared.xml_parse import parse_xml
from .control import controllers
from .environment import MacroMode, RenderedFile, environment

COPIED_MACROS_DIR = "urdf/xacrokit"
XACRO_NS = "{http://www.ros.org/wiki/xacro}"
PREFIX = "${prefix}"  # what the robot macro glues in front of every name (xacro fills it in)


def simple_shape_link(link: Link) -> str | None:
    """The links.xacro macro that makes exactly this link (visual, same collision, shape inertia), if there is one."""
    inertial = link.inertial
    if len(link.visuals) != 1 or len(link.collisions) != 1 or inertial is None:
        return None
    (visual,), (collision,) = link.visuals, link.collisions
    if isinstance(visual.shape, Mesh):
        return None
    same_collision = collision.shape == visual.shape and collision.origin == visual.origin
    computed_here = inertial.kind in ("box", "cylinder", "sphere") and inertial.origin == visual.origin
    if not (same_collision and computed_here):
        return None
    return {Box: "box_link", Cylinder: "cylinder_link", Sphere: "sphere_link"}[type(visual.shape)]


def used_macro_files(robot: Robot) -> list[str]:
    """Library files the robot's macro includes (each brings inertia.xacro and the private helpers with it)."""
    files = ["inertia.xacro"]
    if any(simple_shape_link(link) for link in robot.links):
        files.append("links.xacro")
    if robot.wheels:
        files.append("wheel.xacro")
    if robot.arms:
        files.append("dh.xacro")
    return files


def _copied_macros(files: list[str]) -> list[RenderedFile]:
    """The library files a self-contained package carries: ``files`` and every file they include, as the files'
    own ``<xacro:include>`` elements say (paths relative to the including file)."""
    folder = macros_dir()
    copied: dict[str, str] = {}
    pending = list(files)
    while pending:
        name = pending.pop(0)
        if name in copied:
            continue
        copied[name] = text = (folder / name).read_text(encoding="utf-8")
        root = parse_xml(text, name)
        for include in root.iter(f"{XACRO_NS}include"):
            pending.append(posixpath.normpath(posixpath.join(posixpath.dirname(name), include.get("filename", ""))))
    return [RenderedFile(f"{COPIED_MACROS_DIR}/{name}", text) for name, text in copied.items()]


def dh_table_yaml(robot: Robot, arm_index: int) -> str:
    """The arm's DH table as the YAML that dh_arm reads (SI numbers, material names already namespaced)."""
    arm = robot.arms[arm_index]
    rows = []
    for row in arm.rows:
        entry: dict[str, object] = {
            "name": row.name,
            "link": row.link,
            "type": row.type,
            "a": row.a,
            "d": row.d,
            "alpha": row.alpha,
            "theta": row.theta,
        }
        if row.limit is not None:
            limit = {"effort": row.limit.effort, "velocity": row.limit.velocity}
            if row.limit.lower is not None and row.limit.upper is not None:
                limit.update(lower=row.limit.lower, upper=row.limit.upper)
            entry["limit"] = limit
        if row.dynamics is not None:
            entry["dynamics"] = {"damping": row.dynamics.damping, "friction": row.dynamics.friction}
        if row.mass is not None:
            entry.update(mass=row.mass, radius=row.radius)
            if row.material:
                entry["material"] = material_name(robot, row.material)
        if row.inertia is not None:  # (the tensor as the table gives it: origin in DH frame i, rpy)
            i = row.inertia
            entry["inertia"] = {
                **{"ixx": i.ixx, "ixy": i.ixy, "ixz": i.ixz, "iyy": i.iyy, "iyz": i.iyz, "izz": i.izz},
                "origin": {"xyz": list(i.origin.xyz), "rpy": list(i.origin.rpy)},
            }
        rows.append(entry)
    header = (
        f"# DH table of arm '{arm.name}' ({arm.convention} convention), SI units: m and rad.\n"
        f"# Generated by xacrokit {__version__}; read by urdf/{robot.name}_macro.xacro through dh_arm.\n"
    )
    return header + yaml.safe_dump({"joints": rows}, sort_keys=False, default_flow_style=None, width=120)


def joint_limits_yaml(robot: Robot) -> str:
    """config/joint_limits.yaml: every moving, non-mimic joint's limits in the layout MoveIt's joint_limits.yaml and
    Universal Robots' config/UR/joint_limits.yaml use (has_*_limits flags beside the values); a URDF states no
    acceleration limit: one is claimed where the spec's limit gives ``acceleration`` (MoveIt's time
    parameterization needs one)."""
    limits: list[tuple[str, Limit | None]] = [
        (j.name, j.limit) for j in robot.joints if j.type in MOVING and j.mimic is None
    ]
    limits += [(row.name, row.limit) for arm in robot.arms for row in arm.rows if row.type in MOVING]
    limits += [(w.joint_name, Limit(effort=w.effort, velocity=w.velocity)) for w in robot.wheels]
    entries: dict[str, dict[str, object]] = {}
    for name, limit in limits:
        bounds = limit.bounds if limit is not None else None
        entry: dict[str, object] = {"has_position_limits": bounds is not None}
        if bounds is not None:
            entry.update(min_position=bounds[0], max_position=bounds[1])
        entry["has_velocity_limits"] = limit is not None
        if limit is not None:
            entry["max_velocity"] = limit.velocity
        accelerating = limit is not None and limit.acceleration is not None
        entry["has_acceleration_limits"] = accelerating
        if limit is not None and limit.acceleration is not None:
            entry["max_acceleration"] = limit.acceleration
        entry["has_effort_limits"] = limit is not None
        if limit is not None:
            entry["max_effort"] = limit.effort
        entries[name] = entry
    header = (
        f"# Joint limits of {robot.name} as its URDF gives them (rad, rad/s, N*m; m, m/s, N for prismatic joints), in\n"
        "# the layout of MoveIt's joint_limits.yaml. Generated by xacrokit; no acceleration limit is known here.\n"
    )
    if any(limit is not None and limit.acceleration is not None for _, limit in limits):
        header = (
            f"# Joint limits of {robot.name} as its URDF gives them (rad, rad/s, N*m; m, m/s, N for prismatic joints)\n"
            "# and the accelerations its spec gives (rad/s^2, m/s^2), in the layout of MoveIt's joint_limits.yaml.\n"
        )
    return header + yaml.safe_dump({"joint_limits": entries}, sort_keys=False, width=120)


def bridge_yaml(name: str, entries: list[dict[str, str]]) -> str:
    """config/NAME_bridge.yaml: ros_gz_bridge's parameter_bridge entries, /clock first, then ``entries`` (each
    sensor's topics, :func:`xacrokit.shared.sim_sensors.bridge_entries`), Gazebo to ROS."""
    clock = {
        "ros_topic_name": "clock",
        "gz_topic_name": "clock",
        "ros_type_name": "rosgraph_msgs/msg/Clock",
        "gz_type_name": "gz.msgs.Clock",
        "direction": "GZ_TO_ROS",
    }
    header = (
        f"# Generated by xacrokit {__version__}: ros_gz_bridge (parameter_bridge, config_file) of {name}'s\n"
        "# simulated clock and sensors, Gazebo to ROS.\n"
    )
    return header + yaml.safe_dump([clock, *entries], sort_keys=False, width=120)


@collector_paused()
def render_package(robot: Robot, *, macros: MacroMode = "inline", spec_name: str = "spec.yaml") -> list[RenderedFile]:
    """Every file of ``NAME_description/`` except the expanded URDF (the expand stage adds that)."""
    env = environment()
    macro_files = used_macro_files(robot) if macros != "inline" else []  # (inline: plain XML, nothing to include)
    context = _package_context(robot, macros, spec_name, macro_files)
    name = robot.name
    plan = {
        "package.xml": "package/package.xml.j2",
        "CMakeLists.txt": "package/CMakeLists.txt.j2",
        "README.md": "package/README.md.j2",
        f"urdf/{name}.urdf.xacro": "package/urdf/robot.urdf.xacro.j2",
        f"urdf/{name}_macro.xacro": "package/urdf/robot_macro.xacro.j2",
        f"urdf/{name}.materials.xacro": "package/urdf/robot.materials.xacro.j2",
        f"urdf/{name}.gazebo.xacro": "package/urdf/robot.gazebo.xacro.j2",
        f"urdf/{name}.ros2_control.xacro": "package/urdf/robot.ros2_control.xacro.j2",
        "launch/display.launch.py": "package/launch/display.launch.py.j2",
        "launch/gazebo.launch.py": "package/launch/gazebo.launch.py.j2",
        f"worlds/{name}.sdf": "package/worlds/world.sdf.j2",
        f"rviz/{name}.rviz": "package/rviz/robot.rviz.j2",
    }
    if robot.ros2_control is not None:
        plan[f"config/{name}_controllers.yaml"] = "package/config/controllers.yaml.j2"
        plan["launch/control.launch.py"] = "package/launch/control.launch.py.j2"
    files = [RenderedFile(path, env.get_template(template).render(context)) for path, template in plan.items()]
    seed = env.get_template("package/urdf/robot.extension.xacro.j2").render(
        robot=robot, extension=Markup(robot.extension), extension_source=robot.extension_source
    )
    files.append(RenderedFile(f"urdf/{name}_extension.xacro", seed, seed=True))  # (the user's: written once)
    entries = [entry for sensor in robot.sensors for entry in bridge_entries(sensor)]
    files.append(RenderedFile(f"config/{name}_bridge.yaml", bridge_yaml(name, entries)))
    files.append(RenderedFile("config/joint_limits.yaml", joint_limits_yaml(robot)))
    if macros != "inline":  # inline arms are computed here, not read from their tables by dh_arm
        files += [RenderedFile(f"config/{a.name}.dh.yaml", dh_table_yaml(robot, i)) for i, a in enumerate(robot.arms)]
    if macros == "copy":
        files += _copied_macros(macro_files)
    files += [RenderedFile(file.path, file.content) for file in robot.files]  # (meshes copied or made)
    for file in files:  # generated paths come from validated names; keep it that way
        parts = PurePosixPath(file.path).parts
        assert not PurePosixPath(file.path).is_absolute() and ".." not in parts, file.path
    return sorted(files, key=lambda f: f.path)


def _package_context(robot: Robot, macros: MacroMode, spec_name: str, macro_files: list[str]) -> dict[str, Any]:
    """What the package's templates read."""
    include_prefix = "xacrokit/" if macros == "copy" else "$(find xacrokit)/macros/"
    return {
        "robot": robot,
        "fixed_frame": robot.root,  # RViz's (the launch file passes the prefixed one to rviz2 -f)
        "version": __version__,
        "spec_name": comment_text(spec_name),  # (a file name may hold a newline: it would end a comment)
        "spec_command": command_text("gen-robot " + shlex.quote(spec_name)),
        "macros": macros,
        "macro_includes": [include_prefix + name for name in macro_files],
        "mount_joint": robot.mount_joint_name,
        **(_inline_parts(robot) if macros == "inline" else _library_parts(robot)),
        "material_name": lambda name: material_name(robot, name),
        "has_control": robot.ros2_control is not None,
        # package:// meshes: sdformat makes them model://PACKAGE/..., which Gazebo finds through GZ_SIM_RESOURCE_PATH;
        # ros_gz_sim's gz_sim.launch.py adds each package's exported gazebo_model_path to it
        "has_meshes": robot.has_package_meshes,
        **controllers(robot),
        "prefix": "",
        "fixed_base": not robot.wheels,  # (simulated, a robot without wheels stands fixed to the world)
        "spawn_z": "0.0",
        "sensor_xml": Markup(
            "".join(
                etree.tostring(sensor_element(s, PREFIX, XACRO_NAMESPACE), encoding="unicode", pretty_print=True)
                for s in robot.sensors
            )
        ),
    }


def _inline_parts(robot: Robot) -> dict[str, Any]:
    """The robot macro's body in the inline mode: every link, joint, arm and wheel as plain XML."""
    return {"inline_body": macro_xml(robot_elements(robot, prefix=PREFIX, extras=False))}


def _library_parts(robot: Robot) -> dict[str, Any]:
    """The robot macro's body in the copy/find modes: ``link_parts``, each spec link with the links.xacro macro that
    makes it or else its plain XML, and ``joint_xml``, the spec's joints (arms and wheels are library macro calls)."""
    link_parts = []
    for link in robot.links:
        macro = simple_shape_link(link)
        link_parts.append((link, macro, None if macro else macro_xml([link_element(robot, PREFIX, link)])))
    return {"link_parts": link_parts, "joint_xml": macro_xml(joint_element(PREFIX, j) for j in robot.joints)}


def macro_xml(elements: Iterable[etree._Element]) -> Markup:
    """Emitted elements as the text of a macro body, names glued to ``${prefix}``, which xacro then fills in.

    A mesh filename (the only free text) is escaped so that xacro copies it verbatim. Each part of a link or joint is
    one line, not indented further: readable in a diff, and about a fifth cheaper for xacro than full indentation
    (less whitespace to copy).
    """
    lines = []
    for element in elements:
        for mesh in element.iter("mesh"):
            mesh.set("filename", xacro_text(mesh.get("filename", "")))
        children = list(element)
        if children:  # each part (visual, collision, inertial; parent, child, origin, ...) on a line of its own
            element.text = "\n  "
            for child in children[:-1]:
                child.tail = "\n  "
            children[-1].tail = "\n"
        lines.append(etree.tostring(element, encoding="unicode").strip())
    return Markup("".join(line + "\n" for line in lines))
