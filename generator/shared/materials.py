"""Engineering materials a spec may name as a body's ``density``: the density of each, what grade it is, and where the
number comes from. Look-up ignores case, spaces and hyphens, and reads 'aluminum' as 'aluminium'; a family name
('steel', 'stainless', 'aluminium', 'brass', 'nylon', 'wood') stands for the grade the table's ALIASES say.

Metals and plastics are a named grade's published value (a handbook, a standard, or the maker's data sheet with its
test method). Woods are clear, straight-grained wood at 12 % moisture content: the USDA Wood Handbook gives a species'
specific gravity G at 12 % (oven-dry mass over volume at 12 %), and its chapter 4 makes that a density,
1000 kg/m^3 x G x (1 + 0.12). A real part may differ (knots, plywood glue, a print's infill, a tyre's fillers).

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


def _wood(specific_gravity_12: float) -> float:
    """Density (kg/m^3) at 12 % moisture content of a wood whose specific gravity at 12 % is given (Wood Handbook)."""
    return float(round(1000.0 * specific_gravity_12 * 1.12))


def _wood_source(specific_gravity_12: float) -> str:
    return (
        f"USDA Wood Handbook (FPL-GTR-190) Table 5-3a: specific gravity {specific_gravity_12:.2f} at 12% MC; "
        "density = 1000 kg/m^3 x G x 1.12 (ch. 4)"
    )


MATERIALS: dict[str, Material] = {
    "steel_s355": Material(7850.0, "structural steel (EN 10025 S235 to S355)", "EN 1993-1-1 (Eurocode 3) 3.2.6"),
    "aluminium_6061": Material(2700.0, "6061-T6", _ASM),
    "aluminium_7075": Material(2810.0, "7075-T6", _ASM),
    "titanium_ti6al4v": Material(4430.0, "Ti-6Al-4V (grade 5), annealed", _ASM),
    "copper": Material(8960.0, "pure copper at 20 C", "CRC Handbook of Chemistry and Physics"),
    "pla": Material(1240.0, "PLA (Ingeo 4043D)", "NatureWorks Ingeo 4043D technical data sheet (ASTM D792)"),
    # metals
    "stainless_steel_304": Material(
        8000.0, "AISI Type 304 (UNS S30400)", "ASM material data sheet 'AISI Type 304 Stainless Steel' (8 g/cc)"
    ),
    "stainless_steel_316": Material(
        8000.0,
        "AISI Type 316 (UNS S31600), annealed bar",
        "ASM material data sheet 'AISI Type 316 Stainless Steel, annealed bar', asm.matweb.com (8 g/cc)",
    ),
    "aluminium_6082": Material(
        2700.0, "6082-T6 (EN AW-6082)", "Matmatch data sheet 'BS EN 573-3 Grade 6082 T6' (2.7 g/cm^3 at 23 C)"
    ),
    "brass_c36000": Material(
        8500.0,
        "free-cutting brass UNS C36000 (CuZn36Pb3)",
        "Diversified Bronze alloy data 'C36000 Free-Cutting Brass' (specific gravity 8.5, 0.307 lb/in^3)",
    ),
    "bronze_c93200": Material(
        8910.0,
        "bearing bronze UNS C93200 (SAE 660)",
        "Dura-Bar data sheet 'Bearing Bronze C93200 (SAE 660)' (8.91 g/cm^3 at 20 C, 0.322 lb/in^3)",
    ),
    # plastics
    "abs": Material(1040.0, "ABS (Terluran GP-22)", "BASF Terluran GP-22 data sheet (IDES): 1.04 g/cm^3, ASTM D1505"),
    "petg": Material(
        1230.0,
        "PETG (Eastman Spectar Clear copolyester)",
        "Eastman technical data sheet 'Eastman Spectar Clear Copolyester': 1.23 g/cm^3, ASTM D1505",
    ),
    "polycarbonate": Material(
        1200.0, "PC (Covestro Makrolon 2405)", "Covestro Makrolon 2405 data sheet: 1.20 g/cm^3 at 23 C, ISO 1183"
    ),
    "nylon_pa12": Material(
        1010.0, "PA12 (CR-3D PA 12 filament)", "CR-3D technical data sheet 'PA 12' (2022): 1.01 g/cm^3, DIN EN ISO 1183"
    ),
    "pom_copolymer": Material(
        1410.0,
        "acetal copolymer POM-C (Hostaform C 27021)",
        "Ticona/Celanese data sheet 'HOSTAFORM C 27021 | POM | Unfilled': 1410 kg/m^3, ISO 1183",
    ),
    "natural_rubber": Material(
        950.0,
        "natural rubber (NR), vulcanized, uncompounded (no filler)",
        "MatWeb 'Natural Rubber, Vulcanized (NR, IR, Polyisoprene)': 0.950 g/cc, uncompounded",
    ),
    # woods, clear wood at 12 % moisture content
    "birch_yellow": Material(_wood(0.62), "yellow birch (Betula alleghaniensis), 12% MC", _wood_source(0.62)),
    "maple_sugar": Material(_wood(0.63), "sugar maple (Acer saccharum), 12% MC", _wood_source(0.63)),
    "oak_northern_red": Material(_wood(0.63), "northern red oak (Quercus rubra), 12% MC", _wood_source(0.63)),
    "pine_ponderosa": Material(_wood(0.40), "ponderosa pine (Pinus ponderosa), 12% MC", _wood_source(0.40)),
}

# family names and common spellings -> the grade they stand for
ALIASES: dict[str, str] = {
    "steel": "steel_s355",
    "structural_steel": "steel_s355",
    "stainless_steel": "stainless_steel_304",
    "stainless": "stainless_steel_304",
    "aluminium": "aluminium_6061",
    "titanium": "titanium_ti6al4v",
    "ti6al4v": "titanium_ti6al4v",
    "brass": "brass_c36000",
    "bronze": "bronze_c93200",
    "nylon": "nylon_pa12",
    "pa12": "nylon_pa12",
    "pc": "polycarbonate",
    "pom": "pom_copolymer",
    "acetal": "pom_copolymer",
    "rubber": "natural_rubber",
    "wood": "birch_yellow",
    "birch": "birch_yellow",
    "maple": "maple_sugar",
    "oak": "oak_northern_red",
    "pine": "pine_ponderosa",
}


def material_key(text: str) -> str:
    """The table's spelling of a material name: lower case, words joined by '_', 'aluminum' as 'aluminium'."""
    key = "_".join(text.strip().lower().replace("-", " ").split())
    return key.replace("aluminum", "aluminium")


def find_material(text: str) -> Material | None:
    key = material_key(text)
    return MATERIALS.get(ALIASES.get(key, key))
