"""Inverse kinematics on a robot read once: :class:`IkSolver` is made once per robot, frame and target frame (the
closed form recognised, the chain's joints found, the numeric chain built) and then solves any number of targets.

A chain the closed form knows (:func:`.arm_geometry.recognise`) is solved by it: every branch whose subproblems
have exact roots, each given by its values nearest 0 (or nearest ``near``) within the joints' limits, with the count
of its 2-pi equivalents within them, and checked on the robot with pinocchio (one posed between 1e-9 and POLISHABLE
off, as lines parallel only within the tolerance leave it, is polished by the numeric solver); a branch no value of
which is within the limits is counted, not given. Without ``every`` the candidates are checked nearest first (the
sum of the joints' distances from ``near``; two as near to 1e-9, as a mirror pair can be, the lower values first,
compared joint by joint from joint 1: the numeric search's order) and the first that reaches is the answer. Any
other chain (and a target the closed form does not reach) is searched numerically (:mod:`.inverse`): from ``near``
when given, the NEAREST of ATLAS configurations posed once per solver, then Sobol starts over the limits, until one
reaches (FIRST_STARTS at most) or, for every branch, STARTS more and on until one reaches; the result says how many
ran, and that the list may be incomplete. A chain whose free joints move its frame in fewer directions than the
target constrains (6 for a pose, 3 for a position) at every configuration, and in fewer than they are, has a
continuum of solutions at every target it reaches (a waist and a shoulder, each three axes meeting at a point, move a
hand in 5 of 6): each solution found is said singular, on a continuum.
"""

from __future__ import annotations

import dataclasses
import functools
import itertools
import math
import operator
from collections.abc import Callable, Sequence
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from ..errors import XacrokitError
from ..reader.kinematic_model import KinematicJoint, KinematicModel
from .analytic import Branch, branches
from .arm_geometry import ClosedForm, arm_lines, recognise
from .branch_names import branch_name
from .inverse import Chain, closest_reach, directions, distinct, solve, starts
from .reposed import CLOSE, Reposer

REACHED = 1e-9  # m, or the pose error's norm: a solution farther from the target than this is not one
STARTS = 32  # numeric starts for every branch (--all)
FIRST_STARTS = 256  # numeric starts at most until one reaches (the default; 64 left 2% of general 6R arms unsolved)
ATLAS = 1024  # configurations posed once per solver, the nearest of which start a numeric search
NEAREST = 4  # of them, tried first
PROBES = 8  # spread configurations at which the directions the chain moves its frame in are counted (once a solver)
TURNS_WEIGHT = 0.25  # of the arm's reach: metres per unit of rotation matrices' difference when choosing a start
# (the wrist's last joints turn the frame in a few steps where the position needs the whole arm: on the Panda, 0.25
# left 22% of 1,000 random targets needing a second start where 1.0 left 29%)
POLISHABLE = 1e-3  # m or rad: a branch the closed form brought this near is polished; farther, it is not one
TURN = 2 * math.pi
LIMIT_SLACK = 1e-12  # rad: a value this far beyond a limit is at it
NUMERIC = "numeric (damped least squares)"
_ROOT = ((1.0, 0.0, 0.0, 0.0), (0.0, 1.0, 0.0, 0.0), (0.0, 0.0, 1.0, 0.0))  # (a pose's rows at the root: no turn)
_BOTTOM = [0.0, 0.0, 0.0, 1.0]
ROTATION_SLACK = 1e-6  # a target's R^T R this near the identity, determinant +1 (as validate.quantities.ORTHONORMAL)


@dataclass(frozen=True)
class Solution:
    """Joint values (every joint one sets, by name; the joints that do not move the frame at their rest value), the
    pose error left, and for a closed-form branch its name, how many values 2 pi apart within the limits put the
    frame there too (``equivalents``, this one included; 0 when a continuous joint makes them endless), and the
    singularity it lies on ("" when none)."""

    values: dict[str, float]
    error: float
    branch: str = ""
    equivalents: int = 1
    singular: str = ""


@dataclass(frozen=True)
class Solutions:
    """What ``ik`` found: the solutions, or when there is none, the closest reach; the method, the numeric starts
    run (0 for the closed form), whether the list is every branch there is (``complete``; a branch whose solutions
    are a continuum is given once, said singular), and the closed-form branches left out because no value of theirs
    is within the joints' limits."""

    frame: str
    in_frame: str
    joints: list[str]
    solutions: list[Solution]
    closest: Solution | None
    method: str = NUMERIC
    starts: int = 0
    complete: bool = False
    outside_limits: int = 0
    branches: int = 0  # (the closed form's branches within the limits, of which the solutions are all or one)


_new = object.__new__


def _solution(values: dict[str, float], error: float, branch: str, equivalents: int, singular: str) -> Solution:
    """``Solution(values, error, branch, equivalents, singular)``, its fields written at once: a frozen dataclass's
    __init__ sets each through object.__setattr__, a microsecond a branch (the same object: tested)."""
    made = _new(Solution)
    made.__dict__.update(values=values, error=error, branch=branch, equivalents=equivalents, singular=singular)
    return made


def _closed_solutions(solver: IkSolver, found: list[Solution], complete: bool, outside: int, count: int) -> Solutions:
    """The closed form's ``Solutions`` (as :func:`_solution` makes a Solution: the same object, tested)."""
    made = _new(Solutions)
    made.__dict__.update(
        frame=solver.frame,
        in_frame=solver.in_frame,
        joints=list(solver.names),
        solutions=found,
        closest=None,
        method=solver.method,
        starts=0,
        complete=complete,
        outside_limits=outside,
        branches=count,
    )
    return made


