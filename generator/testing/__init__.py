"""Hypothesis strategies for robot specs, for xacrokit's own tests and for yours.

    from hypothesis import given
    from xacrokit.testing import valid_specs, invalid_specs

    @given(valid_specs())
    def test_my_tool_accepts_any_robot(spec): ...      # spec: a dict, ready for yaml.safe_dump

``valid_specs()`` draws specs that exercise every feature: links of every shape (and bare frames, meshes with
explicit tensors), every joint type, DH arms in both conventions with revolute/prismatic/continuous/fixed rows (some
without a base link, some with a named tool joint), wheels, fixed frames, materials, unit strings (``"150 mm"``,
``"90 deg"``), ros2_control and Gazebo settings, and mesh filenames holding ``${`` / ``$(`` that must come out
verbatim. ``invalid_specs()`` draws ``(spec, fault)``: a valid spec with exactly one fault of the kind named by
``fault``. ``mirrored_specs()`` draws a spec whose ``left_`` limb is mirrored to ``right_`` through a random plane
(tests/validate/test_mirror.py checks every copy is the mirror image).

Requires hypothesis (``pip install '.[test]'`` in a clone of xacrokit).
"""

from __future__ import annotations

import copy
import math
from typing import Any

from hypothesis import strategies as st
from lxml import etree

from ..model import AXIAL, JOINT_TYPES, LIMITED, MOVING
from ..shared.transforms import rpy_matrix

SHAPES = ("box", "cylinder", "sphere", "capsule", "tube", "mesh", "parts", "none")
SOLIDS = ("box", "cylinder", "sphere", "capsule", "tube")  # the shapes whose inertia has a closed form
FAULTS = (
    "negative_mass",
    "swapped_limits",
    "dangling_parent",
    "cycle",
    "duplicate_name",
    "zero_axis",
    "not_positive_definite",
    "triangle_violation",
    "missing_gazebo_reference",
    "wrong_type",
    "bad_unit",
    "injected_name",
    "unknown_material",
    "not_finite",
    "extreme_axis",
    "deep_quantity",
    "tube_inside_out",
    "composite_with_mass",
)

# mesh file names the strategies use (package://some_pkg/meshes/NAME.stl): xacro must write them verbatim
MESH_NAMES = ("part", "${not_evaluated}", "$(find nothing)", "a&b<c>", "$${x}", "x$$y")  # xacro refused $$ once
_size = st.floats(min_value=0.01, max_value=1.0, allow_nan=False)
_mass = st.floats(min_value=0.01, max_value=20.0, allow_nan=False)
_coord = st.floats(min_value=-1.0, max_value=1.0, allow_nan=False)
_angle = st.one_of(st.sampled_from([k * math.pi / 2 for k in range(-4, 5)]), st.floats(-math.pi, math.pi))


@st.composite
def _length(draw, value=_size) -> Any:
    """A length as a number, or as a string in mm or cm (the spec's unit syntax)."""
    number = draw(value)
    form = draw(st.sampled_from(["number", "number", "mm", "cm"]))
    if form == "mm":
        return f"{number * 1000!r} mm"
    return f"{number * 100!r} cm" if form == "cm" else number


@st.composite
def _angle_value(draw) -> Any:
    angle = draw(_angle)
    form = draw(st.sampled_from(["number", "number", "deg"]))
    return f"{math.degrees(angle)!r} deg" if form == "deg" else angle


@st.composite
def _origin(draw) -> dict[str, Any]:
    origin: dict[str, Any] = {}
    if draw(st.booleans()):
        origin["xyz"] = [draw(_length(_coord)) for _ in range(3)]
    way = draw(st.sampled_from(["none", "rpy", "rpy", "quat", "axis_angle"]))  # (one way at a time)
    if way == "rpy":
        origin["rpy"] = [draw(_angle_value()) for _ in range(3)]
    elif way == "quat":  # a unit quaternion [x, y, z, w], as a calibration gives it
        values = draw(st.lists(st.floats(-1, 1, allow_nan=False), min_size=4, max_size=4).filter(_long_enough))
        norm = math.sqrt(sum(v * v for v in values))
        origin["quat"] = [v / norm for v in values]
    elif way == "axis_angle":
        axis = draw(st.lists(st.floats(-1, 1, allow_nan=False), min_size=3, max_size=3).filter(_long_enough))
        origin["axis_angle"] = {"axis": axis, "angle": draw(_angle_value())}
    return origin


