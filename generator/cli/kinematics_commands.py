"""The kinematics commands, ``gen-robot pose`` and ``gen-robot jacobian`` (``ik`` is :mod:`.ik_command`): their
options and what they print (shells over :mod:`xacrokit.kinematics`, imported when the command runs: the CLI starts
without numpy)."""

from __future__ import annotations

import argparse
import contextlib
import sys
from collections.abc import Iterator
from typing import TYPE_CHECKING, Any

from ..errors import XacrokitError
from ..shared.value_text import comment_text
from .arguments import add_robot_options, robot_input
from .json_output import print_json, require_finite

if TYPE_CHECKING:
    from ..reader.kinematic_model import LimitWarning
    from ..reader.read_robot import ReadRobot

ROTATION_FORMS = ("rpy", "quat_xyzw", "quat_wxyz", "rotvec", "axis_angle", "matrix", "points")
EULER_FORMS = ("euler", "intrinsic", "extrinsic")  # (euler:SEQ scipy's case; intrinsic:AXES, extrinsic:AXES said)


def rotation_form(text: str) -> str:
    """``--rotation``'s value, checked: one of :data:`ROTATION_FORMS`, or Euler angles as ``euler:XYZ`` (scipy's
    sequence: upper case intrinsic, lower case extrinsic), ``intrinsic:ZYZ`` or ``extrinsic:xyz`` (the kind said, the
    axes in either case), the same twelve sequences an origin's ``euler`` takes."""
    from ..validate.quantities import EULER_SEQUENCES, euler_axes_problem, euler_sequence_problem  # (start-up)

    if text in ROTATION_FORMS:
        return text
    kind, colon, axes = text.partition(":")
    if not colon or kind not in EULER_FORMS:
        forms = ", ".join(ROTATION_FORMS)
        raise argparse.ArgumentTypeError(
            f"{comment_text(text)!r} is no rotation form: give one of {forms}, or Euler angles as euler:XYZ (upper "
            "case intrinsic, lower case extrinsic), intrinsic:ZYZ or extrinsic:xyz"
        )
    if kind == "euler" and axes not in EULER_SEQUENCES:
        raise argparse.ArgumentTypeError(euler_sequence_problem(axes))
    if kind != "euler" and axes.upper() not in EULER_SEQUENCES:
        raise argparse.ArgumentTypeError(euler_axes_problem(kind, axes))
    return f"{kind}:{axes}"


def euler_sequence(form: str) -> str | None:
    """scipy's sequence of a checked ``--rotation`` Euler form (intrinsic upper case, extrinsic lower), else None."""
    kind, _, axes = form.partition(":")
    if kind == "intrinsic":
        return axes.upper()
    if kind == "extrinsic":
        return axes.lower()
    return axes if kind == "euler" else None