class MovingFrame(XacrokitError):
    """The frame a target is given in (``frame``) moves with a joint (``joint``); the command line says which option
    named it."""

    def __init__(self, frame: str, joint: str) -> None:
        super().__init__(f"frame {frame!r} moves with joint {joint!r}; give a frame fixed to the root")
        self.frame, self.joint = frame, joint


@dataclass
class IkSolver:
    """Inverse kinematics of ``frame`` with targets in ``in_frame`` (a frame fixed to the root) on a kinematic
    model; :meth:`solve` takes a target as a 4x4 pose."""

    model: KinematicModel
    frame: str
    in_frame: str
    form: ClosedForm | None = field(init=False)
    chain: Chain = field(init=False)
    rest: np.ndarray = field(init=False)
    base: Any = field(init=False)
    atlas: tuple[np.ndarray, np.ndarray, np.ndarray, tuple[np.ndarray, np.ndarray]] | None = field(
        init=False, default=None
    )
    reach: float = field(init=False, default=1.0)
    ranges: list[tuple[float, float] | None] = field(init=False, default_factory=list)
    spread: list[np.ndarray] | None = field(init=False, default=None)
    moves: np.ndarray = field(init=False)
    reposer: Reposer | None = field(init=False, default=None)
    names: list[str] = field(init=False, default_factory=list)
    rest_values: list[float] = field(init=False, default_factory=list)  # (the rest pose, plain floats)
    centres: list[float] = field(init=False, default_factory=list)  # (the closed form's chain at rest)
    bounds: list[tuple[float, float, float, float] | None] = field(init=False, default_factory=list)  # (_nearest_turns)
    within: tuple[float, ...] = field(init=False, default=())  # (each chain joint's limits, -inf and inf if none)
    slack_bounds: tuple[float, ...] | None = field(init=False, default=None)  # (_turns_count's)
    base_rows: tuple[tuple[float, ...], ...] | None = field(init=False, default=None)  # (None: the root's axes)
    whole: bool = field(init=False, default=False)  # (the closed form's chain is every joint one sets, in order)
    continua: dict[bool, str] = field(init=False, default_factory=dict)  # (:meth:`_continuum`, by position_only)

    def __post_init__(self) -> None:
        model = self.model
        target, base = model.frame_id(self.frame), model.frame_id(self.in_frame)
        if model.model.frames[base].parentJoint != 0:
            raise MovingFrame(self.in_frame, model.model.names[model.model.frames[base].parentJoint])
        self.form = recognise(arm_lines(model, target))
        chain_joints = [model.joints[k] for k in self.form.lines.joints] if self.form is not None else []
        self.ranges = [j.limits if j.kind != "continuous" else None for j in chain_joints]
        self.chain = numeric_chain(model, target)
        self.rest = np.clip(np.zeros(len(model.joints)), self.chain.lower, self.chain.upper)
        path = {int(j) for j in model.model.supports[model.model.frames[target].parentJoint]}
        moved = {int(model.model.getJointId(name)) for name in self.chain_names(path)}
        self.moves = np.array([int(model.model.getJointId(j.name)) in moved for j in model.joints])
        self.base = model.placed(model.configuration({}))[base].copy()
        self.reach = float(np.linalg.norm(model.placed(model.configuration({}))[target].translation))
        self.names, self.rest_values = [j.name for j in model.joints], self.rest.tolist()
        if self.form is not None:
            self.reposer = Reposer.of(model, target, self.form.lines.joints, self.rest)
            self.centres = [self.rest_values[k] for k in self.form.lines.joints]
            self.bounds = [None if r is None else (r[0] - LIMIT_SLACK, r[1] + LIMIT_SLACK, *r) for r in self.ranges]
            self.within = tuple(v for r in self.ranges for v in (r if r is not None else (-math.inf, math.inf)))
            ends = [b[:2] for b in self.bounds if b is not None]
            self.slack_bounds = tuple(v for b in ends for v in b) if len(ends) == len(self.bounds) else None
            rows = tuple(tuple(row) for row in self.base.homogeneous[:3].tolist())
            signs = all(math.copysign(1.0, v) > 0 for row in rows for v in row)  # (no -0.0: its sums differ)
            self.base_rows = None if rows == _ROOT and signs else rows
            self.whole = list(self.form.lines.joints) == list(range(len(self.names)))

    def chain_names(self, path: set[int]) -> set[str]:
        """The joints one sets that move a frame whose path from the root holds the pinocchio joints ``path``: those
        on it, and the leaders of the mimic joints on it."""
        names = {self.model.model.names[j] for j in path}
        return {*names, *(f.leader for f in self.model.followers if f.joint.name in names)}

    @functools.cached_property
    def method(self) -> str:
        """'closed form (three parallel axes)', 'closed form (spherical wrist)' or the numeric search's name."""
        return f"closed form ({self.form.kind})" if self.form is not None else NUMERIC

    def solve(
        self,
        target: np.ndarray | Sequence[Sequence[float]],
        *,
        every: bool = False,
        position_only: bool = False,
        near: Sequence[float] | None = None,
    ) -> Solutions:
        """The joint values that put the frame at ``target`` (4x4, T_IN_FRAME; its rotation ignored when
        ``position_only``): every branch (``every``), else the one nearest ``near`` (joint values in the joints'
        order; default the rest pose)."""
        matrix = np.asarray(target, dtype=float)
        shape = matrix.shape
        if len(shape) == 2 and shape[1] == 4 and shape[0] in (3, 4):  # (its rows read once: checked, then posed)
            read: list[list[float]] = matrix.tolist()
            rows, problem = read, _rows_problem(read, position_only=position_only)
        else:
            rows, problem = None, target_problem(matrix, position_only=position_only)
        if problem:
            raise XacrokitError(f"the target {problem}")
        closed = self.form is not None and not position_only
        pose = self._pose(rows) if closed and rows is not None else None
        # (pinocchio's goal: made only when the closed form does not answer, or the target is no 4x4 of finite numbers)
        goal: Any = self._goal(matrix) if pose is None else None
        seed = self.rest if near is None else np.clip(np.asarray(near, dtype=float), self.chain.lower, self.chain.upper)
        if closed:
            pose = goal.homogeneous.tolist() if pose is None else pose
            found, outside, count = self._closed_form(matrix, pose, every=every, seed=seed)
            if found:
                return _closed_solutions(self, found, len(found) == count, outside, count)
        else:
            outside = 0
        goal = self._goal(matrix) if goal is None else goal
        first = [seed] if near is not None else []
        seeds = first + self._nearest(goal, position_only=position_only)
        searched = self._numeric(goal, every=every, position_only=position_only, seeds=seeds)
        searched.solutions.sort(key=lambda s: _order(s.values, seed, self.model.joints))  # (nearest first)
        return dataclasses.replace(searched, outside_limits=outside)  # (the closed form's, when all were outside)

    def _goal(self, matrix: np.ndarray) -> Any:
        """The target in the root's frame: pinocchio's SE3 (what the numeric search and the check measure)."""
        import pinocchio as pin  # (heavy: pinocchio)

        return self.base * pin.SE3(matrix[:3, :3], matrix[:3, 3])

    def _pose(self, rows: list[list[float]]) -> list[list[float]] | None:
        """:meth:`_goal`'s pose as rows of floats without making it (the closed form and the reposer read floats):
        the base's rows times the target's (``rows``, a 4x4 or 3x4's), summed as pinocchio sums them (with the root's
        axes, to the zero's sign: a row with a 0 in it); None unless a 4x4 of finite numbers whose sums are finite
        (pinocchio's then, as it takes any other)."""
        if len(rows) != 4:
            return None
        m0, m1, m2, _ = rows
        if not math.isfinite(sum(m0) + sum(m1) + sum(m2)):
            return None
        base = self.base_rows
        if base is None and not (0.0 in m0 or 0.0 in m1 or 0.0 in m2):
            return rows  # (1 x + 0 y + 0 z is x but for the sign of a 0)
        composed = []
        for b0, b1, b2, b3 in base or _ROOT:
            composed.append(
                [b0 * m0[0] + b1 * m1[0] + b2 * m2[0], b0 * m0[1] + b1 * m1[1] + b2 * m2[1]]
                + [b0 * m0[2] + b1 * m1[2] + b2 * m2[2], b0 * m0[3] + b1 * m1[3] + b2 * m2[3] + b3]
            )
        return [*composed, _BOTTOM]

    def equivalent_values(self, solution: Solution) -> list[dict[str, float]]:
        """The other values of a closed-form ``solution``'s chain joints, whole turns apart and within the limits
        (the chain's joints only; a continuous joint's turns are endless and not listed)."""
        if self.form is None:
            return []
        joints = self.model.joints
        options = []
        for k in self.form.lines.joints:
            value, limits = solution.values[joints[k].name], joints[k].limits
            if limits is None or joints[k].kind == "continuous":
                options.append([value])
                continue
            first = math.ceil((limits[0] - LIMIT_SLACK - value) / (2 * math.pi))
            last = math.floor((limits[1] + LIMIT_SLACK - value) / (2 * math.pi))
            options.append([value + 2 * math.pi * t for t in range(first, last + 1)])
        names = [joints[k].name for k in self.form.lines.joints]
        combos = itertools.product(*options)
        return [dict(zip(names, combo, strict=True)) for combo in combos if combo != tuple(options_of(solution, names))]

    def _closed_form(
        self, matrix: np.ndarray, pose: list[list[float]], *, every: bool, seed: np.ndarray
    ) -> tuple[list[Solution], int, int]:
        """The closed form's solutions (every branch, or the one nearest ``seed``) for the target ``matrix``, its pose
        in the root's frame ``pose`` (rows), the branches outside the limits and the branches within them."""
        assert self.form is not None  # (only called with one)
        (r00, r01, r02, x), (r10, r11, r12, y), (r20, r21, r22, z), _ = pose
        rotation = ((r00, r01, r02), (r10, r11, r12), (r20, r21, r22))
        centres = self.centres if seed is self.rest else [float(seed[k]) for k in self.form.lines.joints]
        found = branches(self.form, rotation, (x, y, z), exact_only=True)  # (_candidates keeps no other)
        candidates, outside = _candidates(found, (self.within, self.bounds), centres)
        if not every:  # (checked nearest first: the first that reaches is the answer; ties, the lower values)
            _nearest_first(candidates)
        solutions: list[Solution] = []
        for wrapped, branch, _, whole in candidates:
            reached = self._reposed(matrix, pose, wrapped)
            if reached is not None:
                named = branch_name(self.form, reached[1], branch.roots)
                if whole:  # (each value its centre plus a remainder: what _turns_count would take)
                    count = _turns_of(wrapped, self.slack_bounds)
                else:
                    count = _turns_count(branch.values, self.slack_bounds, centres)
                solutions.append(_solution(reached[0], reached[2], named, count, branch.singular))
                if not every:
                    break
        return solutions, outside, len(candidates)

    def _reposed(
        self, matrix: np.ndarray, pose: list[list[float]], wrapped: Sequence[float]
    ) -> tuple[dict[str, float], tuple[float, ...], float] | None:
        """A branch's values (every joint, by name; and the chain's), re-posed on the robot, and its pose error; None
        when it does not reach. The reposer's error first; a branch it leaves further than CLOSE is measured by
        :meth:`_checked` (and polished there when near)."""
        assert self.form is not None  # (only called with one)
        chain = self.form.lines.joints
        w0, w1, w2, w3, w4, w5 = wrapped
        wrapped = (w0 + 0.0, w1 + 0.0, w2 + 0.0, w3 + 0.0, w4 + 0.0, w5 + 0.0)  # (-0.0 + 0.0 is 0.0: no "-0")
        if self.reposer is not None:
            error = self.reposer.error(wrapped, pose)
            if error <= CLOSE and self.whole:  # (the chain is every joint: nothing to place among the others)
                return dict(zip(self.names, wrapped, strict=True)), wrapped, error
            if error <= CLOSE:
                full = self.rest_values.copy()
                for k, value in zip(chain, wrapped, strict=True):
                    full[k] = value
                return dict(zip(self.names, full, strict=True)), wrapped, error
        values = self.rest.copy()
        values[list(chain)] = wrapped
        reached = self._checked(self._goal(matrix), values)
        if reached is None:
            return None
        return _named(self.model.joints, reached[0]), tuple(float(reached[0][k]) for k in chain), reached[1]

    def _checked(self, goal: Any, values: np.ndarray) -> tuple[np.ndarray, float] | None:
        """A branch's values and pose error on the robot (pinocchio), polished when the closed form came near (lines
        parallel or meeting only within TOLERANCE, a tangency); None when it does not reach."""
        error = _error(self.chain, goal, values)
        if REACHED < error < POLISHABLE:
            polished, error = solve(self.chain, goal, position_only=False, start=values, iterations=20)
            values = polished if error <= REACHED else values
        return (values, error) if error <= REACHED else None

    def _nearest(self, goal: Any, *, position_only: bool) -> list[np.ndarray]:
        """The NEAREST of ATLAS configurations (spread over the limits, posed once per solver) whose frame is
        closest to ``goal`` (the squared metres plus the squared rotation matrices' difference times TURNS_WEIGHT
        of the arm's reach, unless ``position_only``): starts a few steps from a solution. (The squared distance less
        the goal's own square is |a|^2 - 2 a.b, a the atlas' row: one matrix-vector product over the atlas made
        with its squares; of those as near, the lower index first: the rest pose.)"""
        weight = TURNS_WEIGHT * max(self.reach, 0.1)
        if self.atlas is None:
            self.atlas = _atlas(self.chain, self.rest, self.moves, weight)
        values, positions, poses, squares = self.atlas
        if position_only:
            score = squares[0] - 2.0 * (positions @ goal.translation)
        else:
            score = squares[1] - 2.0 * (poses @ np.concatenate((goal.translation, weight * goal.rotation.reshape(9))))
        if len(score) > NEAREST:  # (those within the NEAREST-th's score: argpartition leaves ties in any order)
            within = np.flatnonzero(score <= score[np.argpartition(score, NEAREST - 1)[:NEAREST]].max()).tolist()
        else:
            within = list(range(len(score)))
        return [values[k] for k in sorted(within, key=lambda k: (score[k], k))[:NEAREST]]

    def _numeric(self, goal: Any, *, every: bool, position_only: bool, seeds: list[np.ndarray]) -> Solutions:
        found: list[tuple[np.ndarray, float]] = []
        ran, reached_one = 0, False
        if self.spread is None:  # (drawn once per solver: scipy's Sobol costs milliseconds a draw)
            spread = starts(self.chain, self.rest, FIRST_STARTS)
            self.spread = [np.where(self.moves, start, self.rest) for start in spread]  # (the others stay at rest)
        continuum = self._continuum(position_only=position_only)
        for start in [*seeds, *self.spread]:
            ran += 1
            values, error = solve(self.chain, goal, position_only=position_only, start=start)
            found.append((values, error))
            reached_one = reached_one or error <= REACHED
            if reached_one and (not every or ran >= len(seeds) + STARTS):
                break  # (every branch: STARTS starts, and on until one reaches, as the first solution's search)
        if not any(math.isfinite(error) for _, error in found):
            raise XacrokitError("ik cannot search: the pose error is beyond what a float holds at every start")
        reached = distinct([f for f in found if f[1] <= REACHED])
        joints = self.model.joints
        solutions = [Solution(_named(joints, v), e, singular=continuum) for v, e in reached]
        closest = None
        if not solutions:
            values, error = closest_reach(self.chain, goal, position_only=position_only, found=found)
            closest = Solution(_named(joints, values), error)
        names = [j.name for j in joints]  # (a search's list may be incomplete: a continuum may have parts apart)
        return Solutions(self.frame, self.in_frame, names, solutions, closest, NUMERIC, ran, False, 0)

    def _continuum(self, *, position_only: bool) -> str:
        """What every solution lies on ("" when nothing) when the chain's free joints (those with room between their
        limits) move the frame in fewer directions than the target constrains (6 for a pose, 3 for a position) at each
        of PROBES spread configurations, and in fewer than they are: every target it reaches then has a continuum of
        solutions (maybe in parts apart: the search's samples are listed, the list may be incomplete). A regular arm
        at a singular target is not such a chain. Counted once a solver (:func:`.inverse.directions`)."""
        if position_only not in self.continua:
            assert self.spread is not None  # (drawn by the search first)
            needed, what = (3, "position") if position_only else (6, "pose")
            free = self.moves & (self.chain.upper > self.chain.lower)
            found = directions(self.chain, self.spread[1 : 1 + PROBES], position_only=position_only, free=free)
            said = ""
            if found is not None and found < needed and found < int(free.sum()):
                said = (
                    f"on a continuum of solutions: the joints move {self.frame} in only {found} of the {needed} "
                    f"directions of a {what} at any configuration"
                )
            self.continua[position_only] = said
        return self.continua[position_only]


