"""Fleets: ``count`` copies of one robot on a grid, built as a scene's plan directly (``gen-robot fleet``).

The robot spec is read, validated and resolved as a scene's instance spec is (:class:`~.build.RobotSpecs`), and the
copies go through the same checks as a scene's instances (:func:`~.plan.resolve_plan`).
"""

from __future__ import annotations

import math
import shlex
from pathlib import Path

from ..errors import SpecErrors, XacrokitError
from ..load import RawSpec, load_file
from ..model import Origin, Scene
from .build import RobotSpecs, is_scene
from .plan import Planned, ScenePlan, resolve_plan

WORLD = "world"
MAX_FLEET = 1000  # robots: --count beyond this is refused (gen-robot fleet --help); 300 take seconds (benchmarks)


def fleet_scene(spec_path: str | Path, count: int, *, columns: int | None = None, spacing: float = 2.0) -> Scene:
    """``count`` copies of one robot with prefixes r0_ ... r{count-1}_, on a grid in the world (row-major): x along a
    row, ``spacing`` metres apart, ``columns`` to a row (default: a square grid).

    Raises:
        XacrokitError: a count below 1, a spacing that is not a positive length (or one so large that the grid
            leaves the floats), or a scene spec for the robot.
        SpecErrors: the robot spec is unreadable or invalid (located in it).
    """
    if not 1 <= count <= MAX_FLEET:
        raise XacrokitError(f"a fleet has 1 to {MAX_FLEET:,} robots, got count {count:,}")
    if not (spacing > 0 and math.isfinite(spacing)):
        raise XacrokitError(f"the spacing of a fleet must be > 0 m, got {spacing!r}")
    given_columns = columns
    columns = columns or math.ceil(math.sqrt(count))
    robot_raw = load_file(spec_path)
    if is_scene(robot_raw):
        raise XacrokitError(f"{spec_path} is a scene spec; a fleet copies one robot spec (generate the scene itself)")
    fleet = RawSpec(file=f"<fleet of {spec_path}>", data={})  # (locates nothing: no text was written)
    spec_file = Path(spec_path).resolve()
    robot, spec_file, errors, warnings = RobotSpecs().load(fleet, spec_file, spec_file.parent, ("instances", "r0"))
    if robot is None:
        raise SpecErrors(errors)
    planned = []
    for index in range(count):
        row, column = divmod(index, columns)
        origin = Origin(xyz=(column * spacing + 0.0, row * spacing + 0.0, 0.0))
        if not all(math.isfinite(v) for v in origin.xyz):  # (a spacing near the largest float)
            raise XacrokitError(f"the spacing of a fleet is too large: {spacing!r} m puts r{index} at {origin.xyz}")
        planned.append(Planned(f"r{index}", f"r{index}_", WORLD, origin, robot, spec_file))
    command = f"gen-robot fleet {shlex.quote(Path(spec_path).name)} --count {count}"
    if given_columns:
        command += f" --grid {math.ceil(count / given_columns)}x{given_columns}"
    if spacing != 2.0:
        command += f" --spacing {spacing!r}"
    plan = ScenePlan(f"{robot.name}_fleet", WORLD, tuple(planned), tuple(warnings), command=command)
    return resolve_plan(fleet, plan)