def add_kinematics_commands(commands: Any) -> None:
    """Add ``pose`` and ``jacobian`` to the CLI's subcommands."""
    pose = commands.add_parser(
        "pose",
        help="where a link or frame is in another at given joint values (forward kinematics, no ROS needed)",
        description="Print the pose of FRAME in --in (default: the root link) with the joints at --at values "
        "(0 where not given; a mimic joint follows its leader): xyz (m), rpy (rad, URDF's fixed-axis roll, pitch, "
        "yaw), the quaternion (x, y, z, w) and the 4x4 matrix T_IN_FRAME. ROBOT is a spec, URDF or xacro document.",
    )
    _common(pose)
    pose.add_argument(
        "--rotation",
        type=rotation_form,
        default="rpy",
        metavar="FORM",
        help=f"the rotation also in this form (--json: as `rotation`): {', '.join(ROTATION_FORMS)}, or Euler angles "
        "as euler:XYZ (upper case intrinsic, lower case extrinsic), intrinsic:ZYZ or extrinsic:xyz, any of the 12 "
        "sequences (default: rpy)",
    )
    pose.add_argument(
        "--point",
        metavar="X,Y,Z",
        help="also a point given in FRAME's axes (m, each within 1e4), expressed in --in: T_IN_FRAME p (an object "
        "a camera sees)",
    )
    add_robot_options(pose)
    pose.set_defaults(handler=_cmd_pose)
    jac = commands.add_parser(
        "jacobian",
        help="the geometric Jacobian of a frame's origin (6 x n, linear rows first), and tau = J^T w for a wrench",
        description="Print the 6 x n geometric Jacobian of FRAME's origin at --at values: rows vx, vy, vz (m/s) and "
        "wx, wy, wz (rad/s) of FRAME relative to the root link, in --in's axes (default: the root link's), one "
        "column per moving joint (a mimic joint's motion added to its leader's). --wrench also prints tau = J^T w, "
        "w the wrench the tool exerts on the environment in --in's axes: the torque each motor adds to exert it.",
    )
    _common(jac)
    jac.add_argument(
        "--wrench",
        metavar="FX,FY,FZ[,MX,MY,MZ]",
        help="a force (N) and moment (N*m, each within 1e9) the tool exerts on the environment, in --in's axes: prints "
        "tau = J^T w",
    )
    add_robot_options(jac)
    jac.set_defaults(handler=_cmd_jacobian)


def read_robot_of(args: argparse.Namespace) -> ReadRobot:
    from ..reader.read_robot import read_robot  # (heavy: lxml)

    return read_robot(robot_input(args, args.robot))


@contextlib.contextmanager
def kinematics_flags(args: argparse.Namespace) -> Iterator[None]:
    """The kinematics' errors said with the option or argument that named what was wrong."""
    from ..kinematics import MovingFrame  # (heavy: lxml)
    from ..reader.kinematic_model import JointValueError, UnknownName  # (heavy: lxml)

    try:
        yield
    except UnknownName as exc:
        flag = "FRAME" if exc.name == args.frame else "--in"
        flag = f"--at {comment_text(exc.name)}" if exc.role == "joint" else flag
        raise XacrokitError(f"{flag}: {exc.detail}") from None
    except JointValueError as exc:
        raise XacrokitError(f"--at {comment_text(exc.joint)}={comment_text(exc.text)}: {exc.reason}") from None
    except MovingFrame as exc:
        raise XacrokitError(
            f"--in {args.in_frame}: it moves with joint {exc.joint!r}; give a frame fixed to the root"
        ) from None


def _common(parser: argparse.ArgumentParser) -> None:
    parser.add_argument("robot", help="a .urdf, .xacro or .yaml spec")
    parser.add_argument("frame", help="the link or frame whose pose is asked (a spec's frames are links)")
    parser.add_argument("--in", dest="in_frame", metavar="FRAME", help="the frame it is given in (default: the root)")
    parser.add_argument(
        "--at",
        action="append",
        default=[],
        metavar="NAME=VALUE",
        help="a joint's value, e.g. joint_1=30deg or slider=0.1m (rad or m without a unit); repeatable, each joint "
        "once",
    )
    parser.add_argument("--json", action="store_true", help="print JSON")


def _values(args: argparse.Namespace) -> dict[str, str]:
    """The --at values by joint name; a joint given twice is refused (which one was meant is not for us to guess)."""
    given: dict[str, str] = {}
    for item in args.at:
        name, sign, value = item.partition("=")
        if not sign or not name.strip() or not value.strip():
            raise XacrokitError(f"--at {comment_text(item)!r}: give NAME=VALUE, e.g. joint_1=30deg")
        name = name.strip()
        if name in given:
            raise XacrokitError(
                f"--at {comment_text(name)}: the joint is given twice ({comment_text(given[name])} and "
                f"{comment_text(value.strip())}): give each joint once"
            )
        given[name] = value.strip()
    return given


def _warn(warnings: list[LimitWarning]) -> None:
    for warning in warnings:
        sys.stderr.write(
            f"gen-robot: warning: --at {comment_text(warning.joint)}={comment_text(warning.text)}: {warning.outside}\n"
        )


