"""ik's closed forms (issue 43) on arms built as a user builds them: YAML specs with `arms:` DH tables, from
manufacturers' published geometry, in the standard and the modified (Craig) convention, some mounted off the root
and given a tool offset, generated to a package, then solved through the Python API and the command line. Each
target is posed at joint values drawn within the limits, by pinocchio on the generated URDF (checked first against
the DH product written out from the textbook), and every branch `ik --all` gives is compared with an independent
many-start search: scipy's Levenberg-Marquardt on pinocchio's forward kinematics, nothing of xacrokit's solvers.

Sizes: 6 arms x 3 targets, each searched from up to 160 starts and stopped at 8 solutions, the most these structures
have (over 40 targets an arm searched from 400 starts, the last new solution came by start 68: 160 leave that margin
twice over), and one command-line run a target: 8 to 10 s in one process."""

from __future__ import annotations

import json
import math
from dataclasses import dataclass, field

import numpy as np
import pinocchio as pin
import pytest
from scipy.optimize import least_squares

from conftest import dh_product, gen_robot
from xacrokit import generate
from xacrokit.kinematics import ik, ik_solver
from xacrokit.reader.read_robot import read_robot

TURN = 2 * math.pi
UR_LIKE = "closed form (three parallel axes)"
PIEPER = "closed form (spherical wrist)"
DEG = " deg"


def angle(text: str) -> float:
    """An angle as the spec writes it (a number, 'N deg', 'pi/2', '-2*pi'), read here without xacrokit's parser."""
    if text.endswith(DEG):
        return math.radians(float(text[: -len(DEG)]))
    words = {"pi": math.pi, "pi/2": math.pi / 2, "2*pi": TURN}
    if text.lstrip("-") in words:
        return math.copysign(words[text.lstrip("-")], -1.0 if text.startswith("-") else 1.0)
    return float(text)


@dataclass(frozen=True)
class Arm:
    """A spec's arm: DH rows (theta, d, a, alpha) in `convention`, each joint's (lower, upper) limit as written,
    the arm's origin in base_link and the tool's offset (xyz, rpy), and the closed form it should be given."""

    name: str
    convention: str
    rows: tuple[tuple[str, str, str, str], ...]
    limits: tuple[tuple[str, str], ...]
    kind: str
    origin: tuple[tuple[float, ...], tuple[float, ...]] = ((0.0, 0.0, 0.0), (0.0, 0.0, 0.0))
    tool: tuple[tuple[float, ...], tuple[float, ...]] = ((0.0, 0.0, 0.0), (0.0, 0.0, 0.0))
    names: tuple[str, ...] = field(default=tuple(f"joint_{k}" for k in range(1, 7)))

    def spec(self) -> str:
        rows = []
        for k, ((theta, d, a, alpha), (lower, upper)) in enumerate(zip(self.rows, self.limits, strict=True)):
            rows.append(
                f"      - {{name: {self.names[k]}, link: link_{k + 1}, theta: {theta}, d: {d}, a: {a}, alpha: {alpha},"
                f" density: aluminium, radius: 0.04,\n"
                f"         limit: {{lower: {lower}, upper: {upper}, effort: 100, velocity: 180 deg/s}}}}"
            )
        return (
            f"robot: {self.name}\n"
            "links:\n"
            "  base_link: {shape: {cylinder: {radius: 0.1, length: 0.05}}, density: aluminium}\n"
            "arms:\n"
            "  arm:\n"
            "    parent: base_link\n"
            f"    origin: {{xyz: {list(self.origin[0])}, rpy: {list(self.origin[1])}}}\n"
            f"    convention: {self.convention}\n"
            "    joints:\n" + "\n".join(rows) + "\n"
            f"    tool: {{name: tool0, origin: {{xyz: {list(self.tool[0])}, rpy: {list(self.tool[1])}}}}}\n"
        )

    def span(self, k: int) -> tuple[float, float]:
        return angle(self.limits[k][0]), angle(self.limits[k][1])

    def textbook(self, q) -> np.ndarray:
        rows = [dict(zip(("theta", "d", "a", "alpha"), map(angle, row), strict=True)) for row in self.rows]
        return dh_product(rows, q, self.convention, self.origin, self.tool)


