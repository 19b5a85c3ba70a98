"""The check stage: a strict verifier for any URDF, xacro document or spec.

Our own rules run first (structure, joints, inertia, references, prefix, DH kinematics), then independent consumers
(check_urdf, pinocchio, yourdfpy, MuJoCo when installed). Every finding has a stable rule id, a severity, the element
it is about, where it came from when that can be known, and a message saying what is wrong and what would be right.
"""

from __future__ import annotations

import math
import re
import tempfile
from collections.abc import Callable, Iterable, Iterator, Mapping, Sequence
from dataclasses import dataclass, field
from pathlib import Path
from typing import Literal

import numpy as np
from lxml import etree

from .consumers import CONSUMERS, ConsumerResult, available, run_consumers
from .errors import SpecError, SpecErrors, XacrokitError
from .gcpause import collector_paused
from .model import JOINT_TYPES, MOVING
from .physics import TOLERANCE, format_moments, moments_problem, principal_moments
from .tree import Tree
from .units import NUMBER

Severity = Literal["error", "warning"]

# rule id -> (name, severity, what it checks). The ids are stable: scripts may filter on them.
RULES: dict[str, tuple[str, Severity, str]] = {
    "U001": ("urdf-readable", "error", "the document is well-formed XML with a <robot> root"),
    "U002": (
        "numbers-readable",
        "error",
        "every number URDF reads (origins, axes, sizes, masses, tensors, limits, dynamics, colours) is finite, with as "
        "many values as its attribute takes",
    ),
    "S001": ("one-root", "error", "exactly one link has no parent"),
    "S002": ("no-cycle", "error", "no chain of joints leads back to where it started"),
    "S003": ("joint-links-exist", "error", "every joint's parent and child is a link of the document"),
    "S004": ("unique-link-names", "error", "no two links share a name"),
    "S005": ("unique-joint-names", "error", "no two joints share a name"),
    "S006": ("one-parent", "error", "no link is the child of two joints"),
    "N001": (
        "name-plain",
        "warning",
        "link and joint names are not empty, hold no whitespace or control characters and do not start with '/' "
        "(tf2 refuses such frame ids; ROS tools split on spaces)",
    ),
    "J001": ("limit-present", "error", "revolute and prismatic joints have <limit> with lower and upper"),
    "J002": ("limit-order", "error", "lower <= upper"),
    "J003": ("limit-effort", "error", "moving joints' effort limit is > 0"),
    "J004": ("limit-velocity", "error", "moving joints' velocity limit is > 0"),
    "J005": ("continuous-limit", "error", "continuous joints have <limit> with effort and velocity"),
    "J006": ("axis-nonzero", "error", "a joint's axis is not the zero vector"),
    "J007": ("axis-unit", "warning", "a joint's axis has unit length"),
    "J008": ("mimic-target", "error", "<mimic> names an existing moving joint of the same type, not itself"),
    "J009": ("dynamics-present", "warning", "moving joints have <dynamics> (damping, friction)"),
    "J010": ("safety-inside-limits", "error", "safety_controller soft limits lie inside the hard limits"),
    "J011": ("joint-type", "error", "a joint's type is one URDF knows"),
    "J012": (
        "floating-at-root",
        "warning",
        "a floating joint hangs from the root link (simulators reject deeper ones)",
    ),
    "I001": (
        "mass-positive",
        "error",
        "links with geometry have an inertial with mass > 0; so does the body a moving joint moves (its child link or "
        "a link fixed to it)",
    ),
    "I002": ("inertia-positive-definite", "error", "the inertia tensor is positive definite"),
    "I003": ("inertia-triangle", "error", "principal moments obey the triangle inequality"),
    "I004": ("inertia-plausible", "warning", "inertia fits the collision geometry's size (within 100x)"),
    "I005": ("inertia-placeholder", "warning", "the tensor is not an identity-like placeholder"),
    "R001": ("gazebo-reference", "error", "<gazebo reference> names an existing link or joint"),
    "R002": ("material-defined", "error", "a material used by name without a colour is defined"),
    "R003": ("mesh-resolves", "error", "mesh files resolve (package://, file:// or paths) and exist"),
    "P001": ("prefix", "error", "every link, joint, gazebo reference and ros2_control joint carries the prefix"),
    "K001": ("dh-kinematics", "error", "for a spec's DH arms, URDF forward kinematics equal the DH product"),
    "V001": (
        "spec-units",
        "warning",
        "a spec's plain-number angles stay within a turn (joint limits two), and a mass in a shape gives a density "
        "between air's and osmium's (else: degrees, grams or millimetres written without their unit?)",
    ),
    "V002": ("spec-valid", "error", "a spec follows its schema and the rules gen-robot applies (as gen-robot SPEC)"),
    "C001": ("consumer-accepts", "error", "an independent consumer loads the URDF"),
}