def target_problem(matrix: np.ndarray, *, position_only: bool) -> str:
    """What makes ``matrix`` no pose to solve for ("" when it is one): a 4x4 (or its 3x4 top) of finite numbers whose
    top-left 3x3 is a rotation (columns of unit length at right angles, to ROTATION_SLACK, determinant +1; not
    asked when ``position_only``) and whose bottom row is 0 0 0 1 (to 1e-9)."""
    if matrix.ndim != 2 or matrix.shape[0] not in (3, 4) or matrix.shape[1] != 4:
        return f"is a {'x'.join(map(str, matrix.shape))} array; give a 4x4 pose (or its top 3x4)"
    return _rows_problem(matrix.tolist(), position_only=position_only)


def _rows_problem(rows: list[list[float]], *, position_only: bool) -> str:
    """:func:`target_problem` of a 4x4 or 3x4's rows (a solve reads them once, for this and the pose)."""
    if not math.isfinite(sum(rows[0]) + sum(rows[1]) + sum(rows[2])) and not all(
        math.isfinite(v) for v in (*rows[0], *rows[1], *rows[2])
    ):  # (a finite sum says it at once: a solve asks this of every target)
        return "holds a number that is not finite (nan or inf); give a 4x4 pose of finite numbers"
    if len(rows) == 4 and rows[3] != _BOTTOM:  # (a pose's own bottom row told by one comparison)
        x, y, z, w = rows[3]
        if not (abs(x) <= 1e-9 and abs(y) <= 1e-9 and abs(z) <= 1e-9 and abs(w - 1.0) <= 1e-9):  # (a nan fails)
            return f"has the bottom row {rows[3]}; a pose's is [0, 0, 0, 1]"
    if position_only:
        return ""
    (a, b, c, _), (d, e, f, _), (g, h, i, _) = rows[0], rows[1], rows[2]
    g0, g1, g2 = a * a + d * d + g * g - 1.0, b * b + e * e + h * h - 1.0, c * c + f * f + i * i - 1.0
    g3, g4, g5 = a * b + d * e + g * h, a * c + d * f + g * i, b * c + e * f + h * i
    determinant = a * (e * i - f * h) - b * (d * i - f * g) + c * (d * h - e * g)
    high = ROTATION_SLACK
    low = -high
    if determinant > 0.0 and low <= g0 <= high and low <= g1 <= high and low <= g2 <= high:
        if low <= g3 <= high and low <= g4 <= high and low <= g5 <= high:
            return ""  # (every one within the slack: the largest is, without the calls)
    gram = (g0, g1, g2, g3, g4, g5)
    off = max(map(abs, gram))
    if not off <= ROTATION_SLACK or determinant <= 0.0:
        return (
            f"has a top-left 3x3 that is no rotation (its columns' lengths and angles off by up to {off:.3g}, "
            f"determinant {determinant:.6g}); give a rotation matrix, or position_only"
        )
    return ""