def _long_enough(values: list[float]) -> bool:
    """A direction that normalising keeps (well away from the zero vector)."""
    return math.sqrt(sum(v * v for v in values)) > 0.1


@st.composite
def _shape(draw, kind: str) -> dict[str, Any]:
    if kind == "box":
        return {"box": {"size": [draw(_length()) for _ in range(3)]}}
    if kind == "cylinder":
        return {"cylinder": {"radius": draw(_length()), "length": draw(_length())}}
    if kind == "sphere":
        return {"sphere": {"radius": draw(_length())}}
    if kind == "capsule":
        return {"capsule": {"radius": draw(_length()), "length": draw(_length())}}
    if kind == "tube":
        inner = draw(_size)
        outer = inner * draw(st.floats(1.05, 4.0))
        return {"tube": {"inner_radius": inner, "outer_radius": outer, "length": draw(_length())}}
    weird = draw(st.sampled_from(MESH_NAMES))
    return {"mesh": {"filename": f"package://some_pkg/meshes/{weird}.stl", "scale": [1.0, 1.0, 1.0]}}


@st.composite
def _physical_tensor(draw) -> dict[str, float]:
    a, b = draw(_mass), draw(_mass)
    c = abs(a - b) + (a + b - abs(a - b)) * draw(st.floats(0.05, 0.95))
    return {"ixx": a * 0.01, "iyy": b * 0.01, "izz": c * 0.01}


@st.composite
def _turned_tensor(draw) -> dict[str, Any]:
    """A physical tensor R D R^T (D a physical diagonal, R from rpy angles) with its products, maybe in a turned and
    shifted frame (``origin``)."""
    principal = draw(_physical_tensor())
    turn = rpy_matrix(*(draw(st.floats(-math.pi, math.pi)) for _ in range(3))).tolist()
    moments = (principal["ixx"], principal["iyy"], principal["izz"])
    element = [[sum(turn[i][k] * moments[k] * turn[j][k] for k in range(3)) for j in range(3)] for i in range(3)]
    tensor: dict[str, Any] = {"ixx": element[0][0], "iyy": element[1][1], "izz": element[2][2]}
    tensor.update(ixy=element[0][1], ixz=element[0][2], iyz=element[1][2])
    if draw(st.booleans()):
        tensor["origin"] = draw(_origin())
    return tensor


# densities as a spec may give them: kg/m^3, a string with a unit, or a material of the table
_density = st.one_of(
    st.floats(100.0, 20_000.0),
    st.floats(0.1, 20.0).map(lambda d: f"{d!r} g/cm3"),
    st.sampled_from(["steel", "aluminium_6061", "pla", "Stainless Steel", "oak", "abs", "aluminum"]),
)


@st.composite
def _mass_or_density(draw) -> dict[str, Any]:
    """A body's mass (kg or grams) or its density."""
    if draw(st.booleans()):
        return {"density": draw(_density)}
    return {"mass": draw(st.one_of(_mass, _mass.map(lambda m: f"{m * 1000!r} g")))}


@st.composite
def _parts(draw, materials: list[str]) -> list[dict[str, Any]]:
    """The parts of a composite link: closed-form solids, each placed, with a mass or a density."""
    parts = []
    for _ in range(draw(st.integers(1, 3))):
        part: dict[str, Any] = {"shape": draw(_shape(draw(st.sampled_from(SOLIDS)))), "origin": draw(_origin())}
        part.update(draw(_mass_or_density()))
        if materials and draw(st.booleans()):
            part["material"] = draw(st.sampled_from(materials))
        if draw(st.integers(0, 3)) == 0:
            part["collision"] = "none"
        parts.append(part)
    return parts


