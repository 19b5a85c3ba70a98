"""``gen-robot import``: a URDF or xacro document read back as a robot spec (``urdf_to_spec``; wheels recognised by
``wheel_match``)."""
