"""Engineering materials a spec may name as a body's ``density``: the density of each, what grade it is, and where the
number comes from. Look-up ignores case, spaces and hyphens, and reads 'aluminum' as 'aluminium'; a family name
('steel', 'aluminium', 'nylon') stands for the grade the table's ALIASES say.

``gen-robot materials`` prints the table; docs/spec.md explains how a density becomes a mass.
"""

from __future__ import annotations

from dataclasses import dataclass


@dataclass(frozen=True)
class Material:
    density: float  # kg/m^3
    grade: str  # the grade or condition the density is for
    source: str  # where the number is published


MATERIALS: dict[str, Material] = {}

ALIASES: dict[str, str] = {}


def material_key(text: str) -> str:
    """The table's spelling of a material name: lower case, words joined by '_', 'aluminum' as 'aluminium'."""
    key = "_".join(text.strip().lower().replace("-", " ").split())
    return key.replace("aluminum", "aluminium")


def find_material(text: str) -> Material | None:
    key = material_key(text)
    return MATERIALS.get(ALIASES.get(key, key))
