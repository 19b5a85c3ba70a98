"""The render stage: the model becomes the files of a ROS 2 description package, in memory.

jinja2 with StrictUndefined (a template that asks for something the model lacks fails loudly) and XML autoescaping
for the .xacro/.xml templates. Every user string that lands in a xacro file goes through ``xacro_text``, so a ``${``
or ``$(`` in it is written escaped and never evaluated by xacro. Numbers are written with ``repr`` (round-trip exact).
"""

from __future__ import annotations

import re
from dataclasses import dataclass
from functools import cache
from pathlib import PurePosixPath
from typing import Any, Literal

import jinja2
import yaml
from lxml import etree
from markupsafe import Markup

from . import __version__
from .emit import robot_elements
from .gcpause import collector_paused
from .model import Box, Cylinder, Link, Mesh, Origin, Robot, Sphere
from .resources import macros_dir, templates_dir
from .text import material_name, num, vec, xacro_text

MacroMode = Literal["copy", "find", "inline"]
COPIED_MACROS_DIR = "urdf/xacrokit"


@dataclass(frozen=True)
class RenderedFile:
    """One file of the package: a POSIX path relative to the package root and its full text."""

    path: str
    content: str


def indent_block(text: str, width: int) -> Markup:
    """Rendered template text with every non-empty line indented by ``width`` spaces (jinja's ``indent`` also
    indents an empty block's first line)."""
    return Markup(re.sub(r"(?m)^(?=.)", " " * width, str(text)))  # (already rendered, so already escaped)


def simple_shape_link(link: Link) -> str | None:
    """The links.xacro macro that makes exactly this link (visual, same collision, shape inertia), if there is one."""
    visual, collision, inertial = link.visual, link.collision, link.inertial
    if visual is None or inertial is None or isinstance(visual.shape, Mesh):
        return None
    same_collision = collision is not None and collision.shape == visual.shape and collision.origin == visual.origin
    computed_here = inertial.kind != "explicit" and inertial.origin == visual.origin
    if not (same_collision and computed_here):
        return None
    return {Box: "box_link", Cylinder: "cylinder_link", Sphere: "sphere_link"}[type(visual.shape)]


@cache
def environment() -> jinja2.Environment:
    env = jinja2.Environment(
        loader=jinja2.FileSystemLoader(str(templates_dir())),
        undefined=jinja2.StrictUndefined,
        autoescape=jinja2.select_autoescape(enabled_extensions=("xacro.j2", "xml.j2"), default_for_string=False),
        keep_trailing_newline=True,
        trim_blocks=True,
        lstrip_blocks=True,
    )
    env.filters.update(num=num, vec=vec, xacro_text=xacro_text, indent_block=indent_block)
    env.globals.update(
        simple_shape_link=simple_shape_link,
        is_box=lambda s: isinstance(s, Box),
        is_cylinder=lambda s: isinstance(s, Cylinder),
        is_sphere=lambda s: isinstance(s, Sphere),
        is_mesh=lambda s: isinstance(s, Mesh),
        zero_origin=Origin(),
    )
    return env


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
    """The library files a self-contained package carries, with the private helpers they include."""
    folder = macros_dir()
    names = [*files, "_inc/checks.xacro", *(["_inc/frames.xacro"] if "dh.xacro" in files else [])]
    return [RenderedFile(f"{COPIED_MACROS_DIR}/{name}", (folder / name).read_text(encoding="utf-8")) for name in names]


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
            if row.limit.lower is not None:
                limit.update(lower=row.limit.lower, upper=row.limit.upper)
            entry["limit"] = limit
        if row.dynamics is not None:
            entry["dynamics"] = {"damping": row.dynamics.damping, "friction": row.dynamics.friction}
        if row.mass is not None:
            entry.update(mass=row.mass, radius=row.radius)
            if row.material:
                entry["material"] = material_name(robot, row.material)
        rows.append(entry)
    header = (
        f"# DH table of arm '{arm.name}' ({arm.convention} convention), SI units: m and rad.\n"
        f"# Generated by xacrokit {__version__}; read by urdf/{robot.name}_macro.xacro through dh_arm.\n"
    )
    return header + yaml.safe_dump({"joints": rows}, sort_keys=False, default_flow_style=None, width=120)


