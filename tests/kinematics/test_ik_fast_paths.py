"""The closed form's arithmetic written out for speed, against the plain forms it replaced: a branch's name against
the parts placed joint by joint (the naming rule as docs/kinematics.md states it), the reposer's pose error against
pinocchio's log6, and every branch of random targets re-posed by pinocchio's forward kinematics."""

from __future__ import annotations

import math

import numpy as np
import pinocchio as pin
import pytest

from conftest import REPO
from xacrokit.kinematics import ik_solver
from xacrokit.kinematics.analytic import branches
from xacrokit.kinematics.arm_geometry import THREE_PARALLEL
from xacrokit.kinematics.branch_names import SLIGHT, branch_name
from xacrokit.kinematics.reposed import CLOSE
from xacrokit.kinematics.subproblems import add, cross, dot, norm, perpendicular, rotate, scale, sub, subproblem_1
from xacrokit.reader.read_robot import read_robot

ARMS = {
    "ur5": REPO / "examples" / "robots" / "industrial_arm_std_dh.yaml",
    "ur10e": REPO / "examples" / "robots" / "ur10e.yaml",
    "kuka": REPO / "examples" / "robots" / "kuka_kr560_r3100_2.yaml",
}


def plain_name(form, values, roots):
    """The naming rule as docs/kinematics.md states it, with every part placed by joints 3, 2, then 1 in the root's
    frame (the form the fast one replaced): up along axis 1 away from the base, the arm's forward across up and axis
    2, the elbow's side of the line to the wrist (axis 4's point with three parallel axes) in the arm's plane."""
    h, p, size = form.lines.axes, form.lines.points, form.lines.size

    def placed(point, joints):
        for k in reversed(range(joints)):
            point = add(p[k], rotate(h[k], values[k], sub(point, p[k])))
        return point

    def side(measure, names, root):
        return ("a" if root == 0 else "b") if abs(measure) <= SLIGHT else names[0] if measure > 0 else names[1]

    def sensed(direction, *senses):
        for sense in senses:
            if abs(dot(direction, sense)) > 1e-6 * size:
                return direction if dot(direction, sense) > 0 else scale(-1.0, direction)
        return direction

    up = sensed(h[0], sub(p[1], p[0]), (0.0, 0.0, 1.0))
    across = cross(h[1], up)
    forward = sensed(scale(1.0 / norm(across), across), sub(p[1], p[0]), sub(form.wrist, p[0]), (1.0, 0.0, 0.0))
    shoulder, elbow, wrist = placed(p[1], 1), placed(p[2], 2), placed(form.wrist, 4)
    corner = placed(p[3], 3) if form.kind == THREE_PARALLEL else wrist  # (the elbow triangle's far corner)
    if form.kind == THREE_PARALLEL:
        offset = scale(dot(form.parallel, sub(form.wrist, p[0])), rotate(h[0], values[0], form.parallel))
        reach = perpendicular(sub(wrist, p[0]), up)
        first = side(dot(offset, cross(up, reach)), ("left", "right"), roots[0])
    else:
        first = side(dot(rotate(h[0], values[0], forward), sub(wrist, p[0])), ("front", "back"), roots[0])
    n, line = rotate(h[0], values[0], h[1]), sub(corner, shoulder)
    sky = dot(n, cross(line, up))
    elbow_side = dot(n, cross(line, sub(elbow, shoulder)))
    clear = abs(sky) > SLIGHT * norm(line)
    bend = side((elbow_side if sky > 0 else -elbow_side) if clear else 0.0, ("up", "down"), roots[1])
    singular = subproblem_1(h[4], h[5], form.parallel if form.kind == THREE_PARALLEL else h[3])
    flip = side(math.sin(values[4] - singular), ("no flip", "flip"), roots[2])
    return f"shoulder {first}, elbow {bend}, wrist {flip}"