@dataclass(frozen=True)
class Finding:
    rule: str
    severity: Severity
    element_kind: str  # robot, link, joint, gazebo, material, mesh, ros2_control, consumer, value (a spec's)
    element: str
    message: str
    file: str | None = None
    line: int | None = None

    @property
    def name(self) -> str:
        return RULES[self.rule][0]

    def to_dict(self) -> dict[str, object]:
        return {
            "rule": self.rule,
            "name": self.name,
            "severity": self.severity,
            "element": {"kind": self.element_kind, "name": self.element},
            "file": self.file,
            "line": self.line,
            "message": self.message,
        }


@dataclass(frozen=True)
class CheckReport:
    source: str
    kind: str  # urdf, xacro or spec
    robot: str | None
    findings: tuple[Finding, ...]
    consumers: tuple[ConsumerResult, ...] = field(default=())

    @property
    def errors(self) -> list[Finding]:
        return [f for f in self.findings if f.severity == "error"]

    @property
    def warnings(self) -> list[Finding]:
        return [f for f in self.findings if f.severity == "warning"]

    def exit_code(self, strict: bool = False) -> int:
        return 1 if self.errors or (strict and self.warnings) else 0

    def to_dict(self) -> dict[str, object]:
        return {
            "format": "xacrokit-check/1",
            "source": self.source,
            "kind": self.kind,
            "robot": self.robot,
            "summary": {
                "errors": len(self.errors),
                "warnings": len(self.warnings),
                "verdict": "clean" if not self.errors else "errors",
            },
            "findings": [f.to_dict() for f in self.findings],
            "consumers": [{"name": c.name, "status": c.status, "message": c.message} for c in self.consumers],
        }


# ------------------------------------------------------------------------------------------------------------ rules
class _Doc:
    """The parts of a URDF the rules read, with source lines."""

    def __init__(
        self, root: etree._Element, file: str | None, lines: Mapping[tuple[str, str], int] | None, *, source_lines: bool
    ) -> None:
        self.root = root
        self.file = file
        self.spec_lines = lines  # for spec input: (kind, name) -> line in the spec
        self.source_lines = source_lines  # URDF input: element lines are the file's own
        self.links = [e for e in root if e.tag == "link"]
        self.joints = [e for e in root if e.tag == "joint"]
        self.link_names = {e.get("name", "") for e in self.links}
        self.joint_by_name = {e.get("name", ""): e for e in self.joints}
        self.fixed_children: dict[str, list[str]] | None = None  # (built when a rule first asks: _body_has_mass)
        self.massive: set[str] = set()

    def finding(self, rule: str, kind: str, name: str, message: str, element: etree._Element | None = None) -> Finding:
        line = None
        if self.spec_lines is not None:
            line = self.spec_lines.get((kind, name))
            owner = element
            while line is None and owner is not None:  # a mesh, say: the line of the link or joint it belongs to
                if owner.tag in ("link", "joint"):
                    line = self.spec_lines.get((owner.tag, owner.get("name", "")))
                owner = owner.getparent()
        elif element is not None and self.source_lines:
            line = element.sourceline  # (an expanded xacro's lines are not the xacro file's: leave them out)
        return Finding(rule, RULES[rule][1], kind, name, message, self.file, line)


def _float(element: etree._Element | None, attribute: str, default: float | None = None) -> float | None:
    if element is None or element.get(attribute) is None:
        return default
    try:
        return float(element.get(attribute, ""))
    except ValueError:
        return math.nan


def _triple(element: etree._Element | None, attribute: str, default: str = "0 0 0") -> tuple[float, float, float]:
    """Three numbers from an attribute such as xyz or size; NaNs when it does not hold exactly three."""
    text = default if element is None else element.get(attribute, default)
    try:
        values = tuple(float(v) for v in text.split())
    except ValueError:
        values = ()
    return values if len(values) == 3 else (math.nan, math.nan, math.nan)  # type: ignore[return-value]


