"""Hostile inputs, by class: what a fuzzing run of gen-robot found to matter, as hypothesis strategies and lists.

Re-exported by :mod:`xacrokit.testing`. Each class says what gen-robot must give for it (``docs/development.md``,
Bad inputs, has the table and the counts a test run tries):

* :func:`hostile_spec_texts`: a valid spec's text with one value or one piece of structure replaced by something no
  spec may hold (nan, inf, 1e400, a YAML date, sexagesimal 1:30, an Arabic-Indic digit, a 5,000-digit integer, YAML
  tags, an alias, a quantity nested too deeply, a wrong type, a name too long or not a name, a mesh file name with
  control characters, a mimic cycle, tabs, duplicate keys, bytes that are not UTF-8, an alias bomb): exit 2, a
  located error, nothing written.
* :func:`hostile_xacro_documents`: xacro that tries to run code or never ends (sandbox escapes, a macro or file that
  recurses, a binary file, an expression asking for 10 GB): exit 2 with the reason, no code run.
* :func:`hostile_arguments`: command lines (fleet counts and grids beyond any limit, spacings that are no length,
  output paths that are devices or empty, misspelt options): exit 2 with a message.
* :data:`HOSTILE_PATHS` and :func:`make_hostile_path`: inputs that are no document (a device, a FIFO, a link loop, a
  folder): exit 2.
* :data:`HOSTILE_FILE_NAMES` and :func:`hostile_file_names`: spec file names, which generated files quote: every file
  still parses with its own parser.
"""

from __future__ import annotations

import os
from pathlib import Path
from typing import Any

from hypothesis import strategies as st

# -------------------------------------------------------------------------------------------------- file names
HOSTILE_FILE_NAMES = (
    "x.yaml\nimport os; os.system('id')  #",
    "x.yaml\r\nmessage(FATAL_ERROR boom)\n#",
    "a--b--.yaml",
    "quote'\"`$(x)${y}$$z.yaml",
    "nul\x00.yaml",
    "line\u2028sep\x0c\x85.yaml",
    "#[[bracket]].yaml",
    "-->.yaml",
    "\\back\\slash\\",
)


def hostile_file_names() -> st.SearchStrategy[str]:
    """Spec file names that once broke generated files (newlines, --, quotes, $, control characters), or any text."""
    return st.one_of(st.sampled_from(HOSTILE_FILE_NAMES), st.text(min_size=1, max_size=30))


# -------------------------------------------------------------------------------------------------- spec texts
# A valid spec with one marked value: @FIELD@ is replaced by "0.5"-like good values, or by a hostile scalar.
SPEC_TEMPLATE = """\
robot: bot
materials:
  grey: [@rgba@, 0.5, 0.5, 1.0]
links:
  base:
    shape: {box: {size: [@size@, 0.3, 0.1]}}
    mass: @mass@
    material: grey
  arm:
    shape: {mesh: {filename: "package://bot_description/meshes/@mesh@.stl", scale: [@scale@, 1, 1]}}
    mass: 1.0
    inertia: {ixx: 0.01, iyy: 0.01, izz: 0.01}
  follower:
    shape: {sphere: {radius: @radius@}}
    mass: 0.5
joints:
  shoulder:
    type: revolute
    parent: base
    child: arm
    origin: {xyz: [0, 0, @xyz@]}
    axis: [0, @axis@, 1]
    limit: {lower: @lower@, upper: 1.0, effort: @effort@, velocity: @velocity@}
    dynamics: {damping: @damping@}
    safety_controller: {k_velocity: @k_velocity@}
  follow:
    type: revolute
    parent: base
    child: follower
    limit: {lower: -1, upper: 1, effort: 1, velocity: 1}
    mimic: {joint: shoulder, multiplier: @multiplier@}
arms:
  wrist:
    parent: arm
    joints:
      - {name: wrist_joint, link: hand, a: @dh_a@, d: 0, alpha: 0, mass: 0.2,
         limit: {lower: -1, upper: 1, effort: 1, velocity: 1}}
"""
GOOD_VALUES = {"mesh": "part", "axis": "0", "radius": "0.05"}  # every other field: 0.5
NUMBER_FIELDS = (
    "rgba", "size", "mass", "scale", "radius", "xyz", "axis", "lower", "effort", "velocity", "damping",
    "k_velocity", "multiplier", "dh_a",
)  # fmt: skip
# scalars no number field may take, each as YAML text
HOSTILE_NUMBERS = (
    ".nan",
    ".inf",
    "-.inf",
    "1e400",
    "-1e400",
    "2001-12-14",  # a YAML date
    "1:30",  # YAML 1.1 sexagesimal: 90
    '"٣"',  # an Arabic-Indic digit three
    "1" * 5000,  # more digits than Python converts
    "!!timestamp 2001-12-14",
    "!!int 1.5",
    "!!python/object/apply:os.system ['id']",
    "*nowhere",  # an alias of no anchor
    '"' + "(" * 300 + "1" + ")" * 300 + '"',
    '"' + "-" * 3000 + '1"',
    "[1, 2]",
    "{value: 1}",
    "true",
    "~",
    '"1e300 * 1e300"',
    '"${1}"',
    '"$(find x)"',
)


