"""Every rule of the check stage, in the order of the rule table in the docs (generated from RULES). Each family's
module holds its own rows beside its code: adding a rule to a family touches that module alone, and a corpus pair."""

from __future__ import annotations

from . import collision_rules, consumers, inertia_copies, inertia_geometry
from . import inertia_rules as inertia
from . import joint_rules as joints
from . import number_rules as numbers
from . import reference_rules as references
from . import sensor_rules as sensors
from . import spec_rules as spec
from . import structure_rules as structure
from . import urdf_document as document
from .findings import Row

# rule id -> (name, severity, what it checks). The ids are stable: scripts may filter on them.
RULES: dict[str, Row] = {
    **document.RULES,  # U001
    **numbers.RULES,  # U002
    **structure.RULES,  # S001-S006, N001
    **joints.RULES,  # J001-J012
    **inertia.RULES,  # I001-I007
    **inertia_geometry.RULES,  # I008
    **inertia_copies.RULES,  # I009
    **collision_rules.RULES,  # G005, G006
    **references.RULES,  # R001-R003, P001
    **sensors.RULES,  # G002-G004
    **spec.RULES,  # K001, V001, V002
    **consumers.RULES,  # C001
}