def _duplicate_names(doc: _Doc, elements: list[etree._Element], kind: str, rule: str) -> Iterator[Finding]:
    seen: dict[str, etree._Element] = {}
    for element in elements:
        name = element.get("name", "")
        if name in seen:
            message = f"{kind} {name!r} is defined twice (also on line {seen[name].sourceline}); rename one"
            yield doc.finding(rule, kind, name, message, element)
        seen[name] = element


def structure_rules(doc: _Doc) -> Iterator[Finding]:
    yield from _duplicate_names(doc, doc.links, "link", "S004")
    yield from _duplicate_names(doc, doc.joints, "joint", "S005")
    tree: Tree[str] = Tree()  # child -> (parent, joint)
    for joint in doc.joints:
        name = joint.get("name", "")
        parent = joint.find("parent").get("link", "") if joint.find("parent") is not None else ""
        child = joint.find("child").get("link", "") if joint.find("child") is not None else ""
        missing = [
            f"{role} {value!r}" for role, value in (("parent", parent), ("child", child)) if value not in doc.link_names
        ]
        if missing:
            yield doc.finding("S003", "joint", name, f"{' and '.join(missing)} not a link of this robot", joint)
            continue
        first = tree.add(parent, child, name)
        if first is not None:
            loop = tree.path_up(parent, child)
            if loop:  # following this joint leads back to the child: a cycle hanging off the tree
                yield doc.finding(
                    "S002",
                    "joint",
                    name,
                    f"joint {name!r} closes a cycle {' -> '.join([*reversed(loop), child])}; remove it",
                    joint,
                )
            else:
                first_parent, first_joint = first
                yield doc.finding(
                    "S006",
                    "link",
                    child,
                    f"link {child!r} has two parents: {first_parent!r} (joint "
                    f"{first_joint!r}) and {parent!r} (joint {name!r}); a URDF is "
                    "a tree: remove one of the joints",
                    joint,
                )
    roots = tree.roots(doc.link_names)
    in_cycles = sorted(doc.link_names - tree.reachable(roots))
    if in_cycles:
        yield doc.finding(
            "S002",
            "link",
            in_cycles[0],
            f"links {', '.join(in_cycles)} form a cycle; break it by removing one of its joints",
        )
    if len(roots) != 1 and doc.links:
        what = "no link" if not roots else f"{len(roots)} links ({', '.join(roots)})"
        yield doc.finding(
            "S001",
            "robot",
            doc.root.get("name", ""),
            f"{what} have no parent; a robot has exactly one root: connect the trees with joints",
        )


_UNPLAIN = re.compile(r"[\s\x00-\x1f\x7f]")


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


def number_rules(doc: _Doc) -> Iterator[Finding]:
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


def name_rules(doc: _Doc) -> Iterator[Finding]:
    for kind, elements in (("link", doc.links), ("joint", doc.joints)):
        for element in elements:
            name = element.get("name", "")
            if not name:
                problem = "has no name"
            elif _UNPLAIN.search(name):
                problem = "has whitespace or a control character in its name"
            elif name.startswith("/") and kind == "link":
                problem = "has a name starting with '/', which tf2 refuses as a frame id"
            else:
                continue
            yield doc.finding("N001", kind, name, f"{kind} {name!r} {problem}; use letters, digits and _", element)