R2PI = ("-2*pi", "2*pi")
ARMS = [
    # Universal Robots UR3, UR's published standard DH table ("DH parameters for calculations of kinematics and
    # dynamics", UR support article: d1 = 0.1519, a2 = -0.24365, a3 = -0.21325, d4 = 0.11235, d5 = 0.08535,
    # d6 = 0.0819 m, alpha = pi/2, 0, 0, pi/2, -pi/2, 0), rewritten in Craig's modified convention (row i: alpha(i-1),
    # a(i-1), theta(i), d(i)); limits +-360 deg, the elbow +-pi as UR's ROS description limits it.
    Arm(
        "ur3_craig",
        "modified",
        (
            ("0", "0.1519", "0", "0"),
            ("0", "0", "0", "pi/2"),
            ("0", "0", "-0.24365", "0"),
            ("0", "0.11235", "-0.21325", "0"),
            ("0", "0.08535", "0", "pi/2"),
            ("0", "0.0819", "0", "-pi/2"),
        ),
        (R2PI, R2PI, ("-pi", "pi"), R2PI, R2PI, R2PI),
        UR_LIKE,
        names=(
            "shoulder_pan_joint",
            "shoulder_lift_joint",
            "elbow_joint",
            "wrist_1_joint",
            "wrist_2_joint",
            "wrist_3_joint",
        ),
    ),
    # UR10 (the same article: d1 = 0.1273, a2 = -0.612, a3 = -0.5723, d4 = 0.163941, d5 = 0.1157, d6 = 0.0922 m),
    # standard DH with a variant's zero (theta offsets -pi/2 on joints 2 and 4: upright at zero), wall-mounted (the
    # arm's origin turned 90 deg about y, 1 m up) and a 0.15 m tool offset tilted 30 deg; every joint +-2 pi.
    Arm(
        "ur10_wall",
        "standard",
        (
            ("0", "0.1273", "0", "pi/2"),
            ("-pi/2", "0", "-0.612", "0"),
            ("0", "0", "-0.5723", "0"),
            ("-pi/2", "0.163941", "0", "pi/2"),
            ("0", "0.1157", "0", "-pi/2"),
            ("0", "0.0922", "0", "0"),
        ),
        (R2PI,) * 6,
        UR_LIKE,
        origin=((0.0, 0.0, 1.0), (0.0, math.pi / 2, 0.0)),
        tool=((0.0, 0.02, 0.15), (math.pi / 6, 0.0, 0.0)),
    ),
    # ABB IRB 120-3/0.58, ROS-Industrial's abb_irb120_support/urdf/irb120_3_58_macro.xacro: joint 2 0.29 m up,
    # upper arm 0.27 m, elbow offset 0.07 m (a3), 0.302 m to the wrist, flange 0.072 m; no shoulder offset; its
    # limits, in degrees (the table's joint signs and zero match ABB's). Standard DH.
    Arm(
        "irb120",
        "standard",
        (
            ("0", "0.29", "0", "-pi/2"),
            ("-pi/2", "0", "0.27", "0"),
            ("0", "0", "0.07", "-pi/2"),
            ("0", "0.302", "0", "pi/2"),
            ("0", "0", "0", "-pi/2"),
            ("pi", "0.072", "0", "0"),
        ),
        (
            ("-165 deg", "165 deg"),
            ("-110 deg", "110 deg"),
            ("-110 deg", "70 deg"),
            ("-160 deg", "160 deg"),
            ("-120 deg", "120 deg"),
            ("-400 deg", "400 deg"),
        ),
        PIEPER,
    ),
    # KUKA KR 6 R900 sixx (Agilus), ROS-Industrial's kuka_kr6_support/urdf/kr6r900sixx_macro.xacro: joint 2 0.4 m
    # up and 0.025 m ahead (a1), upper arm 0.455 m, elbow offset 0.035 m, 0.42 m to the wrist, flange 0.08 m; KUKA's
    # narrow limits (A2 -190..45 deg, A3 -120..156 deg); modified DH, ceiling-mounted (origin 2 m up, upside down).
    Arm(
        "kr6_ceiling",
        "modified",
        (
            ("0", "0.4", "0", "0"),
            ("0", "0", "0.025", "-pi/2"),
            ("-pi/2", "0", "0.455", "0"),
            ("0", "0.42", "0.035", "-pi/2"),
            ("0", "0", "0", "pi/2"),
            ("0", "0.08", "0", "-pi/2"),
        ),
        (
            ("-170 deg", "170 deg"),
            ("-190 deg", "45 deg"),
            ("-120 deg", "156 deg"),
            ("-185 deg", "185 deg"),
            ("-120 deg", "120 deg"),
            ("-350 deg", "350 deg"),
        ),
        PIEPER,
        origin=((0.0, 0.0, 2.0), (math.pi, 0.0, 0.0)),
    ),
    # Fanuc M-10iA, ROS-Industrial's fanuc_m10ia_support/urdf/m10ia_macro.xacro (and its OPW parameters,
    # JeroenDM/wip_fanuc_opw_parameters: a1 = 0.15, a2 = -0.2, c1 = 0.45, c2 = 0.6, c3 = 0.64, c4 = 0.1 m): shoulder
    # offset 0.15 m, elbow offset 0.2 m; its limits in radians, joint 3's wider than a turn (-3.14..4.61 about -y
    # there, so -4.61..3.14 here, where the table turns joint 3 about +y). Standard DH.
    Arm(
        "m10ia",
        "standard",
        (
            ("0", "0.45", "0.15", "-pi/2"),
            ("-pi/2", "0", "0.6", "0"),
            ("0", "0", "0.2", "-pi/2"),
            ("0", "0.64", "0", "pi/2"),
            ("0", "0", "0", "-pi/2"),
            ("0", "0.1", "0", "0"),
        ),
        (
            ("-3.14", "3.14"),
            ("-1.57", "2.79"),
            ("-4.61", "3.14"),
            ("-3.31", "3.31"),
            ("-3.31", "3.31"),
            ("-6.28", "6.28"),
        ),
        PIEPER,
    ),
    # Staubli TX2-60, ROS-Industrial's staubli_tx2_60_support/urdf/tx2_60_macro.xacro: joint 2 0.375 m up, upper
    # arm 0.29 m, a lateral offset of 0.02 m along axis 3 (d3), forearm 0.31 m, flange 0.07 m, straight up at zero;
    # its limits (joint 5 -121..132.5 deg). Modified DH.
    Arm(
        "tx2_60",
        "modified",
        (
            ("0", "0.375", "0", "0"),
            ("-pi/2", "0", "0", "-pi/2"),
            ("pi/2", "0.02", "0.29", "0"),
            ("0", "0.31", "0", "pi/2"),
            ("0", "0", "0", "-pi/2"),
            ("0", "0.07", "0", "pi/2"),
        ),
        (
            ("-180 deg", "180 deg"),
            ("-127.5 deg", "127.5 deg"),
            ("-152.5 deg", "152.5 deg"),
            ("-270 deg", "270 deg"),
            ("-121 deg", "132.5 deg"),
            ("-270 deg", "270 deg"),
        ),
        PIEPER,
    ),
]