@st.composite
def _link(draw, materials: list[str]) -> dict[str, Any]:
    kind = draw(st.sampled_from(SHAPES))
    link: dict[str, Any] = {}
    if kind == "none":
        if draw(st.booleans()):
            link.update(mass=draw(_mass), inertia=draw(_physical_tensor()))
        return link
    if kind == "parts":
        link["parts"] = draw(_parts(materials))
        if materials and draw(st.booleans()):
            link["material"] = draw(st.sampled_from(materials))
        return link
    link["shape"] = draw(_shape(kind))
    if draw(st.booleans()):
        link["origin"] = draw(_origin())
    if materials and draw(st.booleans()):
        link["material"] = draw(st.sampled_from(materials))
    if kind == "mesh":  # a body with a shape has a mass (gen-robot check requires it); a mesh, a tensor too
        link.update(mass=draw(_mass), inertia=draw(_physical_tensor()))  # (these name no real file to read)
    else:
        link.update(draw(_mass_or_density()))
    collision = draw(st.sampled_from(["default", "same", "none", "other", "list"]))
    if collision in ("other", "list"):
        shapes = [
            {"shape": draw(_shape(draw(st.sampled_from(["box", "cylinder", "sphere"])))), "origin": draw(_origin())}
            for _ in range(1 if collision == "other" else draw(st.integers(1, 3)))
        ]
        link["collision"] = shapes[0] if collision == "other" else shapes
    elif collision != "default":
        link["collision"] = collision
    if kind != "mesh" and draw(st.integers(0, 3)) == 0:  # (more pieces, drawn only)
        link["visuals"] = []
        for _ in range(draw(st.integers(1, 2))):
            more: dict[str, Any] = {"shape": draw(_shape(draw(st.sampled_from(["box", "cylinder", "sphere"]))))}
            more["origin"] = draw(_origin())
            if materials and draw(st.booleans()):
                more["material"] = draw(st.sampled_from(materials))
            link["visuals"].append(more)
    return link


def _limit(draw, kind: str) -> dict[str, Any]:
    limit: dict[str, Any] = {"effort": draw(_mass), "velocity": draw(_mass)}
    if kind in LIMITED:
        low = draw(st.floats(-3.0, 0.0))
        limit.update(lower=low, upper=low + draw(st.floats(0.0, 3.0)))
    return limit


@st.composite
def _joint(draw, parent: str, child: str) -> dict[str, Any]:
    kind = draw(st.sampled_from(JOINT_TYPES))
    joint: dict[str, Any] = {"type": kind, "parent": parent, "child": child, "origin": draw(_origin())}
    if kind in AXIAL:
        axis = [draw(st.sampled_from([0.0, 1.0, -1.0, 0.5])) for _ in range(3)]
        joint["axis"] = axis if any(axis) else [0.0, 0.0, 1.0]
    if kind in MOVING:
        joint["limit"] = _limit(draw, kind)
    if kind in MOVING and draw(st.booleans()):
        joint["dynamics"] = {"damping": draw(st.floats(0.0, 1.0)), "friction": draw(st.floats(0.0, 1.0))}
    return joint


