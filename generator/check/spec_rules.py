"""Rules about a spec, which only spec input can show: its DH arms' URDF kinematics (K001), and what gen-robot says
of the spec itself, as findings: values that look like a units mistake (V001), errors (V002), and the values no real
body has that a spec under strict: false keeps (V003)."""

from __future__ import annotations

import math
from collections.abc import Iterable, Iterator
from pathlib import Path
from typing import TYPE_CHECKING

from ..errors import SpecError, XacrokitError
from ..reader.read_robot import ReadRobot
from ..reader.robot_input import RobotInput
from ..shared.transforms import dh_chain
from .findings import Finding, rule_table, severity
from .urdf_document import Doc

if TYPE_CHECKING:
    from ..model import Robot

RULES = rule_table(
    {
        "K001": ("dh-kinematics", "error", "for a spec's DH arms, URDF forward kinematics equal the DH product"),
        "V001": (
            "spec-units",
            "warning",
            "a spec's plain-number angles stay within a turn (joint limits two) and its plain-number lengths (origins, "
            "sizes, DH a and d) within 10 m, and a mass in a shape, a wheel or a DH row's body gives a density between "
            "air's and osmium's (else: degrees, grams or millimetres written without their unit?)",
        ),
        "V002": (
            "spec-valid",
            "error",
            "a spec follows its schema and the rules gen-robot applies (as gen-robot SPEC)",
        ),
        "V003": (
            "spec-as-given",
            "warning",
            "a spec under strict: false says which of its values no real body has (a mass of 0, a tensor that is not "
            "physical, a moving link without mass, a continuous joint without limit, a limit of 0): written as given",
        ),
    }
)

FK_TOLERANCE = 1e-9  # K001: largest difference allowed between URDF and DH transforms (m, rotation entries)


def spec_findings(problems: Iterable[SpecError], rule: str = "V001") -> tuple[Finding, ...]:
    """A spec's warnings (values that look like a units mistake, V001; or, under strict: false, values no real body
    has, V003) or errors (V002) as findings."""
    from ..validate.physics import Implausible  # (heavy: jsonschema)

    found = []
    for e in problems:
        said = "V003" if rule == "V001" and isinstance(e, Implausible) else rule
        found.append(Finding(said, severity(said), "value", e.path, e.message, e.file, e.line, e.column))
    return tuple(found)


def kinematics_rules(doc: Doc, robot: Robot, urdf_text: str) -> Iterator[Finding]:
    """K001: for each DH arm, FK from its parent to its tool frame equals the DH product at sample joint values (the
    URDF's kinematic model as every command builds it, on the view check already read)."""
    import numpy as np  # (heavy: numpy)

    try:
        model = ReadRobot(RobotInput(Path(doc.file or "robot.urdf")), "spec", urdf_text, doc.view).kinematics
    except XacrokitError:  # (beyond what the kinematics take: more than 150 joints; no DH arm is that long)
        return
    rng = np.random.default_rng(0)
    for arm in robot.arms:
        worst = 0.0
        for trial in range(8):
            values = [
                0.0 if row.type == "fixed" or trial == 0 else float(rng.uniform(-math.pi, math.pi)) for row in arm.rows
            ]
            q = model.configuration(
                {row.name: v for row, v in zip(arm.rows, values, strict=True) if row.type != "fixed"}
            )
            placed = model.placed(q)
            got = (placed[model.frame_id(arm.parent)].inverse() * placed[model.frame_id(arm.tool)]).homogeneous
            want = dh_chain(arm.rows, values, arm.convention, arm.origin, arm.tool_origin)
            worst = max(worst, float(np.abs(got - want).max()))
        if not worst <= FK_TOLERANCE:
            yield doc.finding(
                "K001",
                "link",
                arm.tool,
                f"arm {arm.name!r}: URDF forward kinematics differ from the DH "
                f"product by up to {worst:.3g} (m / rotation entries)",
            )