def spec_text(**values: str) -> str:
    """:data:`SPEC_TEMPLATE` with the given fields' values (YAML text), good values for the others."""
    text = SPEC_TEMPLATE
    for field in (*NUMBER_FIELDS, "mesh"):
        text = text.replace(f"@{field}@", values.get(field, GOOD_VALUES.get(field, "0.5")))
    return text


_MIMIC_CYCLE = spec_text().replace("    safety_controller:", "    mimic: {joint: follow}\n    safety_controller:")
# whole-spec faults: (kind, text)
STRUCTURE_CASES = (
    ("tab_indentation", spec_text().replace("    mass: 0.5", "\tmass: 0.5")),
    ("duplicate_key", spec_text().replace("  follower:\n", "  arm:\n    mass: 2.0\n  follower:\n")),
    ("mis_indented_material", spec_text().replace("    material: grey", "  material: grey")),
    ("unclosed_bracket", spec_text().replace("[0, 0, 0.5]", "[0, 0, 0.5")),
    (
        "mimic_cycle",
        spec_text().replace("    safety_controller:", "    mimic: {joint: follow}\n    safety_controller:"),
    ),
    ("mesh_name_control", spec_text(mesh="part\\x01\\uFFFE")),
    ("mesh_name_nul", spec_text(mesh="part\\0")),
    ("long_robot_name", spec_text().replace("robot: bot", "robot: " + "r" * 100_000)),
    (
        "name_not_a_name",
        spec_text().replace("  follower:", "  1st-link:").replace("child: follower", "child: 1st-link"),
    ),
    ("reserved_robot_name", spec_text().replace("robot: bot", "robot: include")),
    (
        "alias_bomb",
        "a: &a [x, x, x, x, x, x, x, x, x]\n"
        + "".join(
            f"{c}: &{c} [*{p}, *{p}, *{p}, *{p}, *{p}, *{p}, *{p}, *{p}, *{p}]\n"
            for p, c in zip("abcdefgh", "bcdefghi", strict=True)
        )
        + spec_text(),
    ),  # fmt: skip
    ("document_stream", spec_text() + "---\n" + spec_text()),
    ("not_a_mapping", "- robot: bot\n"),
    ("empty", ""),
)


@st.composite
def hostile_spec_texts(draw: Any) -> tuple[str, str]:
    """``(yaml_text, kind)``: :data:`SPEC_TEMPLATE` with one hostile number in one field (kind ``FIELD=VALUE``), or
    a fault of the document's structure (kind its name). Each must give exit 2, located, nothing written."""
    if draw(st.integers(0, 3)) == 0:
        kind, text = draw(st.sampled_from(STRUCTURE_CASES))
        return text, kind
    field = draw(st.sampled_from(NUMBER_FIELDS))
    value = draw(st.sampled_from(HOSTILE_NUMBERS))
    return spec_text(**{field: value}), f"{field}={value[:20]}"


# -------------------------------------------------------------------------------------------------- xacro documents
XACRO_HEAD = '<?xml version="1.0"?>\n<robot name="t" xmlns:xacro="http://www.ros.org/wiki/xacro">\n'
XACRO_CASES = (
    ("escape_subclasses", "<link name=\"${python.vars(python.type)['__subclasses__']}\"/>"),
    ("escape_class", '<link name="${[].__class__}"/>'),
    ("escape_type", '<link name="${python.type(1).mro()}"/>'),
    ("escape_frame", '<link name="${(x for x in [0]).gi_frame.f_back.f_globals}"/>'),
    ("escape_walrus", '<link name="${(g := 1)}"/>'),
    ("escape_subscript", "<link name=\"${python['type'] is not None}\"/>"),
    ("eval_open", '<link name="$(eval open)"/>'),  # (xacro's $(...) ends at the first ")")
    ("eval_import", '<link name="$(eval __import__)"/>'),
    ("recursive_macro", '<xacro:macro name="m" params="n"><xacro:m n="${n}"/></xacro:macro><xacro:m n="1"/>'),
    ("self_include", '<xacro:include filename="doc.urdf.xacro"/>'),
    ("keyword_without_attribute", "<xacro:include/>"),
    ("ten_gigabytes", "<link name=\"${'x' * 10**10}\"/>"),
    ("undefined_property", '<link name="${nothing}"/>'),
    ("missing_block", '<xacro:macro name="m" params="*origin"/><xacro:m/>'),
    ("not_xml", "<link name="),
    ("entity", '<!DOCTYPE r [<!ENTITY e SYSTEM "file:///etc/passwd">]><link name="&e;"/>'),
)


