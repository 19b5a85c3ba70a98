"""The render stage for a scene: the scene package's files, beside the robot packages' (:mod:`.package`).

A scene package carries the macro files and meshes of each robot of ours under ``robots/NAME_description/`` (rendered
by the robot renderer; the meshes' URIs name the scene package), its own entry ``urdf/SCENE.urdf.xacro`` (the world
link and one macro call per instance), a launch file, an RViz configuration and one controllers file per instance
with ros2_control.
"""

from __future__ import annotations

import dataclasses
import shlex

from .. import __version__
from ..gcpause import collector_paused
from ..model import Instance, Origin, Scene
from ..text import command_text, comment_text, xacro_text
from .control import controllers
from .environment import MacroMode, RenderedFile, environment
from .package import render_package

ROBOT_FILES = ("urdf/", "config/")  # what a scene carries of each robot package (no nested package.xml)


@collector_paused()
def render_scene(scene: Scene, *, spec_name: str = "scene.yaml", macros: MacroMode = "inline") -> list[RenderedFile]:
    """Every file of the scene package except the expanded URDF; ``macros`` is how each robot's macro is written."""
    env = environment()
    files: list[RenderedFile] = []
    for robot in scene.robots:
        for file in render_package(robot, macros=macros, spec_name=spec_name):
            if file.path.startswith(ROBOT_FILES) and not file.path.endswith("_controllers.yaml"):
                files.append(RenderedFile(f"robots/{robot.package}/{file.path}", file.content))
        files += [RenderedFile(file.path, file.content) for file in robot.files]  # (its meshes, moved here)
    has_control = any(i.robot is not None and i.robot.ros2_control is not None for i in scene.instances)
    context = {
        "scene": scene,
        "version": __version__,
        "spec_name": comment_text(spec_name),  # (a file name may hold a newline: it would end a comment)
        "spec_command": command_text(scene.command or "gen-robot " + shlex.quote(spec_name)),
        "has_control": has_control,
        "macros": macros,
        "fixed_frame": scene.world,
        "xacro_text": xacro_text,
    }
    for path, template in (
        ("package.xml", "scene/package.xml.j2"),
        ("CMakeLists.txt", "scene/CMakeLists.txt.j2"),
        ("README.md", "scene/README.md.j2"),
        (f"urdf/{scene.name}.urdf.xacro", "scene/scene.urdf.xacro.j2"),
        ("launch/display.launch.py", "scene/display.launch.py.j2"),
        (f"rviz/{scene.name}.rviz", "package/rviz/robot.rviz.j2"),
    ):
        files.append(RenderedFile(path, env.get_template(template).render(context)))
    controllers_template = env.get_template("package/config/controllers.yaml.j2")
    for instance in scene.instances:
        ours = instance.robot
        if ours is not None and ours.ros2_control is not None:
            text = controllers_template.render(
                robot=ours,
                version=__version__,
                spec_name=context["spec_name"],
                prefix=instance.prefix,
                **controllers(ours, instance.prefix, mounted=True),
            )
            files.append(RenderedFile(f"config/{instance.name}_controllers.yaml", text))
    return sorted(files, key=lambda f: f.path)


def render_probe(instance: Instance) -> str:
    """A document holding one third-party instance alone (at the origin of a stand-in for its parent link):
    expanding it tells the scene which links and joints the macro makes (the call is the one the scene's entry
    makes)."""
    probe = dataclasses.replace(instance, origin=Origin())
    return environment().get_template("scene/probe.urdf.xacro.j2").render(instance=probe)