def joint_rules(doc: _Doc) -> Iterator[Finding]:
    types = {j.get("name", ""): j.get("type", "") for j in doc.joints}
    children = {j.find("child").get("link") for j in doc.joints if j.find("child") is not None}
    for joint in doc.joints:
        name, kind = joint.get("name", ""), joint.get("type", "")

        def found(rule: str, message: str, name: str = name, joint: etree._Element = joint) -> Finding:
            return doc.finding(rule, "joint", name, message, joint)

        if kind not in JOINT_TYPES:
            yield found("J011", f"type {kind!r} is not a URDF joint type ({', '.join(JOINT_TYPES)})")
            continue
        limit = joint.find("limit")
        if kind in ("revolute", "prismatic"):
            lower, upper = _float(limit, "lower"), _float(limit, "upper")
            if limit is None or lower is None or upper is None:
                yield found("J001", f"a {kind} joint needs <limit lower upper effort velocity>")
            elif not lower <= upper:
                yield found("J002", f"limit lower ({lower}) is greater than upper ({upper}); swap them")
        if kind == "continuous" and (limit is None or limit.get("effort") is None or limit.get("velocity") is None):
            yield found(
                "J005",
                "a continuous joint needs <limit effort=... velocity=...> (controllers and simulators read them)",
            )
        if kind in MOVING and limit is not None:
            for rule, key, unit in (("J003", "effort", "N*m or N"), ("J004", "velocity", "rad/s or m/s")):
                value = _float(limit, key)
                if value is not None and not value > 0:
                    yield found(rule, f"limit {key} is {value}; it must be > 0 ({unit})")
                elif value is None and kind != "continuous":
                    yield found(rule, f"limit has no {key}; give one > 0 ({unit})")
        if kind in MOVING or kind == "planar":
            axis = _triple(joint.find("axis"), "xyz", "1 0 0")
            norm = math.hypot(*axis)
            if not math.isfinite(norm) or norm == 0:
                yield found(
                    "J006",
                    f"axis {joint.find('axis').get('xyz') if joint.find('axis') is not None else ''!r}"
                    " is zero or unreadable; give a direction such as '0 0 1'",
                )
            elif abs(norm - 1.0) > 1e-6:
                yield found("J007", f"axis has length {norm:.6g}; consumers normalise it, write the unit vector")
        if kind in MOVING and joint.find("dynamics") is None and joint.find("mimic") is None:
            yield found("J009", "moving joint without <dynamics damping friction>; simulators then assume none")
        if kind == "floating" and joint.find("parent") is not None and joint.find("parent").get("link") in children:
            yield found(
                "J012",
                "floating joint below the root link; MuJoCo and most simulators accept a floating "
                "joint only as the base: make it fixed, or the robot's root",
            )
        mimic = joint.find("mimic")
        if mimic is not None:
            target = mimic.get("joint", "")
            if target == name:
                yield found("J008", "a joint cannot mimic itself")
            elif target not in types:
                yield found("J008", f"mimics {target!r}, which is not a joint of this robot")
            elif (
                types[target] not in MOVING
                or kind not in MOVING
                or (types[target] == "prismatic") != (kind == "prismatic")
            ):
                yield found(
                    "J008",
                    f"mimics {target!r} ({types[target]}) from a {kind} joint; both must move, "
                    "and rotate (or slide) alike",
                )
        safety = joint.find("safety_controller")
        if safety is not None and limit is not None and kind in ("revolute", "prismatic"):
            lower, upper = _float(limit, "lower"), _float(limit, "upper")
            soft_lower, soft_upper = _float(safety, "soft_lower_limit"), _float(safety, "soft_upper_limit")
            if lower is not None and soft_lower is not None and soft_lower < lower:
                yield found("J010", f"soft_lower_limit {soft_lower} is below the hard lower limit {lower}")
            if upper is not None and soft_upper is not None and soft_upper > upper:
                yield found("J010", f"soft_upper_limit {soft_upper} is above the hard upper limit {upper}")


_INERTIA = ("ixx", "ixy", "ixz", "iyy", "iyz", "izz")
_PLACEHOLDERS = (1.0, 0.1, 0.01, 1e-3, 1e-4, 1e-5, 1e-6)


def _geometry_extent(geometry: etree._Element | None) -> tuple[float, float, float] | None:
    """Edge lengths of the geometry's own bounding box, or None when unknown (meshes)."""
    if geometry is None:
        return None
    if (box := geometry.find("box")) is not None:
        return _triple(box, "size")
    if (cylinder := geometry.find("cylinder")) is not None:
        r, length = _float(cylinder, "radius", math.nan), _float(cylinder, "length", math.nan)
        return (2 * r, 2 * r, length)  # type: ignore[operator]
    if (sphere := geometry.find("sphere")) is not None:
        diameter = 2 * (_float(sphere, "radius", math.nan) or math.nan)
        return (diameter, diameter, diameter)
    return None


def _massive(link: etree._Element) -> bool:
    inertial = link.find("inertial")
    mass = _float(inertial.find("mass"), "value") if inertial is not None else None
    return mass is not None and mass > 0


