"""Showing a robot: the offline page (``page``, ``page_motion``), its watch server (``watch_server``), a picture
without OpenGL (``picture``) and the kinematic tree as Graphviz DOT (``tree_graph``)."""
