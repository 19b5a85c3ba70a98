"""The write stage: every file xacrokit writes goes through here.

``package_writer`` plans and writes a generated package (create / identical / update / conflict ..., a manifest of
what we wrote, a lock, atomic replacement); ``atomic`` holds the atomic replacement itself and the scratch packages a
spec's meshes are staged in.
"""