def _body_has_mass(doc: _Doc, name: str) -> bool:
    """Whether the rigid body of link ``name`` has mass: a link hanging from it by fixed joints may carry it
    (consumers merge fixed children into their parent, so a moving joint may move a massless link whose fixed child
    carries the mass). Each fixed-joint component has one moved link at its top, so all calls together are linear."""
    if doc.fixed_children is None:
        doc.fixed_children = {}
        for joint in doc.joints:
            parent, child = joint.find("parent"), joint.find("child")
            if joint.get("type") == "fixed" and parent is not None and child is not None:
                doc.fixed_children.setdefault(parent.get("link", ""), []).append(child.get("link", ""))
        doc.massive = {link.get("name", "") for link in doc.links if _massive(link)}
    seen, stack = {name}, [name]
    while stack:  # (a cycle of fixed joints is S002's; ``seen`` keeps this walk finite)
        current = stack.pop()
        if current in doc.massive:
            return True
        for child in doc.fixed_children.get(current, ()):
            if child not in seen:
                seen.add(child)
                stack.append(child)
    return False


def inertia_rules(doc: _Doc) -> Iterator[Finding]:
    moved = {j.find("child").get("link") for j in doc.joints if j.get("type") in MOVING and j.find("child") is not None}
    # (ixx, ixy, ixz, iyy, iyz, izz) of every link that has them; the principal moments of all the finite ones in one
    # batched eigvalsh, consumed in link order below (per-link numpy calls cost ten times more)
    entries = [_inertia_entries(link) for link in doc.links]
    moments_in_order = iter(
        principal_moments([e for e in entries if e is not None and all(math.isfinite(v) for v in e)])
    )
    for link, entry in zip(doc.links, entries, strict=True):
        moments = next(moments_in_order) if entry is not None and all(math.isfinite(v) for v in entry) else None
        name = link.get("name", "")
        inertial = link.find("inertial")
        has_geometry = link.find("visual") is not None or link.find("collision") is not None
        mass = _float(inertial.find("mass"), "value") if inertial is not None else None
        if has_geometry or name in moved:
            why = "has geometry" if has_geometry else "is moved by a joint"
            if mass is None:
                if not has_geometry and _body_has_mass(doc, name):
                    continue  # a massless link whose fixed children carry the moved body's mass
                where = "" if has_geometry else " (nor any link fixed to it)"
                yield doc.finding(
                    "I001",
                    "link",
                    name,
                    f"link {why} but no <inertial> mass{where}; give mass > 0 (kg) and its inertia",
                    link,
                )
                continue
            if not mass > 0:
                yield doc.finding("I001", "link", name, f"mass is {mass}; it must be > 0 kg", link)
                continue
        if entry is None:
            continue
        if mass == 0 and not any(entry) and not (has_geometry or name in moved):
            continue  # an explicit all-zero inertial on a bare frame: a massless frame, as many descriptions write
        if moments is None:
            yield doc.finding("I002", "link", name, "the inertia tensor has unreadable entries", link)
            continue
        problem = moments_problem(moments)
        if problem == "not-positive-definite":
            yield doc.finding(
                "I002",
                "link",
                name,
                f"inertia is not positive definite (principal moments "
                f"{format_moments(moments)}); every principal moment must be > 0",
                link,
            )
            continue
        total = sum(moments)
        if problem == "triangle-inequality":
            yield doc.finding(
                "I003",
                "link",
                name,
                f"principal moments {format_moments(moments)} violate the triangle "
                "inequality: each must be at most the sum of the other two",
                link,
            )
            continue
        ixx, ixy, ixz, iyy, iyz, izz = entry
        if ixy == ixz == iyz == 0 and ixx == iyy == izz and ixx in _PLACEHOLDERS:
            yield doc.finding(
                "I005",
                "link",
                name,
                f"inertia is {ixx:g} * identity, a common placeholder; "
                "compute it from the body (e.g. xacrokit's inertia macros)",
                link,
            )
        if mass and mass > 0:
            yield from _plausibility(doc, link, name, mass, total)


def _inertia_entries(link: etree._Element) -> tuple[float, ...] | None:
    inertial = link.find("inertial")
    inertia = inertial.find("inertia") if inertial is not None else None
    return None if inertia is None else tuple(_float(inertia, key, 0.0) for key in _INERTIA)  # type: ignore[misc]


