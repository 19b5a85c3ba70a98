"""Reading any robot: a URDF, xacro document, spec or scene to URDF text and where it came from (``robot_source``).
Every command that takes a robot reads it here."""
