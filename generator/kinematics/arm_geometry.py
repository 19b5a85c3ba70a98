"""What a closed-form solver needs of an arm, read from the kinematic model (never from names): the joints from the
root to a frame, each joint's axis as a line at the zero pose (its direction h and a point P on it), and the frame's
pose at the zero pose (the product of exponentials: T(q) = E1(q1) ... En(qn) M, Ei the turn about line i).

From those lines, :func:`recognise` says which closed form fits: a 6R arm whose joints 2, 3 and 4 are parallel and
whose axes 5 and 6 meet (Universal Robots' arms and their DH variants), or one whose last three axes meet in one
point (a spherical wrist: Pieper's arms, KUKA, ABB, Fanuc, Staubli) with joints 2 and 3 parallel or axes 1 and 2
meeting at a point A that axis 3 misses, as it misses the wrist centre (else joint 3 keeps the wrist centre's
distance from A, and the first three joints place it in a continuum or nowhere: a waist and a shoulder, two
spherical groups, is such a chain, solved numerically). Lines are parallel, or meet, within TOLERANCE (rad, and m
per m of the arm's size): a CAD export's rounding is within it, and every branch the closed form gives is checked on
the robot and polished (:mod:`.analytic`).
"""

from __future__ import annotations

import functools
import math
from dataclasses import dataclass

import numpy as np

from ..reader.kinematic_model import KinematicModel
from .subproblems import DEGENERATE, Mat, Vec, add, cross, dot, norm, perpendicular, scale, sub

TOLERANCE = 1e-6  # rad between parallel axes; m per m of reach between lines that meet
SIX = 6  # joints: the chains the closed forms solve
THREE_PARALLEL = "three parallel axes"
SPHERICAL_WRIST = "spherical wrist"


@dataclass(frozen=True)
class ArmLines:
    """A chain of revolute joints from the root to a frame: the joints (indices into the model's joints one sets),
    their axes at the zero pose (unit directions, points on them, in the root's frame) and the frame's zero pose."""

    joints: tuple[int, ...]
    axes: tuple[Vec, ...]
    points: tuple[Vec, ...]
    home_rotation: Mat
    home_position: Vec
    size: float  # m: the largest distance of a point of the chain from the root (at least 1): lengths' scale


@dataclass(frozen=True)
class ClosedForm:
    """A recognised arm: its lines, its kind (THREE_PARALLEL or SPHERICAL_WRIST), the point where the wrist axes
    meet (axes 5 and 6, or 4, 5 and 6), the common direction of the parallel axes (n) when there is one, and for a
    spherical wrist whose axes 1 and 2 meet, that point."""

    lines: ArmLines
    kind: str
    wrist: Vec
    parallel: Vec | None
    shoulder: Vec | None

    def __hash__(self) -> int:
        """The fields' hash, made once: the closed forms' constants are cached by form and looked up for every
        target and branch (a frozen dataclass would hash its nested tuples again at each lookup)."""
        return self._hash

    @functools.cached_property
    def _hash(self) -> int:
        return hash((self.lines, self.kind, self.wrist, self.parallel, self.shoulder))


def arm_lines(model: KinematicModel, frame: int) -> ArmLines | None:
    """The chain's lines, or None when the joints that move ``frame`` are not all revolute joints one sets (a
    prismatic, planar or floating joint, or a mimic joint, on the way)."""
    import pinocchio as pin  # (heavy: pinocchio)

    pin_model, data = model.model, model.data
    by_name = {j.name: k for k, j in enumerate(model.joints)}
    followers = {f.joint.name for f in model.followers}
    path = [int(j) for j in pin_model.supports[pin_model.frames[frame].parentJoint] if j > 0]
    joints = []
    for joint_id in path:
        name = pin_model.names[joint_id]
        if name in followers or name not in by_name or model.joints[by_name[name]].kind == "prismatic":
            return None
        joints.append(by_name[name])
    if len(joints) != SIX:
        return None  # (only a six-joint chain has a closed form here)
    q = pin.neutral(pin_model)
    pin.computeJointJacobians(pin_model, data, q)
    pin.updateFramePlacements(pin_model, data)
    axes, points = [], []
    for joint_id, index in zip(path, joints, strict=True):
        world = np.asarray(pin.getJointJacobian(pin_model, data, joint_id, pin.ReferenceFrame.WORLD))
        column = world.reshape(6, pin_model.nv)[:, model.joints[index].v_index]  # (1 DOF: a vector)
        axes.append(_unit((float(column[3]), float(column[4]), float(column[5]))))
        points.append(_vec(data.oMi[joint_id].translation))
    home = data.oMf[frame]
    rotation = home.rotation
    rows = tuple((float(r[0]), float(r[1]), float(r[2])) for r in rotation)
    position = _vec(home.translation)
    size = max([1.0, norm(position)] + [norm(p) for p in points])
    return ArmLines(tuple(joints), tuple(axes), tuple(points), (rows[0], rows[1], rows[2]), position, size)


