"""The closed forms and the branch names made for one arm (:mod:`xacrokit.kinematics.folding`: the arm's numbers
written into the steps' own source and the arithmetic they make trivial taken out) against them as written, on the
example arms and on random DH arms built in arbitrary frame conventions (UR-like and spherical-wrist, twists of pi/2
and others), at random targets, singular ones among them; and the fold's flow rules on small functions of their own
(a number read on a later turn of a loop, or after an if that may change it, is still there)."""

from __future__ import annotations

import importlib.util
import math
import textwrap
from types import SimpleNamespace

import numpy as np
import pinocchio as pin
import pytest
from test_ik_branches import dh_arm, pieper_rows, ur_rows

from conftest import REPO
from xacrokit.kinematics import ik_solver
from xacrokit.kinematics.analytic import _branches, branches, folded
from xacrokit.kinematics.branch_names import _branch_name, _naming_for, branch_name
from xacrokit.kinematics.folding import specialised
from xacrokit.reader.read_robot import read_robot

EXAMPLES = {
    "ur5": REPO / "examples" / "robots" / "industrial_arm_std_dh.yaml",
    "ur10e": REPO / "examples" / "robots" / "ur10e.yaml",
    "kuka": REPO / "examples" / "robots" / "kuka_kr560_r3100_2.yaml",
}


def random_arm(tmp_path, seed):
    """A UR-like or spherical-wrist arm (with and without a shoulder offset), its twists pi/2 or drawn at random."""
    rng = np.random.default_rng(400 + seed)
    kind = seed % 3
    rows = ur_rows(rng) if kind == 0 else pieper_rows(rng, kind == 1)
    if seed % 2:  # (twists other than multiples of pi/2 where the structure allows them: fewer numbers fold)
        if kind == 0:
            rows[0] = (0, rows[0][1], rng.uniform(-0.1, 0.1), rng.uniform(0.3, 2.8))
            rows[3] = (0, rows[3][1], 0, rng.uniform(0.3, 2.8))
            rows[4] = (0, rows[4][1], 0, -rng.uniform(0.3, 2.8))
        else:
            rows[3] = (0, rows[3][1], 0, rng.uniform(0.3, 2.8))
            rows[4] = (0, 0, 0, -rng.uniform(0.3, 2.8))
    return read_robot(dh_arm(tmp_path, f"folded{seed}", rows, seed)), "l7"


def compare_at_random_targets(robot, frame, count, seed):
    """Every branch of the folded closed form is the written one's (values to 1e-12, roots, exactness and the
    singularity), at targets posed at random joint values, every tenth with joint 5 at 0 and the next with joint 3
    at 0 (singular and stretched arms)."""
    model = robot.kinematics
    solver = ik_solver(robot, frame)
    form = solver.form
    assert folded(form) is not _branches  # (the arm's steps were made for it)
    rng = np.random.default_rng(seed)
    frame_id = model.frame_id(frame)
    for index in range(count):
        values = {j.name: float(rng.uniform(*j.span)) for j in model.joints}
        names = list(values)
        if index % 10 in (1, 2):
            values[names[4 if index % 10 == 1 else 2]] = 0.0
        pin.framesForwardKinematics(model.model, model.data, model.configuration(values))
        goal = solver.base.actInv(model.data.oMf[frame_id])
        rotation = tuple(tuple(row) for row in goal.rotation.tolist())
        position = tuple(goal.translation.tolist())
        for exact_only in (False, True):
            ours = branches(form, rotation, position, exact_only=exact_only)
            written = _branches(form, rotation, position, exact_only)
            assert [b[1:] for b in ours] == [b[1:] for b in written], index
            for a, b in zip(ours, written, strict=True):
                assert max(abs(x - y) for x, y in zip(a.values, b.values, strict=True)) <= 1e-12, (index, a, b)


def compare_names(form, seed):
    """The folded branch names are the written ones at random joint values and roots."""
    assert _naming_for(form) is not _branch_name
    rng = np.random.default_rng(seed)
    for _ in range(300):
        values = tuple(float(v) for v in rng.uniform(-2 * math.pi, 2 * math.pi, 6))
        roots = (int(rng.integers(2)), int(rng.integers(2)), int(rng.integers(2)))
        assert branch_name(form, values, roots) == _branch_name(form, values, roots), values


@pytest.mark.parametrize("arm", sorted(EXAMPLES))
def test_the_example_arms_folded_give_the_written_branches(arm):
    robot = read_robot(EXAMPLES[arm])
    compare_at_random_targets(robot, "tool0", 100, 3)
    compare_names(ik_solver(robot, "tool0").form, 3)