def numeric_chain(model: KinematicModel, frame: int) -> Chain:
    """The numeric solver's chain: every joint one sets, with the velocity columns it drives (a mimic joint's column
    joins its leader's) as a matrix made once; a joint that does not move ``frame`` keeps its start (its columns are
    zero there)."""
    columns = {j.name: [(j.v_index, 1.0)] for j in model.joints}
    for follower in model.followers:
        columns[follower.leader].append((follower.joint.v_index, follower.multiplier))
    lower = np.array([j.limits[0] if j.limits else -np.pi for j in model.joints])
    upper = np.array([j.limits[1] if j.limits else np.pi for j in model.joints])
    selection = np.zeros((model.model.nv, len(model.joints)))
    with np.errstate(over="ignore", invalid="ignore"):  # (a mimic's multiplier of 1e308 is judged where it is used)
        for column, drives in enumerate(columns.values()):
            for v, multiplier in drives:
                selection[v, column] += multiplier
    chain = Chain(model.model, frame, list(columns.values()), lower, upper, _configuration(model), model.data)
    return dataclasses.replace(chain, selection=selection)


def _configuration(model: KinematicModel) -> Callable[[np.ndarray], np.ndarray]:
    """pinocchio's q of the joints' values in their order: :meth:`KinematicModel.configuration`'s convention (its
    twin), written with index arrays made once: the solver makes q thousands of times a solve."""
    import pinocchio as pin  # (heavy: pinocchio)

    neutral = [float(v) for v in pin.neutral(model.model)]
    places = [(k, j.q_index, j.kind == "continuous") for k, j in enumerate(model.joints)]
    column = {j.name: k for k, j in enumerate(model.joints)}
    followers = [(f, column[f.leader], f.joint.q_index, f.joint.kind == "continuous") for f in model.followers]

    def configuration(values: np.ndarray) -> np.ndarray:
        q = list(neutral)  # (plain floats: numpy's indexing costs more than the loop on a dozen numbers)
        given = values.tolist()
        for k, index, turns in places:
            if turns:
                q[index], q[index + 1] = math.cos(given[k]), math.sin(given[k])
            else:
                q[index] = given[k]
        for follower, leader, index, turns in followers:  # (its value checked: FollowerValueError when it overflows)
            value = follower.value(given[leader])
            if turns:
                q[index], q[index + 1] = math.cos(value), math.sin(value)
            else:
                q[index] = value
        return np.array(q)

    return configuration