@st.composite
def _arm(draw, prefix: str, parent: str, materials: list[str]) -> dict[str, Any]:
    rows = []
    for index in range(draw(st.integers(1, 4))):
        kind = draw(st.sampled_from(["revolute", "revolute", "prismatic", "continuous", "fixed"]))
        row: dict[str, Any] = {
            "name": f"{prefix}_joint_{index}",
            "link": f"{prefix}_link_{index}",
            "a": draw(_length(_coord)),
            "d": draw(_length(_coord)),
            "alpha": draw(_angle_value()),
            "type": kind,
        }
        if draw(st.booleans()):
            row["theta"] = draw(_angle_value())
        if kind != "fixed":
            row["limit"] = _limit(draw, kind)
        if kind != "fixed" or draw(st.booleans()):  # a moved link has a mass
            row["mass"] = draw(_mass)
            if materials and draw(st.booleans()):
                row["material"] = draw(st.sampled_from(materials))
            if draw(st.booleans()):  # (a published tensor, placed in DH frame i)
                row["inertia"] = {"origin": draw(_origin()), **draw(_turned_tensor())}
        rows.append(row)
    arm: dict[str, Any] = {
        "parent": parent,
        "convention": draw(st.sampled_from(["standard", "modified"])),
        "joints": rows,
    }
    if draw(st.integers(0, 3)) == 0:  # (its first joint on parent, as UR's description hangs it)
        arm["base"] = False
    else:
        arm["origin"] = draw(_origin())
    if draw(st.booleans()):
        arm["tool"] = {"name": f"{prefix}_tool", "origin": draw(_origin())}
    else:
        arm["tool"] = {"name": f"{prefix}_tool0"}
    if draw(st.booleans()):  # its joint named, as UR names it (wrist_3-flange)
        arm["tool"]["joint"] = f"{prefix}_link-{prefix}_tool"
    return arm


@st.composite
def valid_specs(draw, max_links: int = 5) -> dict[str, Any]:
    """A random valid spec (a dict): every name unique, one tree, physical masses and tensors."""
    materials = [f"color_{i}" for i in range(draw(st.integers(0, 3)))]
    spec: dict[str, Any] = {"robot": draw(st.sampled_from(["bot", "robot_1", "_r", "Arm7"]))}
    if materials:
        spec["materials"] = {name: [draw(st.floats(0, 1)) for _ in range(3)] + [1.0] for name in materials}
    count = draw(st.integers(1, max_links))
    # (link and joint names as real robots write them too: parts joined by . / or -)
    spec["links"] = {
        draw(st.sampled_from([f"link_{i}", f"link-{i}", f"arm/link.{i}"])): draw(_link(materials)) for i in range(count)
    }
    links = list(spec["links"])
    spec["joints"] = {
        draw(st.sampled_from([f"joint_{i}", f"base-joint.{i}"])): draw(
            _joint(links[draw(st.integers(0, i - 1))], links[i])
        )
        for i in range(1, count)
    }
    for joint in spec["joints"].values():  # a floating joint is a floating base: it hangs from the root
        if joint["type"] == "floating":
            joint["parent"] = links[0]
    for joint in spec["joints"].values():  # a moved link has a mass (and, without a shape, an inertia)
        child = spec["links"][joint["child"]]
        if joint["type"] != "fixed" and not {"mass", "density", "parts"} & set(child):
            child.update(mass=draw(_mass), inertia=draw(_physical_tensor()))
    moving = [n for n, j in spec["joints"].items() if j["type"] in MOVING]
    if len(moving) >= 2 and draw(st.booleans()):
        follower, leader = moving[-1], moving[0]
        if spec["joints"][follower]["type"] == spec["joints"][leader]["type"]:
            spec["joints"][follower]["mimic"] = {"joint": leader, "multiplier": draw(st.floats(-2, 2)), "offset": 0.0}
    _add_attachments(draw, spec, links, materials)
    return spec


def _add_attachments(draw: Any, spec: dict[str, Any], links: list[str], materials: list[str]) -> None:
    """Arms, wheels, frames, ros2_control and Gazebo settings hung on ``links`` of ``spec`` (each maybe)."""
    all_links = list(links)
    arms = {}
    for k in range(draw(st.integers(0, 2))):
        arms[f"arm_{k}"] = draw(_arm(f"arm_{k}", draw(st.sampled_from(all_links)), materials))
        all_links += [row["link"] for row in arms[f"arm_{k}"]["joints"]]
    if arms:
        spec["arms"] = arms
    wheels = _wheels(draw, links)
    if wheels:
        spec["wheels"] = wheels
    frames = _frames(draw, links)
    if frames:
        spec["frames"] = frames
    if draw(st.booleans()):
        spec["ros2_control"] = {}
    if draw(st.booleans()):
        spec["gazebo"] = {"links": {draw(st.sampled_from(links)): {"mu1": draw(st.floats(0, 2)), "mu2": 0.5}}}