def _plausibility(doc: _Doc, link: etree._Element, name: str, mass: float, trace: float) -> Iterator[Finding]:
    """Compare trace(I) with a solid box filling the collision geometry's bounding box: m * diagonal^2 / 6."""
    extents = [_geometry_extent(c.find("geometry")) for c in link.findall("collision")]
    if not extents or any(e is None or not all(math.isfinite(v) for v in e) for e in extents):
        return
    diagonal_sq = max(sum(v * v for v in e) for e in extents)  # type: ignore[union-attr]
    expected = mass * diagonal_sq / 6.0
    if expected > 0 and not 1e-2 <= trace / expected <= 1e2:
        yield doc.finding(
            "I004",
            "link",
            name,
            f"inertia (trace {trace:.3g} kg*m^2) is {trace / expected:.3g} times "
            f"that of a solid body filling the collision geometry ({expected:.3g}); "
            "a units mistake (mm for m, g for kg)?",
            link,
        )


def reference_rules(
    doc: _Doc, package_paths: Mapping[str, str | Path] | None, base_dir: Path | None
) -> Iterator[Finding]:
    for gazebo in doc.root.findall("gazebo"):
        reference = gazebo.get("reference")
        if reference is not None and reference not in doc.link_names and reference not in doc.joint_by_name:
            yield doc.finding(
                "R001", "gazebo", reference, f"<gazebo reference={reference!r}> names no link or joint", gazebo
            )
    defined = {m.get("name") for m in doc.root.findall("material")}
    for material in doc.root.iter("material"):
        if material.getparent() is doc.root:
            continue
        name = material.get("name")
        has_own = material.find("color") is not None or material.find("texture") is not None
        if name and not has_own and name not in defined:
            yield doc.finding(
                "R002",
                "material",
                name,
                f"material {name!r} is used but not defined; add <material name={name!r}><color rgba=.../></material>",
                material,
            )
    for mesh in doc.root.iter("mesh"):
        filename = mesh.get("filename", "")
        problem, severity_rule = _mesh_problem(filename, package_paths, base_dir)
        if problem:
            finding = doc.finding("R003", "mesh", filename, problem, mesh)
            if severity_rule == "warning":
                finding = Finding(
                    finding.rule,
                    "warning",
                    finding.element_kind,
                    finding.element,
                    finding.message,
                    finding.file,
                    finding.line,
                )
            yield finding


def _mesh_problem(
    filename: str, package_paths: Mapping[str, str | Path] | None, base_dir: Path | None
) -> tuple[str | None, Severity]:
    from .expansion import find_package

    if filename.startswith("package://"):
        package, _, rest = filename[len("package://") :].partition("/")
        try:
            folder = Path(find_package(package, package_paths))
        except LookupError:
            return (
                f"package {package!r} is not known here, so {filename!r} cannot be checked; pass "
                f"--package {package}=PATH",
                "warning",
            )
        path = folder / rest
    elif filename.startswith("file://"):
        path = Path(filename[len("file://") :])
    elif re.match(r"^[a-z][a-z0-9+.-]*://", filename):
        return f"{filename!r}: unknown URI scheme; use package:// or file://", "error"
    else:
        path = (base_dir or Path.cwd()) / filename
    if not path.is_file():
        return f"mesh file {filename!r} does not exist (looked at {path})", "error"
    return None, "error"


def prefix_rules(doc: _Doc, prefix: str) -> Iterator[Finding]:
    named = [("link", e) for e in doc.links] + [("joint", e) for e in doc.joints]
    named += [("gazebo", g) for g in doc.root.findall("gazebo") if g.get("reference") is not None]
    named += [("ros2_control", j) for j in doc.root.findall("ros2_control/joint")]
    for kind, element in named:
        name = element.get("reference") if kind == "gazebo" else element.get("name", "")
        if not (name or "").startswith(prefix):
            yield doc.finding(
                "P001", kind, name or "", f"{kind} {name!r} does not start with the prefix {prefix!r}", element
            )


# ------------------------------------------------------------------------------------------------------------ inputs
def _notes(problems: Iterable[SpecError], rule: str = "V001") -> tuple[Finding, ...]:
    """A spec's warnings (values that look like a units mistake; V001) or errors (V002) as findings."""
    return tuple(Finding(rule, RULES[rule][1], "value", e.path, e.message, e.file, e.line) for e in problems)