@st.composite
def hostile_xacro_documents(draw: Any) -> tuple[str, str]:
    """``(text, kind)``: a xacro document (file name ``doc.urdf.xacro``) that tries to run code, never ends, or is
    broken. Expanding or checking it must give exit 2 with the reason and run nothing."""
    kind, body = draw(st.sampled_from(XACRO_CASES))
    if kind == "entity":
        return '<?xml version="1.0"?>\n' + body.replace("<link", '<robot name="t"><link') + "</robot>", kind
    return XACRO_HEAD + body + "\n</robot>\n", kind


# -------------------------------------------------------------------------------------------------- command lines
# {spec}: a valid robot spec; {out}: a folder that does not exist yet
ARGUMENT_CASES = (
    ("count_huge", ["fleet", "{spec}", "--count", "10000000", "-o", "{out}"]),
    ("count_digits", ["fleet", "{spec}", "--count", "9" * 5000, "-o", "{out}"]),
    ("count_superscript", ["fleet", "{spec}", "--count", "²", "-o", "{out}"]),
    ("count_negative", ["fleet", "{spec}", "--count", "-3", "-o", "{out}"]),
    ("count_nan", ["fleet", "{spec}", "--count", "nan", "-o", "{out}"]),
    ("grid_superscript", ["fleet", "{spec}", "--count", "4", "--grid", "²x²", "-o", "{out}"]),
    ("grid_zero", ["fleet", "{spec}", "--count", "4", "--grid", "0x4", "-o", "{out}"]),
    ("grid_too_small", ["fleet", "{spec}", "--count", "9", "--grid", "2x2", "-o", "{out}"]),
    ("grid_digits", ["fleet", "{spec}", "--count", "4", "--grid", "1x" + "9" * 5000, "-o", "{out}"]),
    ("spacing_deep", ["fleet", "{spec}", "--count", "2", "--spacing", "(" * 3000 + "1" + ")" * 3000, "-o", "{out}"]),
    ("spacing_infinite", ["fleet", "{spec}", "--count", "2", "--spacing", "1e400", "-o", "{out}"]),
    ("spacing_angle", ["fleet", "{spec}", "--count", "2", "--spacing", "90 deg", "-o", "{out}"]),
    ("output_device", ["{spec}", "-o", "/dev/null"]),
    ("output_empty", ["{spec}", "-o", ""]),
    ("misspelt_option", ["{spec}", "--dryrun"]),
    ("unknown_command", ["genrate", "{spec}"]),
    ("check_without_path", ["check"]),
    ("bad_mapping", ["check", "{spec}", "prefix=r1_"]),
    ("missing_spec", ["{out}.yaml"]),
)


@st.composite
def hostile_arguments(draw: Any) -> tuple[list[str], str]:
    """``(argv, kind)``: a gen-robot command line with ``{spec}`` (a valid robot spec) and ``{out}`` (a path that
    does not exist) to fill in. Each must give exit 2 with a message and write nothing."""
    kind, words = draw(st.sampled_from(ARGUMENT_CASES))
    return list(words), kind


# -------------------------------------------------------------------------------------------------- paths
HOSTILE_PATHS = ("device", "fifo", "link_loop", "folder", "dangling_link", "binary", "huge")


def make_hostile_path(kind: str, folder: Path) -> Path:
    """A path of kind ``kind`` (one of :data:`HOSTILE_PATHS`) in ``folder``, named like a spec (``.yaml``)."""
    path = folder / f"{kind}.yaml"
    if kind == "device":
        return Path("/dev/zero")
    if kind == "fifo":
        os.mkfifo(path)
    elif kind == "link_loop":
        other = folder / f"{kind}_other.yaml"
        path.symlink_to(other)
        other.symlink_to(path)
    elif kind == "folder":
        path.mkdir()
    elif kind == "dangling_link":
        path.symlink_to(folder / "nothing_here.yaml")
    elif kind == "binary":
        path.write_bytes(bytes(range(128, 256)) * 64)
    elif kind == "huge":
        with open(path, "wb") as handle:  # a sparse file beyond the spec size limit
            handle.truncate(100 * 1024 * 1024)
    else:
        raise ValueError(f"unknown kind {kind!r}; one of {', '.join(HOSTILE_PATHS)}")
    return path