def _atlas(
    chain: Chain, rest: np.ndarray, moves: np.ndarray, weight: float
) -> tuple[np.ndarray, np.ndarray, np.ndarray, tuple[np.ndarray, np.ndarray]]:
    """The rest pose and ATLAS - 1 configurations spread over the chain's limits (Sobol, a fixed seed), the frame's
    position at each and its pose (the position, then the rotation flattened times ``weight``, m per rad), and
    their squared lengths: a target at the rest pose starts there (and is answered with it)."""
    import pinocchio as pin  # (heavy: pinocchio)

    values = np.where(moves, np.array(starts(chain, rest, ATLAS, seed=1)), rest)  # (joints that move the frame)
    poses = np.empty((len(values), 12))
    for k, row in enumerate(values):
        pin.framesForwardKinematics(chain.model, chain.data, chain.configuration(row))
        placed = chain.data.oMf[chain.frame]
        poses[k, :3], poses[k, 3:] = placed.translation, weight * placed.rotation.reshape(9)
    positions = np.ascontiguousarray(poses[:, :3])
    return values, positions, poses, ((positions * positions).sum(axis=1), (poses * poses).sum(axis=1))


def _error(chain: Chain, goal: Any, values: np.ndarray) -> float:
    import pinocchio as pin  # (heavy: pinocchio)

    pin.framesForwardKinematics(chain.model, chain.data, chain.configuration(values))
    return float(np.linalg.norm(pin.log6(goal.actInv(chain.data.oMf[chain.frame])).vector))


