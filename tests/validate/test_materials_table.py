"""The built-in materials table (xacrokit.shared.materials): every density physically plausible, every key in the
table's own spelling, every alias pointing at a grade, every source naming something specific, look-up forgiving case,
spaces and hyphens, and a few values checked against the published numbers they come from."""

from __future__ import annotations

import pytest

from xacrokit.shared.materials import ALIASES, MATERIALS, find_material, material_key

# osmium, the densest element, is 22 590 kg/m^3; nothing solid a robot is built of is lighter than 1 kg/m^3
LIGHTEST, DENSEST = 1.0, 22_590.0


@pytest.mark.parametrize("name", sorted(MATERIALS))
def test_every_density_is_physically_plausible(name):
    assert LIGHTEST <= MATERIALS[name].density <= DENSEST


@pytest.mark.parametrize("name", sorted(MATERIALS))
def test_every_key_is_in_the_tables_own_spelling(name):
    assert material_key(name) == name


@pytest.mark.parametrize("alias", sorted(ALIASES))
def test_every_alias_is_in_the_tables_spelling_and_names_a_grade(alias):
    assert material_key(alias) == alias
    assert ALIASES[alias] in MATERIALS
    assert alias not in MATERIALS  # an alias never shadows a grade of the same name
    assert find_material(alias) is MATERIALS[ALIASES[alias]]


@pytest.mark.parametrize("name", sorted(MATERIALS))
def test_every_grade_and_source_names_something_specific(name):
    material = MATERIALS[name]
    assert material.grade.strip() and material.source.strip()
    vague = {"internet", "web", "wikipedia", "various", "typical", "common", "unknown", "n/a", "tbd"}
    assert material.source.strip().lower() not in vague
    # a source names a document, a standard or a table: some capitalised name or a number, and more than one word
    assert len(material.source.split()) >= 3, material.source
    assert any(ch.isupper() or ch.isdigit() for ch in material.source), material.source


@pytest.mark.parametrize(
    "text, key",
    [
        ("Stainless Steel", "stainless_steel_304"),
        ("stainless-steel", "stainless_steel_304"),
        ("  STAINLESS  ", "stainless_steel_304"),
        ("Stainless Steel 316", "stainless_steel_316"),
        ("stainless-steel-304", "stainless_steel_304"),
        ("Brass", "brass_c36000"),
        ("Nylon", "nylon_pa12"),
        ("PC", "polycarbonate"),
        ("Wood", "birch_yellow"),
        ("Oak Northern Red", "oak_northern_red"),
        ("Aluminum 6082", "aluminium_6082"),
        ("natural-rubber", "natural_rubber"),
    ],
)
def test_look_up_ignores_case_spaces_and_hyphens(text, key):
    assert find_material(text) is MATERIALS[key]


def test_an_unknown_name_is_not_found():
    assert find_material("unobtainium") is None
    assert find_material("stainless_steel_999") is None


# spot checks against the published values (the source of each on its line)
@pytest.mark.parametrize(
    "name, density",
    [
        ("stainless_steel_304", 8000.0),  # ASM material data sheet, AISI Type 304 Stainless Steel: 8 g/cc
        ("stainless_steel_316", 8000.0),  # ASM (asm.matweb.com), AISI Type 316 Stainless Steel, annealed bar: 8 g/cc
        ("brass_c36000", 8500.0),  # Diversified Bronze, C36000 Free-Cutting Brass: specific gravity 8.5
        ("bronze_c93200", 8910.0),  # Dura-Bar, Bearing Bronze C93200 (SAE 660): 8.91 g/cm^3 at 20 C
        ("aluminium_6082", 2700.0),  # Matmatch, BS EN 573-3 Grade 6082 T6: 2.7 g/cm^3 at 23 C
        ("abs", 1040.0),  # BASF Terluran GP-22 data sheet: 1.04 g/cm^3, ASTM D1505
        ("petg", 1230.0),  # Eastman Spectar Clear Copolyester TDS: 1.23 g/cm^3, ASTM D1505
        ("polycarbonate", 1200.0),  # Covestro Makrolon 2405: 1.20 g/cm^3, ISO 1183
        ("nylon_pa12", 1010.0),  # CR-3D PA 12 TDS: 1.01 g/cm^3, DIN EN ISO 1183
        ("pom_copolymer", 1410.0),  # Hostaform C 27021 data sheet: 1410 kg/m^3, ISO 1183
        ("natural_rubber", 950.0),  # MatWeb, Natural Rubber, Vulcanized: 0.950 g/cc uncompounded
    ],
)
def test_spot_values_match_their_sources(name, density):
    assert MATERIALS[name].density == pytest.approx(density, abs=0.5)


@pytest.mark.parametrize(
    "name, specific_gravity_12",
    [
        ("birch_yellow", 0.62),  # Wood Handbook FPL-GTR-190 Table 5-3a, yellow birch, 12% MC
        ("maple_sugar", 0.63),  # Wood Handbook FPL-GTR-190 Table 5-3a, sugar maple, 12% MC
        ("oak_northern_red", 0.63),  # Wood Handbook FPL-GTR-190 Table 5-3a, northern red oak, 12% MC
        ("pine_ponderosa", 0.40),  # Wood Handbook FPL-GTR-190 Table 5-3a, ponderosa pine, 12% MC
    ],
)
def test_wood_densities_follow_the_wood_handbook(name, specific_gravity_12):
    # Wood Handbook ch. 4: density at moisture content M = 1000 kg/m^3 x G_M x (1 + M/100)
    assert MATERIALS[name].density == pytest.approx(1000.0 * specific_gravity_12 * 1.12, abs=0.5)
    assert f"{specific_gravity_12:.2f}" in MATERIALS[name].source and "Wood Handbook" in MATERIALS[name].source


def test_the_table_keeps_its_original_grades():
    # the six grades a spec could name before the table grew still give the same numbers
    assert MATERIALS["steel_s355"].density == 7850.0  # EN 1993-1-1 3.2.6
    assert MATERIALS["aluminium_6061"].density == 2700.0  # ASM, 6061-T6: 2.70 g/cc
    assert MATERIALS["aluminium_7075"].density == 2810.0  # ASM, 7075-T6: 2.81 g/cc
    assert MATERIALS["titanium_ti6al4v"].density == 4430.0  # ASM, Ti-6Al-4V: 4.43 g/cc
    assert MATERIALS["copper"].density == 8960.0  # CRC Handbook
    assert MATERIALS["pla"].density == 1240.0  # NatureWorks Ingeo 4043D TDS
