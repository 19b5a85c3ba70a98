"""Inverse kinematics (``gen-robot ik``, and the pose waypoints of ``gen-robot size``): joint values that put a frame at
a pose, within the joints' limits, by damped least squares on the frame's Jacobian (pinocchio's closed-loop inverse
kinematics, as its documentation writes it), from several starts (the two-link arm has two elbow branches).

The search is deterministic: the first start is the one given (or every joint at 0, clipped into its limits), the
others uniform in the limits (a continuous joint: one turn either way) from a fixed seed. A start converges when the
pose error (m, and rad for the orientation, the norm of the log of the error's rotation) is below TOLERANCE.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np

TOLERANCE = 1e-10  # m and rad: the pose error at which a start stops
ITERATIONS = 500  # steps per start
STARTS = 16  # starts of `gen-robot ik` (the first one given)
LONGEST_STEP = 0.5  # rad or m: the most a joint moves in one step
DISTINCT = 1e-3  # rad or m: two solutions closer than this in every joint are one
STALL = 6  # steps without halving the error: a start is stuck (another start is cheaper than waiting)
POLISHED = 4  # the best ends of a search that fails polished for the closest reach
RANK_TOLERANCE = 1e-6  # of the largest singular value: a smaller one is a direction the frame is not moved in
# (a chain that lacks a direction by its structure leaves its singular value at rounding's 1e-16 of the largest: the
# simple humanoid's waist and shoulder 1.8e-17 to 1.5e-16 over 63 spread configurations; a regular arm's smallest
# exceeds 1e-6 at a random configuration but with odds of about 1e-6, and over 63 spread ones the UR5's, the KR 560's
# and the Panda's reached 0.26-0.33 (their least 4e-5 to 1e-3); axes that meet within the closed form's tolerance,
# 1e-6 m per m, leave about 1e-6: counted as meeting, as the closed form counts them)


@dataclass(frozen=True)
class Chain:
    """What the solver moves: the model and frame, and for each joint one sets the pinocchio velocity columns it
    drives with their multipliers (a mimic joint's column joins its leader's), its limits, and how joint values make
    pinocchio's q."""

    model: object
    frame: int
    columns: list[list[tuple[int, float]]]
    lower: np.ndarray
    upper: np.ndarray
    configuration: Callable[[np.ndarray], np.ndarray]
    data: Any = None  # (pinocchio Data to reuse across starts; a new one when None)
    selection: np.ndarray | None = None  # (nv x joints: the columns as a matrix, when made once for many solves)

    def selected(self, full: np.ndarray) -> np.ndarray:
        """The Jacobian's columns combined per joint one sets (a mimic joint's times its multiplier)."""
        if self.selection is not None:
            result: np.ndarray = full @ self.selection
            return result
        combined: np.ndarray = np.array([sum(m * full[:, v] for v, m in drives) for drives in self.columns]).T
        return combined


def solve(
    chain: Chain,
    target: object,
    *,
    position_only: bool,
    start: Sequence[float] | np.ndarray,
    iterations: int = ITERATIONS,
) -> tuple[np.ndarray, float]:
    """Joint values from ``start`` that put the frame at ``target`` (a pinocchio SE3 in the root's frame; its rotation
    ignored when ``position_only``), kept within the limits; and the pose error left. A start that has not halved its
    error in STALL steps is stuck (against a limit, or in a local minimum out of reach) and ends there. A step that
    would take joints past their limits is made again without them (:func:`_bounded_step`)."""
    from scipy.linalg.lapack import dposv  # (heavy: scipy; LAPACK's Cholesky solve, 7x less overhead than numpy's)

    lower, upper = chain.lower, chain.upper
    limits = (lower.tolist(), upper.tolist())
    values = np.clip(np.array(start, dtype=float), lower, upper)
    error, best = math.inf, (math.inf, 0)
    with np.errstate(over="ignore", invalid="ignore"):  # (judged below: a mimic's multiplier of 1e308)
        for step_count in range(iterations):
            residual, full = residual_and_jacobian(chain, target, values, position_only=position_only)
            error = math.sqrt(float(residual @ residual))
            step = (
                _bounded_step(chain.selected(full), (residual, error), values, limits, dposv)
                if TOLERANCE <= error < math.inf
                else None
            )
            if step is None:  # (reached, or a pose or step that is not finite numbers: the start ends where it is)
                break
            if error < 0.5 * best[0]:
                best = (error, step_count)
            elif step_count - best[1] > STALL:
                break
            values = np.minimum(np.maximum(values + step, lower), upper)  # (np.clip, without its wrappers)
    return values, error


