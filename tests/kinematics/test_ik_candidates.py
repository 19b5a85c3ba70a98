"""The closed form's candidates as the solver keeps them, against the plain rules they were written from: each
branch's values turned to the nearest within the limits, one met twice (whole turns apart in every joint, to 1e-6)
left out with the first kept, the equivalents counted from the turned values, and the solutions made without a
dataclass's __init__ equal to those made with it."""

from __future__ import annotations

import dataclasses
import math

import numpy as np
import pytest

from xacrokit.kinematics.analytic import Branch
from xacrokit.kinematics.inverse_solver import (
    LIMIT_SLACK,
    Solution,
    Solutions,
    _candidates,
    _closed_solutions,
    _nearest_turns,
    _solution,
    _turns_count,
    _turns_of,
)

TURN = 2 * math.pi


def plain_candidates(found, limits, centres):
    """Every exact branch turned by whole turns to its values nearest ``centres`` within ``limits`` (none: counted
    outside), then each compared with those kept before it, joint by joint modulo 2 pi."""
    bounds = [(lo - LIMIT_SLACK, hi + LIMIT_SLACK, lo, hi) for lo, hi in limits]
    kept, outside = [], 0
    for branch in found:
        if not branch.exact:
            continue
        wrapped, distance = _nearest_turns(branch.values, bounds, centres)
        if not wrapped:
            outside += 1
            continue
        if any(
            all(abs(math.remainder(a - b, TURN)) < 1e-6 for a, b in zip(wrapped, other, strict=True))
            for other, *_ in kept
        ):
            continue
        kept.append((wrapped, branch, distance))
    return kept, outside


def ranges(rng, wide):
    """Six joints' limits: a UR's whole two turns each, or a few narrower than a turn (some branches outside)."""
    if wide:
        return [(-TURN, TURN)] * 6
    return [tuple(sorted(rng.uniform(-4.0, 4.0, 2))) if rng.random() < 0.4 else (-TURN, TURN) for _ in range(6)]


def branch_sets(rng, count):
    """Eight branches a target, some of them another's values whole turns over (a root met twice: the cosine -1, a
    tangency), moved by less than 1e-6 or by a little more, some near joint 3's half turn, some not exact."""
    for _ in range(count):
        found = []
        for k in range(8):
            values = list(rng.uniform(-2 * math.pi, 2 * math.pi, 6))
            if k % 3 == 2 and rng.random() < 0.3:
                values[2] = math.pi - float(rng.uniform(0, 1e-6))
            if found and rng.random() < 0.4:
                twin = list(found[int(rng.integers(len(found)))].values)
                turns = rng.integers(-1, 2, 6)
                nudge = float(rng.choice([0.0, 2e-7, 8e-7, 3e-6, 1e-4]))
                values = [
                    v + TURN * int(t) + nudge * float(rng.uniform(-1, 1)) for v, t in zip(twin, turns, strict=True)
                ]
            found.append(Branch(tuple(values), (k % 2, k // 2 % 2, k // 4), bool(rng.random() < 0.9)))
        yield found


@pytest.mark.parametrize("wide", [True, False])
def test_the_candidates_are_the_plain_rules(wide):
    rng = np.random.default_rng(43)
    left, moved = 0, 0
    for found in branch_sets(rng, 1500):
        limits = ranges(rng, wide)
        centres = [0.0] * 6 if rng.random() < 0.5 else list(rng.uniform(-1.0, 1.0, 6))
        bounds = [(lo - LIMIT_SLACK, hi + LIMIT_SLACK, lo, hi) for lo, hi in limits]
        within = tuple(v for pair in limits for v in pair)
        ours, outside = _candidates(found, (within, bounds), centres)
        plain, plain_outside = plain_candidates(found, limits, centres)
        assert outside == plain_outside
        assert [(list(w), b) for w, b, _, _ in ours] == [(w, b) for w, b, _ in plain]
        for (_, _, distance, _), (_, _, plain_distance) in zip(ours, plain, strict=True):
            assert abs(distance - plain_distance) < 1e-12
        left += sum(b.exact for b in found) - outside - len(ours)
        moved += sum(not whole for *_, whole in ours)
    assert left > 300  # (twins met often: the duplicates' rule is exercised)
    assert moved > 100 or wide  # (narrow limits: values moved by a turn, the other path, exercised too)


def test_the_equivalents_counted_from_the_turned_values_are_the_values_counted():
    rng = np.random.default_rng(7)
    for _ in range(3000):
        limits = ranges(rng, bool(rng.random() < 0.5))
        flat = tuple(v for lo, hi in limits for v in (lo - LIMIT_SLACK, hi + LIMIT_SLACK))
        bounds = [(lo - LIMIT_SLACK, hi + LIMIT_SLACK, lo, hi) for lo, hi in limits]
        centres = [0.0] * 6 if rng.random() < 0.5 else list(rng.uniform(-1.0, 1.0, 6))
        values = Branch(tuple(rng.uniform(-3 * math.pi, 3 * math.pi, 6)), (0, 0, 0), True)
        for wrapped, branch, _, whole in _candidates([values], (tuple(v for p in limits for v in p), bounds), centres)[
            0
        ]:
            if whole:
                assert _turns_of(wrapped, flat) == _turns_count(branch.values, flat, centres)
    assert _turns_of([0.0] * 6, None) == 0 == _turns_count([0.0] * 6, None, [0.0] * 6)


def test_solutions_made_at_once_are_the_dataclasses():
    values = {"a": 0.5, "b": -1.25}
    made = _solution(values, 1e-13, "shoulder left, elbow up, wrist flip", 4, "wrist singularity")
    assert made == Solution(values, 1e-13, "shoulder left, elbow up, wrist flip", 4, "wrist singularity")
    assert set(vars(made)) == {f.name for f in dataclasses.fields(Solution)}
    assert dataclasses.replace(made, error=0.0).error == 0.0
    with pytest.raises(dataclasses.FrozenInstanceError):
        made.error = 1.0  # type: ignore[misc]

    class Solver:  # (the fields the closed form's Solutions takes of its solver)
        frame, in_frame, names, method = "tool0", "base_link", ["a", "b"], "closed form (three parallel axes)"

    whole = _closed_solutions(Solver(), [made], False, 1, 3)  # type: ignore[arg-type]
    assert whole == Solutions("tool0", "base_link", ["a", "b"], [made], None, Solver.method, 0, False, 1, 3)
    assert set(vars(whole)) == {f.name for f in dataclasses.fields(Solutions)}
    assert whole.joints is not Solver.names  # (a copy: the caller's list is its own)
