"""The robot for another program, written from its URDF: MuJoCo's MJCF (``mjcf``, with ``mjcf_actuators`` and
``mjcf_meshes``)."""