def _wheels(draw: Any, links: list[str]) -> dict[str, Any]:
    wheels = {}
    for k in range(draw(st.integers(0, 2))):
        wheels[f"wheel_{k}"] = {
            "parent": draw(st.sampled_from(links)),
            "origin": draw(_origin()),
            "radius": draw(_length()),
            "width": draw(_length()),
            "axis": draw(st.sampled_from(["x", "y", "z"])),
            **draw(_mass_or_density()),
        }
        if draw(st.booleans()):  # its joint named, as real robots name them
            wheels[f"wheel_{k}"]["joint"] = f"drive_{k}"
    return wheels


def _frames(draw: Any, links: list[str]) -> dict[str, Any]:
    frames = {}
    for k in range(draw(st.integers(0, 2))):
        frame: dict[str, Any] = {"parent": draw(st.sampled_from(links)), "origin": draw(_origin())}
        if draw(st.booleans()):
            frame.update(shape=draw(_shape(draw(st.sampled_from(SOLIDS)))), **draw(_mass_or_density()))
        if draw(st.booleans()):
            frame["joint"] = draw(st.sampled_from([f"mount_{k}", f"base-mount_{k}"]))
        frames[f"frame_{k}"] = frame
    return frames


@st.composite
def mirrored_specs(draw, max_links: int = 4) -> dict[str, Any]:
    """A random valid spec with a ``mirror`` entry: a pelvis, a torso fixed on it somewhere, and a limb of 1 to
    ``max_links`` links named ``left_...`` (any shapes, origins in every form, revolute, continuous, prismatic and
    fixed joints with any axes, maybe a branch, a frame and a mimic joint) hung from the torso and mirrored to
    ``right_...`` through a random plane."""
    spec: dict[str, Any] = {"robot": "mirrored", "links": {"pelvis": {}, "torso": draw(_link([]))}}
    spec["joints"] = {"torso_joint": {"type": "fixed", "parent": "pelvis", "child": "torso", "origin": draw(_origin())}}
    above = ["torso"]
    for index in range(draw(st.integers(1, max_links))):
        name, parent = f"left_link_{index}", draw(st.sampled_from(above))
        spec["links"][name] = draw(_link([]))
        joint = draw(_joint(parent, name).filter(lambda j: j["type"] not in ("floating", "planar")))
        spec["joints"][f"left_joint_{index}"] = joint
        above = above[1:] + [name] if index == 0 else above + [name]  # (the limb starts at the torso, then branches)
    for joint in spec["joints"].values():  # a moved link has a mass (and, without a shape, an inertia)
        child = spec["links"][joint["child"]]
        if joint["type"] != "fixed" and not {"mass", "density", "parts"} & set(child):
            child.update(mass=draw(_mass), inertia=draw(_physical_tensor()))
        if "inertia" in child:  # (a tensor with products, in a frame of its own: the mirror turns both)
            child["inertia"] = draw(_turned_tensor())
        elif "shape" in child and draw(st.booleans()):
            child["com"] = draw(_origin())
    moving = [n for n, j in spec["joints"].items() if j["type"] in MOVING]
    if len(moving) >= 2 and spec["joints"][moving[-1]]["type"] == spec["joints"][moving[0]]["type"]:
        spec["joints"][moving[-1]]["mimic"] = {"joint": moving[0], "multiplier": draw(st.floats(-2, 2)), "offset": 0.1}
    if draw(st.booleans()):
        frame = {"parent": draw(st.sampled_from(above)), "origin": draw(_origin())}
        spec["frames"] = {"left_frame": frame | {"shape": draw(_shape("box")), "mass": draw(_mass)}}
    plane = draw(st.sampled_from(["xz", "yz", "xy"]))
    spec["mirror"] = [{"joint": "left_joint_0", "rename": ["left_", "right_"], "plane": plane}]
    return spec