Candidate = tuple[
    tuple[float, ...], Branch, float, bool
]  # (values, branch, distance, whether the turns were whole ones)


def _candidates(
    found: list[Branch],
    bounds: tuple[tuple[float, ...], Sequence[tuple[float, float, float, float] | None]],
    centres: Sequence[float],
) -> tuple[list[Candidate], int]:
    """The exact branches by their values nearest ``centres`` (:func:`_nearest_turns`), each once (one met twice,
    whole turns apart, is left out: :func:`_distinct`), with their distance from ``centres`` and whether each value
    is its centre plus the remainder of its difference (True: :func:`_turns_of` counts its equivalents); and how
    many have no value within the limits. ``bounds``: the six joints' limits (flat, -inf and inf for a continuous
    joint) and their :func:`_nearest_turns` bounds. (The common case written out for the six joints: centres at 0
    and every value within half a turn of 0 and within the limits: the values as they are, but for a zero's sign,
    which :meth:`IkSolver._reposed` takes off; else :func:`_turned`.)"""
    candidates: list[Candidate] = []
    keys: list[float] = []  # (each candidate's joints 3 and 5 from their centres, summed: the duplicates' test)
    outside = 0
    l0, h0, l1, h1, l2, h2, l3, h3, l4, h4, l5, h5 = bounds[0]
    zero = not any(centres)
    remainder, low, half, turn = math.remainder, -_HALF, _HALF, TURN
    # (every value within half a turn of 0 is within the limits: the six tests once a target, not once a branch)
    wide = l0 <= low and l1 <= low and l2 <= low and l3 <= low and l4 <= low and l5 <= low
    wide = wide and h0 >= half and h1 >= half and h2 >= half and h3 >= half and h4 >= half and h5 >= half
    for branch in found:
        values, _, exact, _ = branch
        if not exact:  # (a subproblem without an exact root: this branch's triangle does not close)
            continue
        if zero:  # (each value's remainder, taken only when it is more than half a turn from 0)
            v0, v1, v2, v3, v4, v5 = values
            v0 = v0 if low <= v0 <= half else remainder(v0, turn)
            v1 = v1 if low <= v1 <= half else remainder(v1, turn)
            v2 = v2 if low <= v2 <= half else remainder(v2, turn)
            v3 = v3 if low <= v3 <= half else remainder(v3, turn)
            v4 = v4 if low <= v4 <= half else remainder(v4, turn)
            v5 = v5 if low <= v5 <= half else remainder(v5, turn)
            if wide or (
                l0 <= v0 <= h0
                and l1 <= v1 <= h1
                and l2 <= v2 <= h2
                and l3 <= v3 <= h3
                and l4 <= v4 <= h4
                and l5 <= v5 <= h5
            ):
                distance = abs(v0) + abs(v1) + abs(v2) + abs(v3) + abs(v4) + abs(v5)
                candidates.append(((v0, v1, v2, v3, v4, v5), branch, distance, True))
                keys.append(v2 + v4)
                continue
            turned = _wrapped_within(values, bounds[1], centres)  # (what _turned comes to when the remainders fail)
        else:
            turned = _turned(values, bounds, centres)
        if turned is None:
            outside += 1
            continue
        candidates.append((turned[0], branch, turned[1], turned[2]))
        keys.append(turned[3])
    return (_distinct(candidates) if _close_pair(keys) else candidates), outside


