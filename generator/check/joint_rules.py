"""Joint rules (J001-J012): a joint's type, limits, axis, mimic, dynamics and safety controller are ones consumers
accept."""

from __future__ import annotations

import math
from collections.abc import Iterator

from ..shared.joint_types import AXIAL, JOINT_TYPES, LIMITED, MOVING
from ..shared.kinematic_tree import cycles
from ..shared.urdf_view import Attributes, Joint, Mimic
from .findings import Finding, Severity, rule_table
from .urdf_document import Doc, number_of

RULES = rule_table(
    {
        "J001": (
            "limit-present",
            "error",
            "revolute and prismatic joints have <limit> (urdfdom rejects them without); a <limit> without lower and "
            "upper is a warning (URDF reads them as 0: the joint cannot move)",
        ),
        "J002": ("limit-order", "error", "lower <= upper"),
        "J003": (
            "limit-effort",
            "error",
            "a <limit> has an effort, not negative (urdfdom rejects it without, pinocchio a negative one); 0 is a "
            "warning (Gazebo then applies no force)",
        ),
        "J004": (
            "limit-velocity",
            "error",
            "a <limit> has a velocity, not negative (urdfdom rejects it without, pinocchio a negative one); 0 is a "
            "warning (Gazebo then holds the joint still)",
        ),
        "J005": (
            "continuous-limit",
            "error",
            "a continuous joint's <limit>, when given (it is optional), has effort and velocity (urdfdom rejects it "
            "without)",
        ),
        "J006": ("axis-nonzero", "error", "a joint's axis is not the zero vector"),
        "J007": ("axis-unit", "warning", "a joint's axis has unit length"),
        "J008": (
            "mimic-target",
            "error",
            "<mimic> names an existing joint, not itself and not round a cycle; a target of another kind (a fixed "
            "joint, or prismatic for revolute) is a warning",
        ),
        "J009": (
            "dynamics-present",
            "info",
            "moving joints have <dynamics> (damping, friction; optional in URDF: without it simulators assume none)",
        ),
        "J010": ("safety-inside-limits", "error", "safety_controller soft limits lie inside the hard limits"),
        "J011": ("joint-type", "error", "a joint's type is one URDF knows"),
        "J012": (
            "floating-at-root",
            "warning",
            "a floating joint hangs from the root link (simulators reject deeper ones)",
        ),
        "J013": (
            "limit-range",
            "warning",
            "a revolute or prismatic joint's lower and upper limits differ (equal ones leave it no motion: real "
            "limits, a continuous joint or a fixed one says what is meant; CAD exporters write 0 and 0 when they "
            "know none)",
        ),
    }
)


def _mimic_cycles(doc: Doc) -> Iterator[Finding]:
    """J008 for mimic joints that follow each other round a loop (none of them moves by itself)."""
    mimics = {j.name: j.mimic.joint or "" for j in doc.view.joints if j.mimic is not None}
    for loop in cycles(mimics):
        if len(loop) > 1:  # (a joint that mimics itself has its own message)
            message = f"mimic joints {' -> '.join([*loop, loop[0]])} form a cycle: none of them moves by itself"
            yield doc.finding("J008", "joint", loop[0], message, doc.joint_by_name.get(loop[0]))


def joint_rules(doc: Doc) -> Iterator[Finding]:
    types = {j.name: j.type or "" for j in doc.view.joints}
    yield from _mimic_cycles(doc)
    children = {j.child for j in doc.view.joints if j.child is not None}
    for joint in doc.view.joints:
        kind = joint.type or ""
        found = _At(doc, joint)
        if kind not in JOINT_TYPES:
            yield found("J011", f"type {kind!r} is not a URDF joint type ({', '.join(JOINT_TYPES)})")
            continue
        yield from _range(found, kind, joint.limit)
        yield from _rates(found, kind, joint.limit)
        yield from _axis(found, kind, joint)
        if kind in MOVING and joint.dynamics is None and joint.mimic is None:
            yield found("J009", "no <dynamics damping friction>: simulators assume none (URDF makes it optional)")
        if kind == "floating" and joint.parent in children:
            yield found(
                "J012",
                "floating joint below the root link; MuJoCo and most simulators accept a floating "
                "joint only as the base: make it fixed, or the robot's root",
            )
        yield from _mimic(found, kind, joint.mimic, types)
        yield from _safety(found, kind, joint.limit, joint.safety_controller)


class _At:
    """A finding about one joint: ``found(rule, message, level=None)``."""

    def __init__(self, doc: Doc, joint: Joint) -> None:
        self.doc, self.joint, self.name = doc, joint, joint.name

    def __call__(self, rule: str, message: str, level: Severity | None = None) -> Finding:
        return self.doc.finding(rule, "joint", self.name, message, self.joint.element, level)