@st.composite
def invalid_specs(draw, faults: tuple[str, ...] = FAULTS) -> tuple[dict[str, Any], str]:
    """``(spec, fault)``: a valid spec with one fault of kind ``fault`` (one of :data:`FAULTS`)."""
    spec = copy.deepcopy(draw(valid_specs()))
    fault = draw(st.sampled_from(faults))
    links = spec["links"]
    name = draw(st.sampled_from(sorted(links)))
    _FAULT_MAKERS[fault](draw, spec, links, name)
    return spec, fault


def _fault_negative_mass(draw: Any, spec: dict[str, Any], links: dict[str, Any], name: str) -> None:
    links[name] = {"shape": {"sphere": {"radius": 0.1}}, "mass": -draw(_mass)}


def _fault_swapped_limits(draw: Any, spec: dict[str, Any], links: dict[str, Any], name: str) -> None:
    spec.setdefault("joints", {})["bad_joint"] = {
        "type": "revolute",
        "parent": name,
        "child": "bad_link",
        "limit": {"lower": 1.0, "upper": -1.0, "effort": 1, "velocity": 1},
    }
    links["bad_link"] = {}


def _fault_dangling_parent(draw: Any, spec: dict[str, Any], links: dict[str, Any], name: str) -> None:
    spec.setdefault("frames", {})["bad_frame"] = {"parent": "no_such_link"}


def _fault_cycle(draw: Any, spec: dict[str, Any], links: dict[str, Any], name: str) -> None:
    links["loop_a"], links["loop_b"] = {}, {}
    spec.setdefault("joints", {})["loop_ab"] = {"type": "fixed", "parent": "loop_a", "child": "loop_b"}
    spec["joints"]["loop_ba"] = {"type": "fixed", "parent": "loop_b", "child": "loop_a"}


def _fault_duplicate_name(draw: Any, spec: dict[str, Any], links: dict[str, Any], name: str) -> None:
    spec.setdefault("wheels", {})[name] = {"parent": name, "radius": 0.1, "width": 0.05, "mass": 1.0}


def _fault_zero_axis(draw: Any, spec: dict[str, Any], links: dict[str, Any], name: str) -> None:
    spec.setdefault("joints", {})["bad_joint"] = {
        "type": "continuous",
        "parent": name,
        "child": "bad_link",
        "axis": [0, 0, 0],
    }
    links["bad_link"] = {}


def _fault_not_positive_definite(draw: Any, spec: dict[str, Any], links: dict[str, Any], name: str) -> None:
    links[name] = {"mass": 1.0, "inertia": {"ixx": 1.0, "iyy": 1.0, "izz": 1.0, "ixy": 1.5}}


def _fault_triangle_violation(draw: Any, spec: dict[str, Any], links: dict[str, Any], name: str) -> None:
    links[name] = {"mass": 1.0, "inertia": {"ixx": 1.0, "iyy": 1.0, "izz": 2.5}}


def _fault_missing_gazebo_reference(draw: Any, spec: dict[str, Any], links: dict[str, Any], name: str) -> None:
    spec["gazebo"] = {"links": {"no_such_link": {"mu1": 1.0}}}


def _fault_wrong_type(draw: Any, spec: dict[str, Any], links: dict[str, Any], name: str) -> None:
    links[name] = {"shape": {"box": {"size": [1, 1, 1]}}, "mass": draw(st.sampled_from([[1.0], {"kg": 1}, True]))}


def _fault_bad_unit(draw: Any, spec: dict[str, Any], links: dict[str, Any], name: str) -> None:
    links[name] = {"shape": {"sphere": {"radius": draw(st.sampled_from(["3 parsecs", "90 deg", "1 kg", "x"]))}}}


def _fault_injected_name(draw: Any, spec: dict[str, Any], links: dict[str, Any], name: str) -> None:
    bad = draw(st.sampled_from(["a${x}", "b$(find y)", "c<d", "e&f", "g h", "1st"]))
    links[bad] = links.pop(name)
    for joint in spec.get("joints", {}).values():
        joint["parent"] = bad if joint["parent"] == name else joint["parent"]
        joint["child"] = bad if joint["child"] == name else joint["child"]