@pytest.mark.parametrize("arm", sorted(ARMS))
def test_a_branch_is_named_as_its_parts_placed_joint_by_joint_say(arm):
    solver = ik_solver(read_robot(ARMS[arm]), "tool0")
    rng = np.random.default_rng(5)
    names = set()
    for _ in range(2000):
        values = tuple(rng.uniform(-2 * math.pi, 2 * math.pi, 6))
        roots = tuple(int(r) for r in rng.integers(0, 2, 3))
        name = branch_name(solver.form, values, roots)
        assert name == plain_name(solver.form, values, roots), values
        names.add(name)
    assert len(names) == 8  # (every name met: the test compares every side of every measure)


@pytest.mark.parametrize("arm", sorted(ARMS))
def test_every_branch_re_poses_by_pinocchio_and_the_reposer_agrees_with_log6(arm):
    robot = read_robot(ARMS[arm])
    model = robot.kinematics
    solver = ik_solver(robot, "tool0")
    frame = model.frame_id("tool0")
    chain = solver.form.lines.joints
    rng = np.random.default_rng(9)
    for _ in range(100):
        values = {j.name: float(rng.uniform(*j.span)) for j in model.joints}
        pin.framesForwardKinematics(model.model, model.data, model.configuration(values))
        goal = model.data.oMf[frame].copy()
        rotation = tuple(tuple(row) for row in goal.rotation.tolist())
        found = [b for b in branches(solver.form, rotation, tuple(goal.translation.tolist())) if b.exact]
        assert found
        for branch in found:
            named = {model.joints[k].name: v for k, v in zip(chain, branch.values, strict=True)}
            pin.framesForwardKinematics(model.model, model.data, model.configuration(named))
            log6 = float(np.linalg.norm(pin.log6(goal.actInv(model.data.oMf[frame])).vector))
            assert log6 < 1e-9
            ours = solver.reposer.error(list(branch.values), goal.homogeneous.tolist())
            assert ours <= CLOSE and abs(ours - log6) <= 1e-12
        nudged = list(found[0].values)
        nudged[int(rng.integers(0, 6))] += float(rng.choice([1e-7, 1e-4, 0.3]))
        named = {model.joints[k].name: v for k, v in zip(chain, nudged, strict=True)}
        pin.framesForwardKinematics(model.model, model.data, model.configuration(named))
        log6 = float(np.linalg.norm(pin.log6(goal.actInv(model.data.oMf[frame])).vector))
        ours = solver.reposer.error(nudged, goal.homogeneous.tolist())
        assert ours > CLOSE and 0.5 * log6 < ours < 2 * log6  # (off the target: both say so, about as far)


@pytest.mark.parametrize("arm", sorted(ARMS))
def test_the_first_answer_is_the_nearest_branch_and_of_two_as_near_the_lower_values(arm):
    """With ``near`` halfway between two branches, the two are exactly as near (sum of the joints' distances): the
    first answer is the nearest of every branch, and of two as near (to 1e-9) the one whose values are lower, joint by
    joint from joint 1, whichever rounding the two distances took."""
    robot = read_robot(ARMS[arm])
    model = robot.kinematics
    solver = ik_solver(robot, "tool0")
    names = [j.name for j in model.joints]
    rng = np.random.default_rng(17)
    ties = 0
    for _ in range(40):
        values = {j.name: float(rng.uniform(*j.span)) for j in model.joints}
        pin.framesForwardKinematics(model.model, model.data, model.configuration(values))
        target = model.data.oMf[model.frame_id("tool0")].homogeneous
        every = solver.solve(target, every=True).solutions
        a, b = (np.array([s.values[n] for n in names]) for s in rng.choice(every, 2, replace=False))
        near = (a + b) / 2
        listed = solver.solve(target, every=True, near=near).solutions

        def key(solution, near=near):
            row = [solution.values[n] for n in names]
            return round(sum(abs(v - c) for v, c in zip(row, near, strict=True)), 9), row

        ordered = sorted(listed, key=key)
        ties += key(ordered[0])[0] == key(ordered[1])[0]
        (first,) = solver.solve(target, near=near).solutions
        assert first.branch == ordered[0].branch
        assert all(abs(first.values[n] - ordered[0].values[n]) < 1e-12 for n in names)
    assert ties >= 10  # (the midpoint's two branches are the nearest most of the time: the rule is exercised)