def residual_and_jacobian(
    chain: Chain, target: object, values: np.ndarray, *, position_only: bool
) -> tuple[np.ndarray, np.ndarray]:
    """The pose error's vector at ``values`` (the position's difference in the root's axes, or the log of the
    relative pose) and its derivative by pinocchio's velocity columns (6 or 3 x nv)."""
    import pinocchio as pin  # (heavy: pinocchio)

    model: Any = chain.model
    data = chain.data if chain.data is not None else model.createData()
    goal: Any = target
    pin.computeJointJacobians(model, data, chain.configuration(values))  # (the joints' placements with them: one pass)
    current = pin.updateFramePlacement(model, data, chain.frame)
    if position_only:
        residual = current.translation - goal.translation
        full = pin.getFrameJacobian(model, data, chain.frame, pin.ReferenceFrame.LOCAL_WORLD_ALIGNED)
        return residual, np.asarray(full).reshape(6, model.nv)[:3]  # (a 1-DOF robot's comes as a vector)
    relative = goal.actInv(current)
    full = pin.getFrameJacobian(model, data, chain.frame, pin.ReferenceFrame.LOCAL)
    return pin.log6(relative).vector, pin.Jlog6(relative) @ np.asarray(full).reshape(6, model.nv)


def directions(
    chain: Chain, configurations: Sequence[np.ndarray], *, position_only: bool, free: np.ndarray
) -> int | None:
    """How many independent directions the ``free`` joints (a mask over the joints one sets: those with room between
    their limits) move the frame in (3 for a position at most, 6 for a pose): the most at any of ``configurations``;
    None when no configuration gives a Jacobian of finite numbers. At each, the rank of the free joints' columns:
    the linear rows scaled by the longest column's (m per rad: a metre and a radian weigh alike; the lengths taken of
    columns divided by their largest entry first, so that a rail of 1e200 m does not overflow them), then each column
    by its largest entry; the singular values above RANK_TOLERANCE of the largest counted."""
    import pinocchio as pin  # (heavy: pinocchio)

    model: Any = chain.model
    data = chain.data if chain.data is not None else model.createData()
    most: int | None = None
    for values in configurations:
        full = pin.computeFrameJacobian(
            model, data, chain.configuration(values), chain.frame, pin.ReferenceFrame.LOCAL_WORLD_ALIGNED
        )
        part = chain.selected(np.asarray(full).reshape(6, model.nv))[:, free]
        if not np.isfinite(part).all():
            continue
        linear = part[:3]
        peak = float(np.abs(linear).max(initial=0.0))
        longest = peak * float(np.linalg.norm(linear / peak, axis=0).max(initial=0.0)) if peak > 0.0 else 0.0
        linear = linear / max(longest, 1e-300)
        part = linear if position_only else np.vstack((linear, part[3:]))
        peaks = np.abs(part).max(axis=0, initial=0.0)  # (each column to a largest entry of 1: a joint's scale, a
        part = part / np.where(peaks > 0.0, peaks, 1.0)  # rail of 1e200 m or a mimic's 1e7, hides no other's column)
        sizes = np.linalg.svd(part, compute_uv=False) if part.size else np.zeros(0)
        rank = int((sizes > RANK_TOLERANCE * sizes.max(initial=0.0)).sum())
        most = rank if most is None else max(most, rank)
    return most


def closest_reach(
    chain: Chain, target: object, *, position_only: bool, found: list[tuple[np.ndarray, float]]
) -> tuple[np.ndarray, float]:
    """Out of reach: the values within the limits that bring the frame closest to ``target`` (the least pose error),
    from the POLISHED best ends of the search ``found``, each polished by a bounded quasi-Newton descent on half the
    squared error (scipy's L-BFGS-B, its gradient J^T r): damped least squares clipped at a limit stops short of the
    closest point, where the gradient along the limit is not yet zero."""
    from scipy.optimize import minimize  # (heavy: scipy)

    def cost(values: np.ndarray) -> tuple[float, np.ndarray]:
        residual, full = residual_and_jacobian(chain, target, values, position_only=position_only)
        with np.errstate(over="ignore", invalid="ignore"):
            part = chain.selected(full)
            value, gradient = 0.5 * float(residual @ residual), part.T @ residual
        if not (math.isfinite(value) and np.isfinite(gradient).all()):
            return math.inf, np.zeros(len(values))
        return value, gradient

    finite = sorted((f for f in found if math.isfinite(f[1])), key=lambda f: f[1])[:POLISHED]
    best = min(finite, key=lambda f: f[1])
    bounds = list(zip(chain.lower, chain.upper, strict=True))
    for values, _ in finite:
        result = minimize(
            cost, values, jac=True, method="L-BFGS-B", bounds=bounds, options={"ftol": 1e-15, "gtol": 1e-12}
        )
        polished = np.clip(result.x, chain.lower, chain.upper)
        error = math.sqrt(2 * cost(polished)[0]) if math.isfinite(cost(polished)[0]) else math.inf
        if error < best[1]:
            best = (polished, error)
    return best