def _fault_unknown_material(draw: Any, spec: dict[str, Any], links: dict[str, Any], name: str) -> None:
    links[name] = {"shape": {"sphere": {"radius": 0.1}}, "mass": 1.0, "material": "no_such_colour"}


def _fault_not_finite(draw: Any, spec: dict[str, Any], links: dict[str, Any], name: str) -> None:
    # (.nan, .inf in YAML; a quantity beyond any double)
    value = draw(st.sampled_from([math.nan, math.inf, -math.inf, "1e400 kg", "1e300 * 1e300"]))
    links[name] = {"shape": {"sphere": {"radius": 0.1}}, "mass": value}


def _fault_extreme_axis(draw: Any, spec: dict[str, Any], links: dict[str, Any], name: str) -> None:
    # normalising it would divide by zero or overflow
    spec.setdefault("joints", {})["bad_joint"] = {
        "type": "continuous",
        "parent": name,
        "child": "bad_link",
        "axis": draw(st.sampled_from([[0, 1e-320, 0], [1e308, 1e308, 0], [0, 0, 1e-12]])),
        "limit": {"effort": 1, "velocity": 1},
    }
    links["bad_link"] = {"mass": 1.0, "inertia": {"ixx": 1.0, "iyy": 1.0, "izz": 1.0}}


def _fault_deep_quantity(draw: Any, spec: dict[str, Any], links: dict[str, Any], name: str) -> None:
    # thousands of parentheses once exhausted the parser's recursion
    depth = draw(st.integers(150, 3000))
    links[name] = {"shape": {"sphere": {"radius": "(" * depth + "0.1" + ")" * depth}}, "mass": 1.0}


def _fault_tube_inside_out(draw: Any, spec: dict[str, Any], links: dict[str, Any], name: str) -> None:
    # its bore as wide as the tube
    radius = draw(_size)
    tube = {"inner_radius": radius * draw(st.floats(1.0, 2.0)), "outer_radius": radius, "length": 0.1}
    links[name] = {"shape": {"tube": tube}, "mass": 1.0}


def _fault_composite_with_mass(draw: Any, spec: dict[str, Any], links: dict[str, Any], name: str) -> None:
    # a composite's mass is its parts'
    links[name] = {"parts": [{"shape": {"sphere": {"radius": 0.1}}, "mass": 1.0}], "mass": 1.0}


_FAULT_MAKERS: dict[str, Any] = {  # (each puts its fault into the spec)
    "negative_mass": _fault_negative_mass,
    "swapped_limits": _fault_swapped_limits,
    "dangling_parent": _fault_dangling_parent,
    "cycle": _fault_cycle,
    "duplicate_name": _fault_duplicate_name,
    "zero_axis": _fault_zero_axis,
    "not_positive_definite": _fault_not_positive_definite,
    "triangle_violation": _fault_triangle_violation,
    "missing_gazebo_reference": _fault_missing_gazebo_reference,
    "wrong_type": _fault_wrong_type,
    "bad_unit": _fault_bad_unit,
    "injected_name": _fault_injected_name,
    "unknown_material": _fault_unknown_material,
    "not_finite": _fault_not_finite,
    "extreme_axis": _fault_extreme_axis,
    "deep_quantity": _fault_deep_quantity,
    "tube_inside_out": _fault_tube_inside_out,
    "composite_with_mass": _fault_composite_with_mass,
}


# ------------------------------------------------------------------------------------------------ URDF-level faults
URDF_FAULTS: dict[str, str] = {
    # fault -> the check rule meant to catch it
    "negative_mass": "I001",
    "swapped_limits": "J002",
    "dangling_parent": "S003",
    "cycle": "S002",
    "duplicate_name": "S004",
    "zero_axis": "J006",
    "not_positive_definite": "I002",
    "triangle_violation": "I003",
    "missing_gazebo_reference": "R001",
}