class Independent:
    """Pinocchio's own model of the generated URDF: forward kinematics, and a many-start Levenberg-Marquardt
    search (scipy) with no limits, its solutions told apart modulo 2 pi."""

    def __init__(self, urdf, names):
        self.model = pin.buildModelFromUrdf(str(urdf))
        self.data = self.model.createData()
        self.frame = self.model.getFrameId("tool0")
        self.index = [self.model.idx_qs[self.model.getJointId(n)] for n in names]

    def q(self, values) -> np.ndarray:
        q = np.zeros(self.model.nq)
        q[self.index] = values
        return q

    def pose(self, values) -> pin.SE3:
        pin.framesForwardKinematics(self.model, self.data, self.q(values))
        return self.data.oMf[self.frame].copy()

    def error(self, values, goal) -> float:
        return float(np.linalg.norm(pin.log6(goal.actInv(self.pose(values))).vector))

    def search(self, goal: pin.SE3, starts: int, seed: int) -> list[np.ndarray]:
        def residual(values):
            return pin.log6(goal.actInv(self.pose(values))).vector

        def jacobian(values):
            q = self.q(values)
            pin.computeJointJacobians(self.model, self.data, q)
            pin.updateFramePlacements(self.model, self.data)
            local = pin.getFrameJacobian(self.model, self.data, self.frame, pin.LOCAL)[:, self.index]
            return pin.Jlog6(goal.actInv(self.data.oMf[self.frame])) @ local

        rng = np.random.default_rng(seed)
        found: list[np.ndarray] = []
        for _ in range(starts):
            fit = least_squares(residual, rng.uniform(-math.pi, math.pi, 6), jac=jacobian, method="lm", xtol=1e-15)
            if self.error(fit.x, goal) <= 1e-10 and not any(same_turns(fit.x, other) for other in found):
                found.append(fit.x)
                if len(found) == 8:  # (the most a UR-like or spherical-wrist arm has)
                    break
        return found