def kinematics_rules(doc: _Doc, robot, urdf_text: str) -> Iterator[Finding]:
    """K001: for each DH arm, FK from its parent to its tool frame equals the DH product at sample joint values."""
    import pinocchio as pin

    from .kinematics import dh_chain

    model = pin.buildModelFromXML(urdf_text)
    data = model.createData()
    rng = np.random.default_rng(0)
    for arm in robot.arms:
        worst = 0.0
        for trial in range(8):
            q = pin.neutral(model)
            values = []
            for row in arm.rows:
                value = 0.0 if row.type == "fixed" or trial == 0 else float(rng.uniform(-math.pi, math.pi))
                if row.type != "fixed":
                    joint = model.getJointId(row.name)
                    start = model.idx_qs[joint]
                    if model.nqs[joint] == 2:
                        q[start], q[start + 1] = math.cos(value), math.sin(value)
                    else:
                        q[start] = value
                values.append(value)
            pin.framesForwardKinematics(model, data, q)
            got = (data.oMf[model.getFrameId(arm.parent)].inverse() * data.oMf[model.getFrameId(arm.tool)]).homogeneous
            want = dh_chain(arm.rows, values, arm.convention, arm.origin, arm.tool_origin)
            worst = max(worst, float(np.abs(got - want).max()))
        if not worst <= TOLERANCE:
            yield doc.finding(
                "K001",
                "link",
                arm.tool,
                f"arm {arm.name!r}: URDF forward kinematics differ from the DH "
                f"product by up to {worst:.3g} (m / rotation entries)",
            )


def _load_urdf(
    path: Path, kind: str, mappings: Mapping[str, str] | None, package_paths: Mapping[str, str | Path] | None
) -> tuple[str, object | None, dict | None, tuple[Finding, ...]]:
    """URDF text, and for spec input the robot model, the spec lines and the spec's warnings."""
    if kind == "spec":
        from .pipeline import spec_urdf

        described = spec_urdf(path)
        return described.urdf, described.robot, described.lines, _notes(described.warnings)
    if kind == "xacro":
        from .expansion import expand_file

        return expand_file(path, mappings, package_paths=package_paths), None, None, ()
    try:
        return path.read_text(encoding="utf-8"), None, None, ()
    except (OSError, UnicodeDecodeError) as exc:
        why = exc.strerror if isinstance(exc, OSError) and exc.strerror else str(exc)
        raise XacrokitError(f"cannot read {path}: {why}") from None


def input_kind(path: Path) -> str:
    """spec, xacro or urdf: by the file's suffix, or for another suffix by its first 4 KiB (XML starts with '<'; a
    xacro document declares the xacro namespace or uses a xacro: element)."""
    name = path.name.lower()
    if name.endswith((".yaml", ".yml")):
        return "spec"
    if name.endswith(".xacro"):
        return "xacro"
    if name.endswith((".urdf", ".xml")):
        return "urdf"
    try:
        with path.open("rb") as file:
            head = file.read(4096)
    except OSError:
        return "urdf"  # (reading it again says why it cannot be read)
    text = head.decode("utf-8", "replace").lstrip("\ufeff \t\r\n")
    if not text.startswith("<"):
        return "spec"
    return "xacro" if re.search(r"xmlns:xacro\s*=|<xacro:", text) else "urdf"


