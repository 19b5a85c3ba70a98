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


_ASM = "ASM Aerospace Specification Metals, asm.matweb.com"

MATERIALS: dict[str, Material] = {
    "steel_s355": Material(7850.0, "structural steel (EN 10025 S235 to S355)", "EN 1993-1-1 (Eurocode 3) 3.2.6"),
    "aluminium_6061": Material(2700.0, "6061-T6", _ASM),
    "aluminium_7075": Material(2810.0, "7075-T6", _ASM),
    "titanium_ti6al4v": Material(4430.0, "Ti-6Al-4V (grade 5), annealed", _ASM),
    "copper": Material(8960.0, "pure copper at 20 C", "CRC Handbook of Chemistry and Physics"),
    "pla": Material(1240.0, "PLA (Ingeo 4043D)", "NatureWorks Ingeo 4043D technical data sheet (ASTM D792)"),
}

# family names and common spellings -> the grade they stand for
ALIASES: dict[str, str] = {
    "steel": "steel_s355",
    "structural_steel": "steel_s355",
    "aluminium": "aluminium_6061",
    "titanium": "titanium_ti6al4v",
    "ti6al4v": "titanium_ti6al4v",
}


def material_key(text: str) -> str:
    """The table's spelling of a material name: lower case, words joined by '_', 'aluminum' as 'aluminium'."""
    key = "_".join(text.strip().lower().replace("-", " ").split())
    return key.replace("aluminum", "aluminium")


def find_material(text: str) -> Material | None:
    key = material_key(text)
    return MATERIALS.get(ALIASES.get(key, key))