def _turned(
    values: tuple[float, ...],
    bounds: tuple[tuple[float, ...], Sequence[tuple[float, float, float, float] | None]],
    centres: Sequence[float],
) -> tuple[tuple[float, ...], float, bool, float] | None:
    """One branch's values turned as :func:`_candidates` takes them: each its centre plus the remainder of its
    difference (a difference within half a turn is its own, taken without the call) when all are within the
    limits, else :func:`_nearest_turns`'; with their distance from the centres, whether they are the first kind,
    and joints 3 and 5's differences from their centres, summed (:func:`_close_pair`'s key). None: no value within
    the limits."""
    l0, h0, l1, h1, l2, h2, l3, h3, l4, h4, l5, h5 = bounds[0]
    c0, c1, c2, c3, c4, c5 = centres
    v0, v1, v2, v3, v4, v5 = values
    remainder = math.remainder
    d0, d1, d2, d3, d4, d5 = v0 - c0, v1 - c1, v2 - c2, v3 - c3, v4 - c4, v5 - c5
    if not (-_HALF <= d0 <= _HALF and -_HALF <= d1 <= _HALF and -_HALF <= d2 <= _HALF):
        d0, d1, d2 = remainder(d0, TURN), remainder(d1, TURN), remainder(d2, TURN)
    if not (-_HALF <= d3 <= _HALF and -_HALF <= d4 <= _HALF and -_HALF <= d5 <= _HALF):
        d3, d4, d5 = remainder(d3, TURN), remainder(d4, TURN), remainder(d5, TURN)
    w0, w1, w2, w3, w4, w5 = c0 + d0, c1 + d1, c2 + d2, c3 + d3, c4 + d4, c5 + d5
    if l0 <= w0 <= h0 and l1 <= w1 <= h1 and l2 <= w2 <= h2 and l3 <= w3 <= h3 and l4 <= w4 <= h4 and l5 <= w5 <= h5:
        distance = abs(w0 - c0) + abs(w1 - c1) + abs(w2 - c2) + abs(w3 - c3) + abs(w4 - c4) + abs(w5 - c5)
        return (w0, w1, w2, w3, w4, w5), distance, True, d2 + d4
    return _wrapped_within(values, bounds[1], centres)


def _wrapped_within(
    values: tuple[float, ...], bounds: Sequence[tuple[float, float, float, float] | None], centres: Sequence[float]
) -> tuple[tuple[float, ...], float, bool, float] | None:
    """:func:`_turned` of values some remainder of which is beyond the limits: :func:`_nearest_turns`' values."""
    wrapped, distance = _nearest_turns(values, bounds, centres)
    if not wrapped:
        return None
    remainder = math.remainder
    return (
        tuple(wrapped),
        distance,
        False,
        remainder(wrapped[2] - centres[2], TURN) + remainder(wrapped[4] - centres[4], TURN),
    )


_HALF = TURN / 2  # (a difference this near 0 is its own remainder: math.remainder(d, TURN) == d, exactly)
_NEAR = 3e-6  # rad: keys farther apart than this (less whole turns) are of branches apart at joint 3 or 5
# (the duplicates' test below takes two within 1e-6 at each: their keys within 2e-6, and a rounding more)


def _close_pair(keys: list[float]) -> bool:
    """Whether two of the keys (joints 3 and 5 from their centres, each within half a turn, summed) are within _NEAR
    of each other, whole turns apart or not: else no two candidates are one branch (two branches of one target
    differ at joint 3, or share it and differ at joint 5: a spherical wrist's flip), and :func:`_distinct` has
    nothing to do."""
    if len(keys) < 2:
        return False
    low, half, turn, near = -_HALF, _HALF, TURN, _NEAR
    ordered = sorted([k - turn if k > half else k + turn if k < low else k for k in keys])
    previous = ordered[-1] - turn
    for value in ordered:
        if value - previous <= near:
            return True
        previous = value
    return False


def _distinct(candidates: list[Candidate]) -> list[Candidate]:
    """The candidates without one met twice, whole turns apart in every joint (to 1e-6), the first one kept."""
    kept: list[Candidate] = []
    remainder = math.remainder
    for candidate in candidates:
        wrapped = candidate[0]
        for other in kept:  # (two branches differ at joint 3 or 5, but for the shoulder's)
            apart = wrapped[2] - other[0][2]
            if _APART < apart < _TURN_LESS or -_TURN_LESS < apart < -_APART:
                continue  # (joint 3 more than 1e-6 from a whole turn apart, told without a call)
            if (
                abs(remainder(apart, TURN)) < 1e-6
                and abs(remainder(wrapped[4] - other[0][4], TURN)) < 1e-6
                and _same_turns(wrapped, other[0])
            ):
                break
        else:
            kept.append(candidate)
    return kept


_APART, _TURN_LESS = 2e-6, TURN - 2e-6  # (a difference between them is more than 1e-6 from any whole turn)


