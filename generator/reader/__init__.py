"""Reading any robot, once: what to read (``robot_input``), a URDF, xacro document, spec or scene to URDF text
(``robot_source``), the read robot every feature takes, its text and typed view parsed once (``read_robot``), its
one kinematic model (``kinematic_model``); meshes copied out of a robot's folder safely (``mesh_copies``) and named
poses (``named_poses``). Every command that takes a robot reads it here."""

from typing import Literal

InputKind = Literal["urdf", "xacro", "spec"]  # what a robot file is (:func:`.robot_source.input_kind`)