def _bounded_step(
    part: np.ndarray,
    at: tuple[np.ndarray, float],
    values: np.ndarray,
    limits: tuple[list[float], list[float]],
    dposv: Any,
) -> np.ndarray | None:
    """The damped least-squares step on the Jacobian's columns of the joints one sets (``part``) from ``at`` (the
    residual and its norm), at most LONGEST_STEP in any joint; when it would take joints past their ``limits``, the
    step made again with those joints held (their columns left out: an active set), so that the others make up the
    clipped joints' share instead of the step losing it (on the Panda's limits a start otherwise takes twice the
    steps). None when it is not finite numbers."""
    residual, error = at
    made = _step(part, residual, error, dposv)
    if made is None:
        return None
    step, moves = made
    bounds = zip(values.tolist(), moves, limits[0], limits[1], strict=True)  # (plain floats: 5 numpy calls cost more)
    over = [k for k, (v, d, low, high) in enumerate(bounds) if (v + d < low and d < 0.0) or (v + d > high and d > 0.0)]
    if over and len(over) < len(moves):
        held = part.copy()
        held[:, over] = 0.0
        again = _step(held, residual, error, dposv)
        step = again[0] if again is not None else step
    return step


def _step(part: np.ndarray, residual: np.ndarray, error: float, dposv: Any) -> tuple[np.ndarray, list[float]] | None:
    """The damped least-squares step on the Jacobian's columns ``part`` (``dposv``: LAPACK's Cholesky solve, imported
    once a start), at most LONGEST_STEP in any joint, and as plain floats; None when it is not finite numbers."""
    normal = part @ part.T
    normal.flat[:: len(residual) + 1] += 1e-12 + 1e-3 * error  # (less damping as it closes in: quadratic near it)
    _, solved, info = dposv(normal, residual)
    if info != 0:  # (not positive definite: a matrix of inf or NaN)
        return None
    step: np.ndarray = solved @ part
    moves = step.tolist()  # (plain floats: numpy's calls cost more on 7)
    if not math.isfinite(sum(moves)):
        return None
    largest = max(map(abs, moves), default=0.0)
    factor = -LONGEST_STEP / largest if largest > LONGEST_STEP else -1.0  # (near a singularity, out of reach: a
    step *= factor  # step that would leap across the range is shortened; and the sign: the step is -J^T solved)
    return step, [factor * d for d in moves]


def starts(chain: Chain, first: Sequence[float] | np.ndarray, count: int = STARTS, seed: int = 0) -> list[np.ndarray]:
    """``first``, then ``count - 1`` starts spread over the limits' box: a scrambled Sobol sequence (scipy; a fixed
    seed, so the same search every run), which fills the box's corners evenly where uniform draws leave some empty
    (16 uniform starts once missed one of the two-link arm's elbow branches)."""
    from scipy.stats import qmc  # (heavy: scipy)

    drawn = 1 << max(count - 1, 0).bit_length()  # (Sobol's balance holds for a power of two: draw one, use count)
    spread = qmc.Sobol(d=len(chain.lower), scramble=True, seed=seed).random(drawn)[1:count]
    with np.errstate(over="ignore"):
        width = chain.upper - chain.lower
    if np.isfinite(width).all():
        return [np.array(first, dtype=float)] + [chain.lower + u * width for u in spread]
    # (limits of -1e308 and 1e308: their width overflows; each start a weighted mean of the two instead)
    return [np.array(first, dtype=float)] + [chain.lower * (1 - u) + chain.upper * u for u in spread]


def distinct(found: list[tuple[np.ndarray, float]]) -> list[tuple[np.ndarray, float]]:
    """The solutions that differ from every one before them by more than DISTINCT in some joint."""
    kept: list[tuple[np.ndarray, float]] = []
    for values, error in found:
        if all(np.abs(values - other).max() > DISTINCT for other, _ in kept):
            kept.append((values, error))
    return kept
