"""Multi-robot scenes: several robots (our specs and third-party xacro macros) in one description.

A scene is the robot pipeline's sibling, not a second pipeline: it is loaded like a robot spec, checked and resolved
here into a :class:`~xacrokit.model.Scene` (which knows every link and joint name of every instance before anything
is written), rendered beside the robot packages (:mod:`xacrokit.render.scene`), expanded and written by the same
functions as a robot's package (:mod:`xacrokit.pipeline`). Any name two instances would share is an error listing
the names and the instances, found before writing; a third-party macro's names are found by expanding it alone first.

``build`` reads a scene spec, ``fleet`` makes copies of one robot, both into the typed plan of ``plan``, which
resolves it (``probe`` learns the third-party macros' names).
"""

from __future__ import annotations

from .build import build_scene, is_scene, scene_validator
from .fleet import fleet_scene

__all__ = ["build_scene", "fleet_scene", "is_scene", "scene_validator"]
