"""Reading any robot: a URDF, xacro document, spec or scene to URDF text and where it came from (``robot_source``),
walked through one typed, located view (``urdf_view``); meshes copied out of a robot's folder safely
(``mesh_copies``). Every command that takes a robot reads it here."""

from typing import Literal

InputKind = Literal["urdf", "xacro", "spec"]  # what a robot file is (:func:`.robot_source.input_kind`)