@collector_paused()
def render_package(robot: Robot, *, macros: MacroMode = "inline", spec_name: str = "spec.yaml") -> list[RenderedFile]:
    """Every file of ``NAME_description/`` except the expanded URDF (the expand stage adds that)."""
    env = environment()
    macro_files = used_macro_files(robot)
    include_prefix = "xacrokit/" if macros == "copy" else "$(find xacrokit)/macros/"
    if macros == "inline":  # plain XML computed here: no library macros to include
        macro_files = []
    context = {
        "robot": robot,
        "version": __version__,
        "spec_name": spec_name,
        "macros": macros,
        "macro_includes": [include_prefix + name for name in macro_files],
        "inline_body": _inline_body(robot) if macros == "inline" else "",
        "material_name": lambda name: material_name(robot, name),
        "has_control": robot.ros2_control is not None,
        **controllers(robot),
        "prefix": "",
    }
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
        f"rviz/{name}.rviz": "package/rviz/robot.rviz.j2",
    }
    if robot.ros2_control is not None:
        plan[f"config/{name}_controllers.yaml"] = "package/config/controllers.yaml.j2"
    files = [RenderedFile(path, env.get_template(template).render(context)) for path, template in plan.items()]
    if macros != "inline":  # inline arms are computed here, not read from their tables by dh_arm
        files += [RenderedFile(f"config/{a.name}.dh.yaml", dh_table_yaml(robot, i)) for i, a in enumerate(robot.arms)]
    if macros == "copy":
        files += _copied_macros(macro_files)
    for file in files:  # generated paths come from validated names; keep it that way
        parts = PurePosixPath(file.path).parts
        assert not PurePosixPath(file.path).is_absolute() and ".." not in parts, file.path
    return sorted(files, key=lambda f: f.path)


def _inline_body(robot: Robot) -> Markup:
    """The robot's links, joints, arms and wheels as plain XML for the robot macro, names glued to ``${prefix}``.

    Written by the direct emitter with the literal prefix ``${prefix}``, which xacro then fills in; a mesh filename
    (the only free text) is escaped so that xacro copies it verbatim. Each part of a link or joint is one line, not
    indented further: readable in a diff, and about a fifth cheaper for xacro than full indentation (less whitespace
    to copy).
    """
    lines = []
    for element in robot_elements(robot, prefix="${prefix}", extras=False):
        for mesh in element.iter("mesh"):
            mesh.set("filename", xacro_text(mesh.get("filename", "")))
        children = list(element)
        if children:  # each part (visual, collision, inertial; parent, child, origin, ...) on a line of its own
            element.text = "\n  "
            for child in children[:-1]:
                child.tail = "\n  "
            children[-1].tail = "\n"
        lines.append(etree.tostring(element, encoding="unicode").strip())
    return Markup("\n".join(lines) + "\n")


def controllers(robot: Robot, prefix: str = "", *, mounted: bool = False) -> dict[str, Any]:
    """What config/..._controllers.yaml sets up for ``robot`` (names with ``prefix``): ``drive``, a
    diff_drive_controller for its wheels when they make a differential drive (see :func:`_differential_drive`), and
    ``command_groups``, the other controlled joints grouped by their first command interface (one forward command
    controller per group). ``mounted``: the robot is fixed into a scene's URDF, so its drive must not publish the
    odom -> base transform (the base would have two parents in TF)."""
    drive = _differential_drive(robot, prefix)
    if drive:
        drive["odom_tf"] = not mounted
    driven = set(drive["left"] + drive["right"]) if drive else set()
    groups: dict[str, list[str]] = {}
    for joint in robot.ros2_control or ():
        if joint.interfaces.command and prefix + joint.name not in driven:
            groups.setdefault(joint.interfaces.command[0], []).append(prefix + joint.name)
    return {"command_groups": groups, "drive": drive}


def _differential_drive(robot: Robot, prefix: str) -> dict[str, Any] | None:
    """The diff_drive_controller parameters of a robot whose wheels are a differential drive: two or more wheels on
    one parent link, axles along +y unrotated (a positive speed drives forward, REP 103), velocity-commanded, of one
    radius, on both sides of the parent's x-z plane. Separation: mean left y - mean right y. Otherwise None."""
    controlled = {j.name: j for j in robot.ros2_control or ()}
    wheels = robot.wheels
    if len(wheels) < 2 or len({w.parent for w in wheels}) != 1:
        return None
    for wheel in wheels:
        joint = controlled.get(wheel.joint_name)
        if wheel.axis != "y" or any(wheel.origin.rpy) or joint is None:
            return None
        if tuple(joint.interfaces.command[:1]) != ("velocity",):
            return None
    if len({w.radius for w in wheels}) != 1:
        return None
    left = [w for w in wheels if w.origin.xyz[1] > 0]
    right = [w for w in wheels if w.origin.xyz[1] < 0]
    if not left or not right or len(left) + len(right) != len(wheels):
        return None
    separation = sum(w.origin.xyz[1] for w in left) / len(left) - sum(w.origin.xyz[1] for w in right) / len(right)
    return {
        "left": [prefix + w.joint_name for w in left],
        "right": [prefix + w.joint_name for w in right],
        "separation": separation,
        "radius": wheels[0].radius,
        "base_frame": prefix + robot.root,
        "odom_frame": prefix + "odom",
    }