def _nearest_first(candidates: list[Candidate]) -> None:
    """Sorted in the order the first solution is looked for in: nearest first, two as near (the distances equal to
    1e-9) the lower values first. (By the distance alone when no two are within 2e-9: rounding to 1e-9 keeps the
    order, and puts apart two more than 1e-9 apart; it costs a microsecond a value.)"""
    candidates.sort(key=_distance_of)  # (an itemgetter: no Python frame per candidate)
    for k in range(1, len(candidates)):
        if candidates[k][2] - candidates[k - 1][2] <= 2e-9:
            candidates.sort(key=lambda c: (round(c[2], 9), c[0]))
            return


_distance_of = operator.itemgetter(2)  # (a candidate's distance)


def _nearest_turns(
    values: Sequence[float], bounds: Sequence[tuple[float, float, float, float] | None], centres: Sequence[float]
) -> tuple[list[float], float]:
    """Each value turned by whole turns to the one nearest its centre (0, or the value given as ``near``) within
    its range (``bounds``: the limits less and more LIMIT_SLACK, then the limits; None: a continuous joint, any
    turn), and the sum of the values' distances from their centres; an empty list when a value has none. (A value
    within its range stays: the turns' count of :func:`_turns_count` is 0 or less below it and 0 or more above.)"""
    wrapped: list[float] = []
    distance = 0.0
    for value, bound, centre in zip(values, bounds, centres, strict=True):
        value = centre + math.remainder(value - centre, TURN)
        if bound is not None:
            low, high, lower, upper = bound
            if not low <= value <= high:
                first, last = math.ceil((low - value) / TURN), math.floor((high - value) / TURN)
                if first > last:
                    return [], math.inf
                value += TURN * (first if first > 0 else last)  # (below: first > 0; above: last < 0)
            value = lower if value < lower else upper if value > upper else value
        wrapped.append(value)
        distance += abs(value - centre)
    return wrapped, distance


def _turns_count(values: Sequence[float], bounds: Sequence[float] | None, centres: Sequence[float]) -> int:
    """How many combinations of whole turns of the six ``values`` (taken as :func:`_nearest_turns` takes them)
    stay within their ranges (``bounds``: each joint's limits less and more LIMIT_SLACK, flat; None when a joint
    is continuous): a solution's equivalents, this one included (0: a continuous joint makes them endless)."""
    if bounds is None:
        return 0
    (c0, c1, c2, c3, c4, c5), (v0, v1, v2, v3, v4, v5) = centres, values
    remainder = math.remainder
    w0, w1, w2 = c0 + remainder(v0 - c0, TURN), c1 + remainder(v1 - c1, TURN), c2 + remainder(v2 - c2, TURN)
    w3, w4, w5 = c3 + remainder(v3 - c3, TURN), c4 + remainder(v4 - c4, TURN), c5 + remainder(v5 - c5, TURN)
    return _turns_of((w0, w1, w2, w3, w4, w5), bounds)


def _turns_of(wrapped: Sequence[float], bounds: Sequence[float] | None) -> int:
    """:func:`_turns_count` of values already turned to their centres (each its centre plus the remainder of its
    difference, as :func:`_candidates` made them)."""
    if bounds is None:
        return 0
    l0, h0, l1, h1, l2, h2, l3, h3, l4, h4, l5, h5 = bounds
    w0, w1, w2, w3, w4, w5 = wrapped
    floor, ceil = math.floor, math.ceil
    count = (floor((h0 - w0) / TURN) - ceil((l0 - w0) / TURN) + 1) * (
        floor((h1 - w1) / TURN) - ceil((l1 - w1) / TURN) + 1
    )
    count *= (floor((h2 - w2) / TURN) - ceil((l2 - w2) / TURN) + 1) * (
        floor((h3 - w3) / TURN) - ceil((l3 - w3) / TURN) + 1
    )
    return (
        count
        * (floor((h4 - w4) / TURN) - ceil((l4 - w4) / TURN) + 1)
        * (floor((h5 - w5) / TURN) - ceil((l5 - w5) / TURN) + 1)
    )


def options_of(solution: Solution, names: Sequence[str]) -> list[float]:
    return [solution.values[name] for name in names]


def _same_turns(a: Sequence[float], b: Sequence[float]) -> bool:
    """Whether two values lists are whole turns apart in every joint (to 1e-6): one branch met twice."""
    if abs(math.remainder(a[0] - b[0], TURN)) >= 1e-6:  # (most pairs differ at the first joint: no loop for them)
        return False
    for x, y in zip(a, b, strict=True):  # (a loop that leaves at the first joint apart: most pairs differ early)
        if abs(math.remainder(x - y, TURN)) >= 1e-6:
            return False
    return True


def _named(joints: Sequence[KinematicJoint], values: np.ndarray) -> dict[str, float]:
    return {j.name: float(v) for j, v in zip(joints, values, strict=True)}


def _order(values: dict[str, float], seed: np.ndarray, joints: Sequence[KinematicJoint]) -> tuple[float, ...]:
    """Nearest ``seed`` first; two as near (a symmetric arm's mirror branches), the lower values first: an order
    that does not hang on which start found which."""
    distance = round(_distance(values, seed, joints), 9)
    return (distance, *(round(values[j.name], 9) for j in joints))


def _distance(values: dict[str, float], seed: np.ndarray, joints: Sequence[KinematicJoint]) -> float:
    return sum(abs(values[j.name] - float(s)) for j, s in zip(joints, seed, strict=True))
