"""Facts and helpers shared by the stages and the features, each written once: units, the inertia of solids,
rigid transforms, the kinematic tree walk, joint types, mesh solids, ROS package lookup, how values are written as
text, materials, the shipped data files, simulated sensors, macro banners, safe input files, the GC pause and the
progress line. Nothing here imports a stage or a feature."""