def _numbers(text: str, kinds: tuple[str, ...], counts: tuple[int, ...], said: str) -> list[float]:
    """Comma-separated finite numbers, as many as one of ``counts``, the k-th a quantity of ``kinds[k]`` (SI, no
    unit) within what xacrokit takes of it; XacrokitError ``said`` otherwise (with the bound, for a number beyond)."""
    from ..shared.units import bound_problem  # (start-up: a command's work loads when it runs)

    try:
        values = [float(v) for v in text.split(",")]
    except ValueError:
        values = []
    if len(values) not in counts or not all(abs(v) < float("inf") for v in values):
        raise XacrokitError(said)
    beyond = next((b for b in map(bound_problem, kinds, values) if b is not None), None)
    if beyond is not None:
        raise XacrokitError(f"{said.partition(': ')[0]}: {beyond}")
    return values


def _cmd_pose(args: argparse.Namespace) -> int:
    from ..kinematics import pose  # (heavy: lxml)

    at = _values(args)
    robot = read_robot_of(args)
    with kinematics_flags(args):
        found = pose(robot, args.frame, in_frame=args.in_frame, at=at)
    _warn(found.warnings)
    described = pose_dict(found.matrix, args.rotation)
    if args.point is not None:
        described["point"] = _point(args.point, found.matrix)
    require_finite(described, "the pose")  # (in text too: never inf or NaN as an answer)
    if args.json:
        print_json({"frame": found.frame, "in": found.in_frame, **described})
        return 0
    frame, in_frame = comment_text(found.frame), comment_text(found.in_frame)  # (names as text: no control codes)
    lines = [f"pose of {frame} in {in_frame}{_at(found.values)}:"]
    lines.append("  xyz        " + _row(described["xyz"]) + "  m")
    lines.append("  rpy        " + _row(described["rpy"]) + "  rad (URDF: R = Rz(y) Ry(p) Rx(r))")
    lines.append("  quat_xyzw  " + _row(described["quat_xyzw"]))
    lines += ["  matrix     " + _row(row) for row in described["matrix"][:1]]
    lines += ["             " + _row(row) for row in described["matrix"][1:]]
    if args.rotation not in ("rpy", "quat_xyzw", "matrix"):
        label = "euler" if euler_sequence(args.rotation) else args.rotation
        lines.append(f"  {label:<10} {_form_text(described['rotation']['value'])}")
    if "point" in described:
        point = comment_text(args.point)
        lines.append(f"  point      {_row(described['point'])}  m in {in_frame} ({point} in {frame})")
    sys.stdout.write("\n".join(lines) + "\n")
    return 0


def _cmd_jacobian(args: argparse.Namespace) -> int:
    from ..kinematics import jacobian, joint_torques  # (heavy: lxml)

    at = _values(args)
    robot = read_robot_of(args)
    with kinematics_flags(args):
        found = jacobian(robot, args.frame, in_frame=args.in_frame, at=at)
    _warn(found.pose.warnings)
    torques = None
    if args.wrench is not None:
        said = f"--wrench {args.wrench!r}: give FX,FY,FZ or FX,FY,FZ,MX,MY,MZ (N, N*m)"
        kinds = ("force",) * 3 + ("torque",) * 3
        torques = joint_torques(found, _numbers(args.wrench, kinds, (3, 6), said))
    rows = [[float(v) for v in row] for row in found.matrix]
    out: dict[str, Any] = {"frame": found.pose.frame, "in": found.pose.in_frame, "joints": found.joints}
    out["jacobian"] = rows
    if torques is not None:
        out["torques"] = dict(zip(found.joints, map(float, torques), strict=True))
    require_finite(out, "the Jacobian")  # (in text too: never inf or NaN as an answer)
    if args.json:
        print_json(out)
        return 0
    frame, in_frame = comment_text(found.pose.frame), comment_text(found.pose.in_frame)  # (no control codes)
    if not found.joints:
        sys.stdout.write(f"{frame}: the robot has no joint to move: its Jacobian has no column\n")
        return 0
    names = [comment_text(n) for n in found.joints]
    width = max([len(n) for n in names] + [12])
    lines = [f"jacobian of {frame}'s origin in {in_frame}'s axes{_at(found.pose.values)}:"]
    lines.append("  " + " " * 3 + " ".join(f"{n:>{width}}" for n in names))
    for label, row in zip(("vx", "vy", "vz", "wx", "wy", "wz"), rows, strict=True):
        lines.append(f"  {label} " + " ".join(f"{v:>{width}.6g}" for v in row))
    if torques is not None:
        lines.append("tau = J^T w (N*m, N for a prismatic joint; the torque each motor adds to exert the wrench):")
        lines += [f"  {name:<{width}} {float(t):.6g}" for name, t in zip(names, torques, strict=True)]
    sys.stdout.write("\n".join(lines) + "\n")
    return 0


