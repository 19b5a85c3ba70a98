"""Makes motor_bracket.stl, the 3D-printed part of examples/robots/rover.yaml: an L-shaped bracket exported in
millimetres, as CAD tools export (the spec scales it by 0.001).

The profile is a 40 x 3 mm foot and a 3 x 27 mm upright above it (201 mm^2), extruded 20 mm: 4,020 mm^3, 4.9848 g of
PLA at 1.24 g/cm^3. Run: python examples/robots/cad/motor_bracket.py
"""

from pathlib import Path

import numpy as np
import trimesh

PROFILE = np.array([[0, 0], [40, 0], [40, 3], [3, 3], [3, 30], [0, 30]], dtype=float)  # mm, counter-clockwise
TRIANGLES = np.array([[0, 1, 2], [0, 2, 3], [0, 3, 4], [0, 4, 5]])
WIDTH = 20.0  # mm

if __name__ == "__main__":
    bracket = trimesh.creation.extrude_triangulation(PROFILE, TRIANGLES, height=WIDTH)
    bracket.apply_translation([-20.0, -15.0, -WIDTH / 2])  # (roughly centred on the file's origin)
    assert bracket.is_watertight and abs(bracket.volume - 201.0 * WIDTH) < 1e-9
    bracket.export(Path(__file__).with_name("motor_bracket.stl"))
