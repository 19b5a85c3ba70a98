"""The numbers rule (U002): every number URDF reads is read as urdfdom reads it."""

from __future__ import annotations

import math
import re
from collections.abc import Iterator

from ..shared.units import NUMBER
from ..shared.urdf_view import Shape
from .findings import Finding, rule_table
from .urdf_document import Doc

RULES = rule_table(
    {
        "U002": (
            "numbers-readable",
            "error",
            "every number URDF reads (origins, axes, sizes, masses, tensors, limits, dynamics, colours) is finite, "
            "with as many values as its attribute takes",
        ),
        "G001": (
            "geometry-size",
            "error",
            "box sizes, cylinder radii and lengths and sphere radii are > 0, mesh scales nonzero (negative ones "
            "mirror); MuJoCo rejects a geometry of size 0, which has no volume to collide with",
        ),
    }
)

# element -> attribute -> how many numbers it holds (URDF's numeric attributes; a missing one is another rule's)
_NUMBERS: dict[str, dict[str, int]] = {
    "origin": {"xyz": 3, "rpy": 3},
    "axis": {"xyz": 3},
    "box": {"size": 3},
    "cylinder": {"radius": 1, "length": 1},
    "sphere": {"radius": 1},
    "mesh": {"scale": 3},
    "mass": {"value": 1},
    "inertia": {key: 1 for key in ("ixx", "ixy", "ixz", "iyy", "iyz", "izz")},
    "limit": {key: 1 for key in ("lower", "upper", "effort", "velocity")},
    "dynamics": {"damping": 1, "friction": 1},
    "safety_controller": {key: 1 for key in ("soft_lower_limit", "soft_upper_limit", "k_position", "k_velocity")},
    "mimic": {"multiplier": 1, "offset": 1},
    "color": {"rgba": 4},
}


_URDF_NUMBER = re.compile(NUMBER, re.ASCII)  # what urdfdom reads: ASCII digits only


def _number_problem(text: str, count: int, colour: bool) -> str | None:
    # urdfdom splits a vector on spaces (a tab is no separator) and reads a single value whole (a trailing space fails)
    values = [v for v in text.split(" ") if v] if count > 1 else [text.lstrip(" ")]
    if len(values) != count or not all(_URDF_NUMBER.fullmatch(v) for v in values):
        return f"expected {'a finite number' if count == 1 else f'{count} finite numbers'}"
    numbers = [float(v) for v in values]
    if not all(math.isfinite(v) for v in numbers):
        return f"expected {'a finite number' if count == 1 else f'{count} finite numbers'}"
    if colour and not all(0.0 <= v <= 1.0 for v in numbers):
        return "expected 4 numbers from 0 to 1"
    return None


def number_rules(doc: Doc) -> Iterator[Finding]:
    """U002: numbers that do not read as urdfdom reads them (``rpy="0 0 pi/2"`` left by a macro, ``xyz="0 0"``,
    ``1_0``, a tab between values) and colours outside 0..1. Consumers differ on them: urdfdom prints an error and
    goes on, others refuse the file. Robots repeat their numbers, so each text is judged once."""
    judged: dict[tuple[str, str, str], str | None] = {}
    for element in doc.root.iter(*_NUMBERS):
        counts = _NUMBERS[element.tag]
        for attribute, text in element.items():
            count = counts.get(attribute)
            if count is None:
                continue
            key = (element.tag, attribute, text)
            if key not in judged:
                judged[key] = _number_problem(text, count, element.tag == "color")
            problem = judged[key]
            if problem is None:
                continue
            owner = element
            while owner.getparent() is not None and owner.getparent() is not doc.root:
                owner = owner.getparent()
            if owner.tag in ("link", "joint", "material"):  # (not a <gazebo> or <ros2_control> block's own)
                message = f'<{element.tag} {attribute}="{text}">: {problem}'
                yield doc.finding("U002", owner.tag, owner.get("name", ""), message, element)


_SIZES = {"box": ("size",), "cylinder": ("radius", "length"), "sphere": ("radius",), "mesh": ("scale",)}


def geometry_rules(doc: Doc) -> Iterator[Finding]:
    """G001: a primitive of size 0 (or less), or a mesh scaled by 0, in a link's visual or collision."""
    for link in doc.view.links:
        for kind, geometry in [("visual", g) for g in link.visuals] + [("collision", g) for g in link.collisions]:
            shape = geometry.shape
            for attribute, text, must in _size_problems(shape) if shape is not None else ():
                assert shape is not None  # (for mypy: no problems without a shape)
                yield doc.finding(
                    "G001",
                    "link",
                    link.name,
                    f'{kind} <{shape.kind} {attribute}="{text}">: every value must {must}; a size of 0 has no '
                    "volume, which MuJoCo rejects: give the real size, or leave the geometry out",
                    shape.element,
                )


def _size_problems(shape: Shape) -> Iterator[tuple[str, str, str]]:
    """(attribute, its text, what it must be) for each size of ``shape`` that has no volume."""
    for attribute in _SIZES.get(shape.kind, ()):
        text = shape.get(attribute)
        if text is None:
            continue
        try:
            values = [float(v) for v in text.split()]
        except ValueError:
            continue  # (U002 says it)
        finite = [v for v in values if math.isfinite(v)]
        # a negative mesh scale mirrors the mesh (CAD exports of left/right parts): only 0 collapses it
        mirror = shape.kind == "mesh"
        if any(v == 0 if mirror else not v > 0 for v in finite):
            yield attribute, text, "be nonzero (a negative scale mirrors; 0 flattens the mesh)" if mirror else "be > 0"