def plain_spherical_wrist(form, r_g, p_g):
    """The spherical-wrist chain with joints 2 and 3 parallel as first written (rotation matrices multiplied, every
    subproblem called as a function): the reference the float-written path replaced."""
    from xacrokit.kinematics.analytic import _across, _exact, _roots
    from xacrokit.kinematics.subproblems import (
        apply,
        multiply,
        rotation,
        subproblem_2,
        subproblem_3,
        subproblem_4,
        transposed,
    )

    h, p, n = form.lines.axes, form.lines.points, form.parallel
    centre = add(apply(r_g, form.wrist), p_g)
    found = []
    shoulder = subproblem_4(n, h[0], sub(centre, p[0]), dot(n, sub(form.wrist, p[0])))
    for i, t1 in enumerate(_roots(shoulder)):
        reached = add(p[0], rotate(h[0], t1, sub(centre, p[0])))
        upper, fore = perpendicular(sub(p[2], p[1]), n), perpendicular(sub(form.wrist, p[2]), n)
        elbow = subproblem_3(h[2], fore, scale(-1.0, upper), norm(perpendicular(sub(reached, p[1]), n)))
        for m, q3 in enumerate(_roots(elbow)):
            e3 = add(p[2], rotate(h[2], q3, sub(form.wrist, p[2])))
            q2 = subproblem_1(h[1], sub(e3, p[1]), sub(reached, p[1])) or 0.0
            turned = multiply(multiply(rotation(h[0], -t1), rotation(h[1], q2)), rotation(h[2], q3))
            rest = multiply(transposed(turned), r_g)
            pairs = subproblem_2(h[3], h[4], h[5], apply(rest, h[5]))
            assert pairs is not None  # (random targets: never on the wrist singularity)
            for j, (q4, q5) in enumerate(pairs[0]):
                across = _across(h[5])
                image = rotate(h[4], -q5, rotate(h[3], -q4, apply(rest, across)))
                q6 = subproblem_1(h[5], across, image) or 0.0
                exact = _exact(shoulder) and _exact(elbow) and pairs[1]
                found.append(((-t1, q2, q3, q4, q5, q6), (i, m, j), exact))
    return found


def test_the_spherical_wrist_on_floats_gives_the_plain_chains_branches_each_re_posed_by_pinocchio():
    robot = read_robot(ARMS["kuka"])
    model = robot.kinematics
    solver = ik_solver(robot, "tool0")
    form, frame, chain = solver.form, model.frame_id("tool0"), solver.form.lines.joints
    assert form.parallel is not None  # (the KR 560: joints 2 and 3 parallel, the path written on floats)
    lines = form.lines
    rng = np.random.default_rng(23)
    counted = 0
    for _ in range(300):
        values = {j.name: float(rng.uniform(*j.span)) for j in model.joints}
        pin.framesForwardKinematics(model.model, model.data, model.configuration(values))
        goal = model.data.oMf[frame].copy()
        rotation = tuple(tuple(row) for row in goal.rotation.tolist())
        found = branches(form, rotation, tuple(goal.translation.tolist()))
        r_g = np.asarray(rotation) @ np.asarray(lines.home_rotation).T
        p_g = goal.translation - r_g @ np.asarray(lines.home_position)
        plain = plain_spherical_wrist(form, tuple(map(tuple, r_g.tolist())), tuple(p_g.tolist()))
        assert [(b.roots, b.exact) for b in found] == [(roots, exact) for _, roots, exact in plain]
        for branch, (reference, _, _) in zip(found, plain, strict=True):
            assert max(abs(a - b) for a, b in zip(branch.values, reference, strict=True)) < 1e-9
            if not branch.exact:
                continue
            counted += 1
            named = {model.joints[k].name: v for k, v in zip(chain, branch.values, strict=True)}
            pin.framesForwardKinematics(model.model, model.data, model.configuration(named))
            assert float(np.linalg.norm(pin.log6(goal.actInv(model.data.oMf[frame])).vector)) < 1e-9
    assert counted >= 300 * 4  # (most targets have all 8 branches exact; every one re-posed)
