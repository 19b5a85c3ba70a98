"""Every rule of the check stage, in the order of the rule table in the docs (generated from RULES). Each family's
module holds its own rows beside its code: adding a rule to a family touches that module alone, a corpus pair, and its
title here. The titles (what code scanning shows as an alert's title) are kept together, in TITLES, to be read as one
list: short, whole and worded alike; the docs' rule index (titles_markdown) gives each an anchor for help links."""

from __future__ import annotations

from . import collision_rules, consumers, inertia_copies, inertia_geometry, self_collision_rules
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
    **self_collision_rules.RULES,  # G007, G008
    **references.RULES,  # R001-R003, P001
    **sensors.RULES,  # G002-G004
    **spec.RULES,  # K001, V001, V002
    **consumers.RULES,  # C001
}

# rule id -> its title: a whole phrase of at most 60 characters saying what the rule asks, which code scanning shows
# as the alert's title (SARIF's shortDescription) and docs/check.md beside the rule's anchor. (The rows' long texts
# are cut nowhere: a title is written, never taken from the start of one.)
TITLES: dict[str, str] = {
    "U001": "The document is well-formed XML with a <robot> root",
    "U003": "Every namespace prefix used is declared",
    "U002": "Every number URDF reads is finite and complete",
    "G001": "Geometry sizes are positive and mesh scales nonzero",
    "S001": "Exactly one link has no parent",
    "S002": "No chain of joints forms a cycle",
    "S003": "Every joint's parent and child link exists",
    "S004": "No two links share a name",
    "S005": "No two joints share a name",
    "S006": "No link is the child of two joints",
    "S007": "The robot has a name and at least one link",
    "U004": "The document holds no unexpanded xacro",
    "N001": "Link and joint names are plain frame names",
    "J001": "Revolute and prismatic joints have a <limit>",
    "J002": "A joint's lower limit is at most its upper limit",
    "J003": "A joint limit has an effort that is not negative",
    "J004": "A joint limit has a velocity that is not negative",
    "J005": "A continuous joint's <limit> has effort and velocity",
    "J006": "A joint's axis is not the zero vector",
    "J007": "A joint's axis has unit length",
    "J008": "A mimic joint follows another existing joint",
    "J009": "A moving joint gives its damping and friction",
    "J010": "Soft safety limits lie inside the hard limits",
    "J011": "A joint's type is one URDF knows",
    "J012": "Floating joints hang from the root link only",
    "J013": "A joint's lower and upper limits differ",
    "I001": "Every body a joint moves has a positive mass",
    "I002": "Inertia tensors are positive definite",
    "I003": "Principal moments obey the triangle inequality",
    "I004": "Inertia is plausible for the collision geometry's size",
    "I005": "The inertia tensor is no placeholder",
    "I006": "An <inertial> with a mass has an <inertia>",
    "I007": "The base body has a mass when it has geometry",
    "I008": "Inertia is possible within the link's own geometry",
    "I009": "Inertia is not copied onto a part of another size",
    "G005": "No link collides with its detailed visual mesh",
    "G006": "Wheels and feet on the ground have friction",
    "G007": "No two links collide at the home pose",
    "G008": "Pairs of links that never collide are counted",
    "R001": "A <gazebo reference> names an existing link or joint",
    "R002": "A material used by name is defined",
    "R003": "Mesh files resolve and exist",
    "P001": "Every name carries the prefix",
    "G002": "A sensor's type is one Gazebo knows",
    "G003": "Sensor values are ones a simulator can use",
    "G004": "A full-turn lidar scan reads no direction twice",
    "K001": "URDF kinematics equal the spec's DH arm",
    "V001": "A spec's plain numbers are in plausible units",
    "V002": "A spec follows its schema and gen-robot's rules",
    "V003": "Unphysical values of a spec are written as given",
    "C001": "Every independent consumer accepts the URDF",
}


def anchor(rule: str) -> str:
    """The anchor of ``rule`` in docs/check.md (``rule-u001``), which a help link names after ``#``."""
    return f"rule-{rule.lower()}"


def titles_markdown() -> str:
    """The rule index of docs/check.md (between the check-titles markers): each rule's anchor, id and title."""
    lines = ["| rule | title | severity |", "|---|---|---|"]
    for rule, title in TITLES.items():
        said = title.replace("&", "&amp;").replace("<", "&lt;").replace(">", "&gt;")  # (<limit> is no HTML tag)
        lines.append(f'| <a id="{anchor(rule)}"></a>{rule} | {said} | {RULES[rule][1]} |')
    return "\n".join(lines) + "\n"