@collector_paused()
def check(
    path: str | Path,
    mappings: Mapping[str, str] | None = None,
    *,
    prefix: str | None = None,
    consumers: Sequence[str] | None = None,
    package_paths: Mapping[str, str | Path] | None = None,
    progress: Callable[[str], None] | None = None,
) -> CheckReport:
    """Check a URDF, a xacro document (expanded with ``mappings``) or a spec (generated in memory, never written).

    Args:
        path: the file; ``.yaml``/``.yml`` is a spec, ``.xacro`` a xacro document, ``.urdf``/``.xml`` URDF; any
            other name is told by its content (XML is URDF, or xacro when it declares the xacro namespace; else a
            spec). A URDF or xacro file inside a ROS package finds that package and its siblings for ``package://``
            and ``$(find)`` without ``package_paths``.
        mappings: ``xacro:arg`` values for a xacro document.
        prefix: when given, every link, joint, gazebo reference and ros2_control joint must start with it.
        consumers: which independent consumers to run (default: every installed one of check_urdf, pinocchio,
            yourdfpy, mujoco); ``[]`` for none.
        package_paths: folders for ``$(find PKG)`` and ``package://PKG`` of packages not otherwise found.
        progress: called with a short message as each step starts (the CLI shows it on a terminal).

    Raises:
        XacrokitError: the input cannot be read (a spec file that cannot be read raises SpecErrors, a xacro
            ExpandError). A spec with located errors gives a report of V002 findings instead.
    """
    from .expansion import with_nearby_packages

    path = Path(path)
    say = progress or (lambda message: None)
    kind = input_kind(path)
    if mappings and kind != "xacro":
        raise XacrokitError("name:=value arguments only apply to xacro input")
    if consumers is not None:
        _require_consumers(consumers)
    if kind != "spec":  # a file inside a package finds that package (and its workspace siblings) by itself
        package_paths = with_nearby_packages(path, package_paths)
    say(f"reading {path.name}")
    try:
        text, robot, lines, notes = _load_urdf(path, kind, mappings, package_paths)
    except SpecErrors as exc:
        if all(e.line is None for e in exc.errors):  # the file itself cannot be read: no report to give
            raise
        return CheckReport(str(path), kind, None, _notes(exc.errors, "V002"))
    try:
        root = etree.fromstring(text.encode("utf-8"))
    except etree.XMLSyntaxError as exc:
        finding = Finding("U001", "error", "robot", "", f"not well-formed XML: {exc}", str(path), exc.lineno)
        return CheckReport(str(path), kind, None, (finding,))
    if root.tag != "robot":
        finding = Finding("U001", "error", "robot", "", f"the root element is <{root.tag}>, not <robot>", str(path), 1)
        return CheckReport(str(path), kind, None, (finding,))
    say("running our rules")
    doc = _Doc(root, str(path), lines, source_lines=kind == "urdf")
    findings = [*notes, *structure_rules(doc)]
    structural = any(f.rule.startswith("S") for f in findings)
    findings += number_rules(doc)
    findings += name_rules(doc)
    findings += joint_rules(doc)
    findings += inertia_rules(doc)
    findings += reference_rules(doc, package_paths, path.parent)
    if prefix is not None:
        findings += prefix_rules(doc, prefix)
    if robot is not None and not structural and getattr(robot, "arms", ()):
        findings += kinematics_rules(doc, robot, text)
    names = [c for c in (CONSUMERS if consumers is None else consumers) if consumers is not None or available(c)]
    if names and not structural:
        say(f"running {', '.join(names)}")
    results = _consumers(names, text, structural, package_paths, path.parent)
    findings += [
        Finding("C001", "error", "consumer", r.name, f"{r.name} {r.status}: {r.message}".rstrip(": "), str(path))
        for r in results
        if r.failed
    ]
    unique = tuple(dict.fromkeys(findings))  # (a spec's visual and collision share a mesh: one finding, not two)
    return CheckReport(str(path), kind, root.get("name"), unique, tuple(results))


def _require_consumers(names: Sequence[str]) -> None:
    """Consumers asked for by name must exist and be installed: a verdict that was asked for is never left out."""
    unknown = [n for n in names if n not in CONSUMERS]
    if unknown:
        raise XacrokitError(f"unknown consumer(s) {', '.join(unknown)}; choose from {', '.join(CONSUMERS)}")
    missing = [n for n in names if not available(n)]
    if missing:
        hint = " (pip install 'xacrokit[mujoco]')" if "mujoco" in missing else ""
        raise XacrokitError(
            f"consumer(s) {', '.join(missing)} asked for but not installed{hint}; install them, or leave them out "
            "of --consumers"
        )


def _consumers(
    names: list[str], text: str, structural: bool, package_paths: Mapping[str, str | Path] | None, base_dir: Path
) -> list[ConsumerResult]:
    if not names:
        return []
    if structural:  # a tree that is not a tree hangs check_urdf and crashes others; our finding says it all
        return [
            ConsumerResult(n, "skipped", "not run: the structure errors above make the URDF unusable") for n in names
        ]
    # relative mesh paths are relative to the checked file: make them absolute before the URDF moves to a scratch folder
    root = etree.fromstring(text.encode("utf-8"))
    for mesh in root.iter("mesh"):
        filename = mesh.get("filename", "")
        if filename and "://" not in filename and not Path(filename).is_absolute():
            mesh.set("filename", str(base_dir.resolve() / filename))
    with tempfile.TemporaryDirectory(prefix="xacrokit-check-") as folder:
        urdf = Path(folder) / "robot.urdf"
        urdf.write_text(etree.tostring(root, encoding="unicode"), encoding="utf-8")
        return run_consumers(names, urdf, package_paths=package_paths)