def _form_text(value: Any) -> str:
    """A rotation form's value on one line: numbers as the rows print them, a mapping's keys named."""
    if isinstance(value, dict):
        return "  ".join(f"{key} {_form_text(part)}" for key, part in value.items())
    if isinstance(value, list) and value and isinstance(value[0], list):
        return "  ".join(_row(row) for row in value)
    return _row(value) if isinstance(value, list) else str(value) if isinstance(value, str) else _row([value]).strip()


def pose_dict(matrix: Any, rotation: str = "rpy") -> dict[str, Any]:
    """A 4x4 pose as the commands print it: xyz, rpy (URDF), quat_xyzw (w >= 0), the matrix, and ``rotation`` in the
    form named (:func:`xacrokit.shared.transforms.rotation_forms`)."""
    import numpy as np  # (heavy: numpy)

    from ..shared.transforms import rotation_forms  # (heavy: numpy)

    sequence = euler_sequence(rotation)
    forms = rotation_forms(np.asarray(matrix)[:3, :3], **({"euler": sequence} if sequence else {}))
    return {
        "xyz": [float(v) for v in np.asarray(matrix)[:3, 3]],
        "rpy": forms["rpy"],
        "quat_xyzw": forms["quat_xyzw"],
        "matrix": [[float(v) for v in row] for row in np.asarray(matrix)],
        "rotation": {"form": rotation, "value": forms["euler" if sequence else rotation]},
    }


def _point(text: str, matrix: Any) -> list[float]:
    """T p for a point ``X,Y,Z`` (m, each within 1e4 m as every length xacrokit takes) given as text."""
    import numpy as np  # (heavy: numpy)

    given = _numbers(text, ("length",) * 3, (3,), f"--point {text!r}: give X,Y,Z in metres")
    with np.errstate(over="ignore", invalid="ignore"):  # (judged below)
        point = [float(v) for v in (np.asarray(matrix) @ np.array([*given, 1.0]))[:3]]
    if not all(np.isfinite(point)):  # (a backstop: a pose and a point within their bounds stay finite)
        largest = max(given, key=abs)
        raise XacrokitError(
            f"--point {text!r}: the result overflows (the point {largest:g} m is beyond what a float holds after "
            "the transform)"
        )
    return point


def _at(values: dict[str, float]) -> str:
    return (
        " at " + ", ".join(f"{comment_text(k)} = {v:.6g}" for k, v in values.items()) if values else " at every joint 0"
    )


def listed_values(values: dict[str, float]) -> str:
    """Joint values, one a line, nine decimals; names as text (a name's control codes escaped)."""
    return "".join(f"  {comment_text(name)} = {value:.9f}\n" for name, value in values.items())


def _row(values: Any) -> str:
    """Nine decimals, a value that rounds to zero printed as 0 (not -0.000000000); --json has every digit."""
    return " ".join(f"{(float(v) if abs(float(v)) >= 5e-10 else 0.0):>13.9f}" for v in values)