def recognise(lines: ArmLines | None) -> ClosedForm | None:
    """The closed form that fits a six-joint chain, or None (the numeric search then solves it)."""
    if lines is None or len(lines.joints) != SIX:
        return None
    return _three_parallel(lines) or _spherical_wrist(lines)


def _three_parallel(lines: ArmLines) -> ClosedForm | None:
    h, p, size = lines.axes, lines.points, lines.size
    n = h[1]
    if not (_parallel(h[1], h[2]) and _parallel(h[1], h[3])) or _parallel(h[0], n) or _parallel(h[4], n):
        return None
    wrist = _meeting(h[4], p[4], h[5], p[5], size)
    if wrist is None:
        return None
    upper, fore = perpendicular(sub(p[2], p[1]), n), perpendicular(sub(p[3], p[2]), n)
    if norm(upper) < TOLERANCE * size or norm(fore) < TOLERANCE * size:
        return None  # (a link of no length between parallel axes: the elbow's two branches are one continuum)
    if math.hypot(dot(n, h[5]) - dot(n, h[4]) * dot(h[4], h[5]), dot(n, cross(h[4], h[5]))) < TOLERANCE:
        return None  # (axis 5's turn does not move axis 6 across the parallel axes' direction: no wrist equation)
    return ClosedForm(lines, THREE_PARALLEL, wrist, n, None)


def _spherical_wrist(lines: ArmLines) -> ClosedForm | None:
    h, p, size = lines.axes, lines.points, lines.size
    if _parallel(h[3], h[4]) or _parallel(h[4], h[5]):
        return None
    wrist = _meeting(h[3], p[3], h[4], p[4], size)
    if wrist is None or _distance_to_line(wrist, h[5], p[5]) > TOLERANCE * size:
        return None
    if _parallel(h[1], h[2]) and not _parallel(h[0], h[1]):
        upper, fore = perpendicular(sub(p[2], p[1]), h[1]), perpendicular(sub(wrist, p[2]), h[1])
        if norm(upper) < TOLERANCE * size or norm(fore) < TOLERANCE * size:
            return None
        return ClosedForm(lines, SPHERICAL_WRIST, wrist, h[1], None)
    shoulder = _meeting(h[0], p[0], h[1], p[1], size)
    if shoulder is None:
        return None
    if min(_distance_to_line(wrist, h[2], p[2]), _distance_to_line(shoulder, h[2], p[2])) < TOLERANCE * size:
        return None  # (joint 3 keeps |E3 W - A|: joints 1 to 3 place the wrist centre in a continuum, or nowhere)
    return ClosedForm(lines, SPHERICAL_WRIST, wrist, None, shoulder)


def _parallel(a: Vec, b: Vec) -> bool:
    return norm(cross(a, b)) < TOLERANCE


def _meeting(h1: Vec, p1: Vec, h2: Vec, p2: Vec, size: float) -> Vec | None:
    """The point where two lines meet (the middle of their closest points), None when they are parallel or pass
    farther apart than TOLERANCE x size."""
    across = cross(h1, h2)
    sine2 = dot(across, across)
    if sine2 < TOLERANCE * TOLERANCE:
        return None
    gap = sub(p2, p1)
    if abs(dot(gap, across)) / math.sqrt(sine2) > TOLERANCE * size:
        return None
    c = dot(h1, h2)
    d1, d2 = dot(gap, h1), dot(gap, h2)
    t1 = (d1 - c * d2) / (1.0 - c * c)  # (the closest points: p1 + t1 h1 and p2 + t2 h2)
    t2 = (c * d1 - d2) / (1.0 - c * c)
    return scale(0.5, add(add(p1, scale(t1, h1)), add(p2, scale(t2, h2))))


def _distance_to_line(point: Vec, h: Vec, p: Vec) -> float:
    return norm(perpendicular(sub(point, p), h))


def _unit(a: Vec) -> Vec:
    length = norm(a)
    return scale(1.0 / length, a) if length > DEGENERATE else a


def _vec(values: object) -> Vec:
    x, y, z = (float(v) for v in values)  # type: ignore[attr-defined]
    return (x, y, z)