@pytest.mark.parametrize("arm", sorted(EXAMPLES))
def test_at_quarter_turns_the_folded_branches_are_the_written_ones_to_a_whole_turn(arm):
    """At joint values on quarter turns many of a solve's sums are exactly 0, and the fold may give such a 0 the other
    sign (0 - x written as -x): atan2(+-0, -1) is +-pi, the same joint position. There every branch's roots,
    exactness and singularity are the written ones', and its values theirs to 1e-12 or to a whole turn."""
    robot = read_robot(EXAMPLES[arm])
    model, solver = robot.kinematics, ik_solver(robot, "tool0")
    form, frame_id = solver.form, model.frame_id("tool0")
    rng = np.random.default_rng(7)
    for _ in range(150):
        values = {j.name: float(rng.integers(-2, 3)) * math.pi / 2 for j in model.joints}
        pin.framesForwardKinematics(model.model, model.data, model.configuration(values))
        goal = solver.base.actInv(model.data.oMf[frame_id])
        rotation, position = tuple(tuple(r) for r in goal.rotation.tolist()), tuple(goal.translation.tolist())
        ours, written = branches(form, rotation, position), _branches(form, rotation, position, False)
        assert [b[1:] for b in ours] == [b[1:] for b in written], values
        for a, b in zip(ours, written, strict=True):
            for x, y in zip(a.values, b.values, strict=True):
                whole = round((x - y) / (2 * math.pi))
                assert abs(x - y - 2 * math.pi * whole) <= 1e-12, (values, a, b)


@pytest.mark.parametrize("seed", range(6))
def test_random_arms_folded_give_the_written_branches(tmp_path, seed):
    robot, frame = random_arm(tmp_path, seed)
    compare_at_random_targets(robot, frame, 40, seed)
    compare_names(ik_solver(robot, frame).form, seed)


FLOWS = '''
def carried(k, xs):
    """a read on a later turn of the loop of a number assigned in it (and on the first, of one assigned before)"""
    total = 0.0
    a = 2.0
    for x in xs:
        total += a * x + x * k.one
        a = k.zero
    return total


def kept(k, xs):
    """a number assigned before a loop that changes it, read after the loop"""
    a = k.zero
    for x in xs:
        a = x
    return a * k.one


def branched(k, flag):
    """a number an if may change, read after it; a number read only where it is known"""
    v = k.one
    w, z = k.pair
    if flag:
        v = 2.0 * flag
    return v * 3.0 + w * flag - z * flag + 0.0 * flag


def unpacked(k, x):
    """a tuple of the arm's numbers unpacked in a loop, each read in it"""
    out = []
    for step in range(3):
        a, b, c = k.triple
        out.append(a * x + b * step - c)
    return out
'''


def test_numbers_read_on_a_later_turn_or_after_an_if_are_kept(tmp_path):
    path = tmp_path / "flows_for_folding.py"
    path.write_text(textwrap.dedent(FLOWS), encoding="utf-8")
    spec = importlib.util.spec_from_file_location("flows_for_folding", path)
    assert spec is not None and spec.loader is not None
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    k = SimpleNamespace(zero=0.0, one=1.0, pair=(1.0, -0.0), triple=(0.0, 1.0, -1.0))
    made = specialised(module, {name: {"k": k} for name in ("carried", "kept", "branched", "unpacked")}, 1.0)
    assert made is not None
    for xs in ([], [2.0], [1.5, -3.0, 4.25]):
        assert made["carried"](k, xs) == module.carried(k, xs)
        assert made["kept"](k, xs) == module.kept(k, xs)
    for flag in (0.0, 1.5, -2.0):
        assert made["branched"](k, flag) == module.branched(k, flag)
    assert made["unpacked"](k, 2.5) == module.unpacked(k, 2.5)
    assert made["carried"].__code__.co_code != module.carried.__code__.co_code  # (folded: not the same code)


def test_a_function_the_fold_does_not_know_is_left_as_written(tmp_path):
    path = tmp_path / "unknown_for_folding.py"
    path.write_text("def guarded(k, x):\n    try:\n        return k.one * x\n    finally:\n        pass\n")
    spec = importlib.util.spec_from_file_location("unknown_for_folding", path)
    assert spec is not None and spec.loader is not None
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    assert specialised(module, {"guarded": {"k": SimpleNamespace(one=1.0)}}, 1.0) is None
    assert math.isclose(module.guarded(SimpleNamespace(one=1.0), 2.0), 2.0)