def same_turns(a, b, tolerance=1e-6) -> bool:
    return all(abs(math.remainder(x - y, TURN)) < tolerance for x, y in zip(a, b, strict=True))


def turns_within(value: float, lower: float, upper: float) -> int:
    """How many values 2 pi apart from `value` lie within [lower, upper]."""
    return max(0, math.floor((upper - value) / TURN) - math.ceil((lower - value) / TURN) + 1)


def to_text(matrix: np.ndarray) -> str:
    rpy = pin.rpy.matrixToRpy(matrix[:3, :3])
    return ",".join(repr(float(v)) for v in [*matrix[:3, 3], *rpy])


@pytest.fixture(scope="module")
def built(tmp_path_factory):
    """Each arm's spec written and generated (xacrokit.generate) once: arm name -> (spec path, URDF path)."""
    out = {}
    for arm in ARMS:
        folder = tmp_path_factory.mktemp(arm.name)
        spec = folder / f"{arm.name}.yaml"
        spec.write_text(arm.spec(), encoding="utf-8")
        generate(spec, folder / "package")
        out[arm.name] = (spec, folder / "package" / "urdf" / f"{arm.name}.urdf")
    return out


@pytest.mark.parametrize("arm", ARMS, ids=[a.name for a in ARMS])
def test_every_branch_of_a_spec_built_arm_is_the_many_start_searchs(arm, built):
    """(a) the closed form the structure has; (b) every solution re-posed by pinocchio to 1e-9 and within the
    limits, its 2 pi equivalents counted right; (c) the same branches modulo 2 pi as the independent search finds
    within the limits, the rest counted as outside them; (d) the configuration posed among them; (e) the command
    line's --json the same as the API's."""
    spec, urdf = built[arm.name]
    robot = read_robot(urdf)
    assert ik_solver(robot, "tool0").method == arm.kind
    independent = Independent(urdf, arm.names)
    spans = [arm.span(k) for k in range(6)]
    rng = np.random.default_rng(sum(map(ord, arm.name)))
    for trial in range(3):
        values = np.array([rng.uniform(lo, hi) for lo, hi in spans])
        goal = independent.pose(values)
        assert np.abs(goal.homogeneous - arm.textbook(values)).max() < 1e-12  # (the spec written as meant)
        found = ik(robot, "tool0", goal.homogeneous, every=True)
        assert found.method == arm.kind and found.complete, found
        closed = [np.array([s.values[n] for n in arm.names]) for s in found.solutions]
        context = (arm.name, trial, values.tolist(), [c.tolist() for c in closed])
        assert any(same_turns(values, c) for c in closed), context
        for solution, c in zip(found.solutions, closed, strict=True):
            assert independent.error(c, goal) <= 1e-9, context
            assert all(lo <= v <= hi for v, (lo, hi) in zip(c, spans, strict=True)), context
            assert solution.equivalents == math.prod(turns_within(v, *s) for v, s in zip(c, spans, strict=True))
        searched = independent.search(goal, starts=160, seed=trial)
        within = [v for v in searched if all(turns_within(x, *s) for x, s in zip(v, spans, strict=True))]
        assert len(closed) == len(within) and len(searched) == len(within) + found.outside_limits, (
            context,
            [v.tolist() for v in searched],
        )
        assert all(any(same_turns(v, c) for c in closed) for v in within), context
        said = json.loads(gen_robot("ik", urdf, "tool0", "--to", to_text(goal.homogeneous), "--all", "--json").stdout)
        assert (said["method"], said["outside_limits"]) == (found.method, found.outside_limits)
        assert len(said["solutions"]) == len(found.solutions), (context, said)
        for solution in said["solutions"]:
            (same,) = [
                s for s in found.solutions if all(abs(solution["joints"][n] - s.values[n]) < 1e-9 for n in arm.names)
            ]
            assert (solution["branch"], solution["equivalents"]) == (same.branch, same.equivalents)