def _range(found: _At, kind: str, limit: Attributes | None) -> Iterator[Finding]:
    """J001 (a limited joint's <limit> and its bounds), J002 (lower above upper), J013 (a range of one value)."""
    if kind not in LIMITED:
        return
    lower, upper = number_of(limit, "lower"), number_of(limit, "upper")
    if limit is None:
        yield found("J001", f"a {kind} joint needs <limit lower upper effort velocity>: urdfdom rejects it")
    elif lower is None or upper is None:
        missing = " and ".join(k for k, v in (("lower", lower), ("upper", upper)) if v is None)
        yield found(
            "J001",
            f"<limit> has no {missing}; URDF reads a missing one as 0, so the joint's range is "
            f"[{lower or 0.0:g}, {upper or 0.0:g}]: give both (or make an endless joint continuous)",
            level="warning",
        )
    elif not lower <= upper:
        yield found("J002", f"limit lower ({lower}) is greater than upper ({upper}); swap them")
    elif lower == upper:
        yield found(
            "J013",
            f"limit lower and upper are both {lower}: the joint cannot move; give it its real limits (a CAD exporter "
            "writes 0 and 0 when it knows none), make it continuous if it turns without end, or fixed if it never "
            "moves",
        )


def _rates(found: _At, kind: str, limit: Attributes | None) -> Iterator[Finding]:
    """J005 (a continuous joint's <limit> without effort or velocity), J003/J004 (effort and velocity)."""
    if limit is None:
        return
    if kind == "continuous" and (limit.get("effort") is None or limit.get("velocity") is None):
        missing = " and ".join(k for k in ("effort", "velocity") if limit.get(k) is None)
        yield found(
            "J005",
            f"<limit> has no {missing}; urdfdom rejects a limit without them: give effort and velocity, or leave "
            "the <limit> out (a passive continuous joint needs none)",
        )
    if kind not in MOVING:
        return
    for rule, key, unit, then in (
        ("J003", "effort", "N*m or N", "Gazebo applies no force to the joint"),
        ("J004", "velocity", "rad/s or m/s", "Gazebo holds the joint still"),
    ):
        value = number_of(limit, key)
        if value is not None and value < 0:  # pinocchio rejects it (its lower bound, -value, is above it)
            yield found(rule, f"limit {key} is {value:g}; pinocchio rejects a negative one: give one > 0 ({unit})")
        elif value == 0:
            yield found(
                rule, f"limit {key} is 0: {then} (a placeholder?); give the real one > 0 ({unit})", level="warning"
            )
        elif value is None and kind != "continuous":
            yield found(rule, f"<limit> has no {key}; urdfdom rejects it: give one > 0 ({unit})")


def _axis(found: _At, kind: str, joint: Joint) -> Iterator[Finding]:
    """J006 (a zero or unreadable axis), J007 (an axis that is not a unit vector)."""
    if kind not in AXIAL:
        return
    try:
        axis = [float(v) for v in (joint.axis if joint.axis is not None else "1 0 0").split()]
    except ValueError:
        axis = []
    norm = math.hypot(*axis) if len(axis) == 3 else math.nan
    if not math.isfinite(norm) or norm == 0:
        written = joint.axis if joint.axis is not None else ""
        yield found("J006", f"axis {written!r} is zero or unreadable; give a direction such as '0 0 1'")
    elif abs(norm - 1.0) > 1e-6:
        yield found("J007", f"axis has length {norm:.6g}; consumers normalise it, write the unit vector")


def _mimic(found: _At, kind: str, mimic: Mimic | None, types: dict[str, str]) -> Iterator[Finding]:
    """J008: a mimic of itself, of no joint, or between joints that do not move alike."""
    if mimic is None:
        return
    target = mimic.joint or ""
    if target == found.name:
        yield found("J008", "a joint cannot mimic itself")
    elif target not in types:
        yield found("J008", f"mimics {target!r}, which is not a joint of this robot")
    elif types[target] not in MOVING or kind not in MOVING or (types[target] == "prismatic") != (kind == "prismatic"):
        yield found(
            "J008",
            f"mimics {target!r} ({types[target]}) from a {kind} joint; consumers ignore such a mimic (both "
            "must move, and rotate or slide alike): remove it, or fix the joint types",
            level="warning",
        )


def _safety(found: _At, kind: str, limit: Attributes | None, safety: Attributes | None) -> Iterator[Finding]:
    """J010: soft limits outside the hard ones."""
    if safety is None or limit is None or kind not in LIMITED:
        return
    lower, upper = number_of(limit, "lower"), number_of(limit, "upper")
    soft_lower, soft_upper = number_of(safety, "soft_lower_limit"), number_of(safety, "soft_upper_limit")
    if lower is not None and soft_lower is not None and soft_lower < lower:
        yield found("J010", f"soft_lower_limit {soft_lower} is below the hard lower limit {lower}")
    if upper is not None and soft_upper is not None and soft_upper > upper:
        yield found("J010", f"soft_upper_limit {soft_upper} is above the hard upper limit {upper}")
