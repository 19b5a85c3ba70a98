"""The expand stage: a xacro document to URDF text with the real xacro, safely.

``xacro_expand`` runs xacro (``$(find)`` resolved without ROS, undeclared arguments refused), ``expression_guard``
refuses the expressions of an untrusted document that could reach Python's internals, and ``bounded_child`` runs
such work in a forked child with time and memory bounds (check's consumers use it too).
"""
