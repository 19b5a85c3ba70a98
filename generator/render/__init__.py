"""The render stage: a resolved robot or scene becomes the files of a ROS 2 description package, in memory.

``package`` renders a robot's package, ``scene`` a scene's (which carries its robots' macro files, rendered by
``package``), ``control`` works out the controllers both write, and ``environment`` holds what they share: the jinja2
environment, :class:`RenderedFile` and the macro modes.
"""

from __future__ import annotations

from .control import controllers
from .environment import MacroMode, RenderedFile, environment
from .package import render_package, simple_shape_link
from .scene import render_probe, render_scene

__all__ = [
    "MacroMode",
    "RenderedFile",
    "controllers",
    "environment",
    "render_package",
    "render_probe",
    "render_scene",
    "simple_shape_link",
]