# (a box of 2 m: the tensor below, 1 kg with moments of about 1 kg*m^2, is one a body of that size can have: I008)
_FAULT_LINK = (
    '<link name="fault_link"><visual><geometry><box size="2 2 2"/></geometry></visual>'
    '<inertial><mass value="{mass}"/><inertia ixx="{ixx}" ixy="{ixy}" ixz="0" iyy="1.0" iyz="0" izz="{izz}"/>'
    "</inertial></link>"
)
_FAULT_JOINT = (
    '<joint name="fault_joint" type="{kind}"><parent link="{parent}"/><child link="fault_link"/>'
    '<axis xyz="{axis}"/>{limit}<dynamics damping="0.1" friction="0"/></joint>'
)


def inject_urdf_fault(urdf: str, fault: str, root_link: str) -> str:
    """``urdf`` (a valid robot whose root is ``root_link``) with exactly one fault of kind ``fault``."""

    robot = etree.fromstring(urdf.encode("utf-8"))
    link = {"mass": 1.0, "ixx": 1.0, "ixy": 0.0, "izz": 1.2}  # (not 1 * identity: I005 would call it a placeholder)
    joint = {
        "kind": "revolute",
        "parent": root_link,
        "axis": "0 0 1",
        "limit": '<limit lower="-1" upper="1" effort="1" velocity="1"/>',
    }
    extra: list[str] = []
    if fault == "negative_mass":
        link["mass"] = -1.0
    elif fault == "swapped_limits":
        joint["limit"] = '<limit lower="1" upper="-1" effort="1" velocity="1"/>'
    elif fault == "dangling_parent":
        joint["parent"] = "no_such_link"
    elif fault == "zero_axis":
        joint.update(kind="continuous", axis="0 0 0", limit='<limit effort="1" velocity="1"/>')
    elif fault == "not_positive_definite":
        link["ixy"] = 1.5
    elif fault == "triangle_violation":
        link["izz"] = 2.5  # > ixx + iyy = 2
    elif fault == "cycle":
        extra = [
            '<link name="loop_a"/>',
            '<link name="loop_b"/>',
            '<joint name="loop_ab" type="fixed"><parent link="loop_a"/><child link="loop_b"/></joint>',
            '<joint name="loop_ba" type="fixed"><parent link="loop_b"/><child link="loop_a"/></joint>',
        ]
    elif fault == "duplicate_name":
        extra = [etree.tostring(robot.find("link")).decode()]
    elif fault == "missing_gazebo_reference":
        extra = ['<gazebo reference="no_such_link"><mu1>1.0</mu1></gazebo>']
    else:
        raise ValueError(f"unknown fault {fault!r}; one of {', '.join(URDF_FAULTS)}")
    pieces = [_FAULT_LINK.format(**link), _FAULT_JOINT.format(**joint), *extra]
    for piece in pieces:
        robot.append(etree.fromstring(piece))
    return etree.tostring(robot, encoding="unicode")


# ------------------------------------------------------------------------------------------------ hostile inputs
from .hostile import (  # noqa: E402  (re-exported: the bad inputs of every class, xacrokit.testing.hostile)
    HOSTILE_FILE_NAMES,
    HOSTILE_NUMBERS,
    HOSTILE_PATHS,
    hostile_arguments,
    hostile_file_names,
    hostile_spec_texts,
    hostile_xacro_documents,
    make_hostile_path,
    spec_text,
)

__all__ = [
    "FAULTS",
    "HOSTILE_FILE_NAMES",
    "HOSTILE_NUMBERS",
    "HOSTILE_PATHS",
    "URDF_FAULTS",
    "hostile_arguments",
    "hostile_file_names",
    "hostile_spec_texts",
    "hostile_xacro_documents",
    "inject_urdf_fault",
    "invalid_specs",
    "make_hostile_path",
    "mirrored_specs",
    "spec_text",
    "valid_specs",
]