def test_ik_takes_the_spec_itself_and_says_what_is_wrong_in_one_line(built):
    """`gen-robot ik SPEC` answers as the generated URDF does; a NaN in the target and a frame the robot has not are
    refused with exit 2, a message naming what was wrong, no traceback and nothing on stdout."""
    arm = ARMS[3]  # (the ceiling-mounted KUKA: its origin must reach the spec's reading too)
    spec, urdf = built[arm.name]
    goal = Independent(urdf, arm.names).pose([0.3, -1.2, 0.8, 0.5, -0.7, 1.1]).homogeneous
    by_spec, by_urdf = (
        json.loads(gen_robot("ik", robot, "tool0", "--to", to_text(goal), "--all", "--json").stdout)
        for robot in (spec, urdf)
    )
    assert by_spec["solutions"] and by_spec["method"] == PIEPER
    assert [s["branch"] for s in by_spec["solutions"]] == [s["branch"] for s in by_urdf["solutions"]]
    for a, b in zip(by_spec["solutions"], by_urdf["solutions"], strict=True):
        assert all(abs(a["joints"][n] - b["joints"][n]) < 1e-12 for n in arm.names)
    for argv, words in [
        (["tool0", "--to", "0.5,nan,1.2,0,0,0"], "--to '0.5,nan,1.2,0,0,0'"),
        (["no_such_frame", "--to", "0.5,0,1.2"], "no link or frame 'no_such_frame'"),
    ]:
        result = gen_robot("ik", spec, *argv, "--all", "--json")
        assert result.returncode == 2 and words in result.stderr, result.stderr
        assert "Traceback" not in result.stderr and not result.stdout


@pytest.mark.parametrize(
    ("index", "values"),
    [
        (
            0,
            [
                -2.6087435354695767,
                3.7157966325236487,
                -0.28332823956842823,
                4.018671148890025,
                0.1550200511925759,
                4.706358903878469,
            ],
        ),
        (
            5,
            [
                -1.449353976780111,
                -1.4525388952474871,
                -0.7734704813709647,
                -3.2615351631638565,
                0.9118403863482807,
                -2.577518701218782,
            ],
        ),
    ],
    ids=["ur3_craig", "tx2_60"],
)
def test_every_branch_of_a_target_has_a_name_of_its_own(index, values, built):
    """`--all` names each branch (shoulder, elbow, wrist), one name one branch (docs/kinematics.md): two targets
    that had two branches of one name before the names were measured in the arm's plane (the floor-mounted UR3's
    two elbows at joint 3 = +-0.283 were both 'elbow down'; the TX2-60's two shoulders both 'shoulder front', as the
    elbow was asked for instead of the wrist centre)."""
    arm = ARMS[index]
    _, urdf = built[arm.name]
    goal = Independent(urdf, arm.names).pose(values).homogeneous
    names = [s.branch for s in ik(read_robot(urdf), "tool0", goal, every=True).solutions]
    assert len(names) >= 2 and len(set(names)) == len(names), names


@pytest.mark.parametrize("arm", ARMS, ids=[a.name for a in ARMS])
def test_no_two_branches_of_a_random_target_share_a_name(arm, built):
    """Twenty random targets an arm (joint values uniform within its limits, posed by pinocchio): every branch
    returned has a name of its own (before: 6 to 30 of 30 targets repeated one on these arms)."""
    _, urdf = built[arm.name]
    robot, pose = read_robot(urdf), Independent(urdf, arm.names).pose
    spans = [arm.span(k) for k in range(6)]
    rng = np.random.default_rng(7 + len(arm.name))
    for _ in range(20):
        values = [rng.uniform(lo, hi) for lo, hi in spans]
        names = [s.branch for s in ik(robot, "tool0", pose(values).homogeneous, every=True).solutions]
        assert len(set(names)) == len(names), (values, names)
