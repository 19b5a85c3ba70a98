"""The kinematics commands, ``gen-robot pose`` and ``gen-robot jacobian`` (``ik`` is :mod:`.ik_command`): their
options and what they print (shells over :mod:`xacrokit.kinematics`, imported when the command runs: the CLI starts
without numpy)."""

from __future__ import annotations

import argparse
import contextlib
import sys
from collections.abc import Iterator, Mapping
from typing import TYPE_CHECKING, Any

from ..errors import XacrokitError
from ..shared.value_text import comment_text
from .arguments import add_robot_options, robot_input
from .joint_arguments import JOINT_ORDER, Given, at_values, q_values, row_values, texts
from .json_output import print_json, require_finite

if TYPE_CHECKING:
    from ..kinematics import Jacobian, Pose
    from ..reader.kinematic_model import LimitWarning
    from ..reader.read_robot import ReadRobot
    from .rows_file import Row

ROTATION_FORMS = ("rpy", "quat_xyzw", "quat_wxyz", "rotvec", "axis_angle", "matrix", "points")
EULER_FORMS = ("euler", "intrinsic", "extrinsic")  # (euler:SEQ scipy's case; intrinsic:AXES, extrinsic:AXES said)


def rotation_form(text: str) -> str:
    """``--rotation``'s value, checked: one of :data:`ROTATION_FORMS`, or Euler angles as ``euler:XYZ`` (scipy's
    sequence: upper case intrinsic, lower case extrinsic), ``intrinsic:ZYZ`` or ``extrinsic:xyz`` (the kind said, the
    axes in either case), the same twelve sequences an origin's ``euler`` takes."""
    if text in ROTATION_FORMS:  # (argparse checks the default too: the named forms need no import)
        return text
    from ..validate.quantities import EULER_SEQUENCES, euler_axes_problem, euler_sequence_problem  # (start-up)

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
        description="Print the pose of FRAME in --in (default: the root link) with the joints at --q and --at "
        "values (0 where not given; a mimic joint follows its leader): xyz (m), rpy (rad, URDF's fixed-axis roll, "
        "pitch, yaw), the quaternion (x, y, z, w) and the 4x4 matrix T_IN_FRAME; with --configurations, one pose per "
        "row of a file. ROBOT is a spec, URDF or xacro document.",
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
    pose.add_argument(
        "--configurations",
        metavar="FILE",
        help="a pose for each row of FILE (a trajectory's frames), the robot read once: a .csv (a header row of joint "
        "names, or no header and the values in the joints' order) or a .yaml (a list of mappings joint: value, or of "
        "lists in the joints' order); units as --at takes them; --at overrides a row's value (not with --q)",
    )
    add_robot_options(pose)
    pose.set_defaults(handler=_cmd_pose)
    jac = commands.add_parser(
        "jacobian",
        help="the geometric Jacobian of a frame's origin (6 x n, linear rows first), and tau = J^T w for a wrench",
        description="Print the 6 x n geometric Jacobian of FRAME's origin at --q and --at values: rows vx, vy, vz "
        "(m/s) and wx, wy, wz (rad/s) of FRAME relative to the root link, in --in's axes (default: the root link's), "
        "one column per moving joint (a mimic joint's motion added to its leader's). --exerts also prints tau = J^T "
        "w, w the wrench the tool exerts on the environment in --in's axes: the torque each motor adds to exert it "
        "(size --load takes the opposite: the force the environment applies to the robot).",
    )
    _common(jac)
    jac.add_argument(
        "--exerts",
        metavar="FX,FY,FZ[,MX,MY,MZ]",
        help="the wrench the tool exerts on the environment: force (N) and moment (N*m, each within 1e9), in --in's "
        "axes at FRAME's origin; prints tau = J^T w (a tool pressing 20 N down: --exerts 0,0,-20)",
    )
    # (--wrench, its old name, kept one release: the same sign; renamed so that the flag says which side of the load)
    jac.add_argument("--wrench", metavar="FX,FY,FZ[,MX,MY,MZ]", help="deprecated: --exerts (the same values)")
    add_robot_options(jac)
    jac.set_defaults(handler=_cmd_jacobian)


def read_robot_of(args: argparse.Namespace) -> ReadRobot:
    from ..reader.read_robot import read_robot  # (heavy: lxml)

    return read_robot(robot_input(args, args.robot), emitted=True)  # (a spec: the URDF gen-robot SPEC writes)


@contextlib.contextmanager
def kinematics_flags(args: argparse.Namespace, given: Mapping[str, Given] | None = None) -> Iterator[None]:
    """The kinematics' errors said with the option or argument that named what was wrong (a joint's value with
    where ``given`` says it was given: --at, --q or a file's line; --at without it)."""
    from ..kinematics import MovingFrame  # (heavy: lxml)
    from ..reader.kinematic_model import JointValueError, UnknownName  # (heavy: lxml)

    given = given or {}
    try:
        yield
    except UnknownName as exc:
        flag = "FRAME" if exc.name == args.frame else "--in"
        where = given[exc.name].where if exc.name in given else f"--at {comment_text(exc.name)}"
        raise XacrokitError(f"{where if exc.role == 'joint' else flag}: {exc.detail}") from None
    except JointValueError as exc:
        said = given[exc.joint].said if exc.joint in given else None
        said = said or f"--at {comment_text(exc.joint)}={comment_text(exc.text)}"
        raise XacrokitError(f"{said}: {exc.reason}") from None
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
        metavar="NAME=VALUE[,...]",
        help="joint values by name, e.g. joint_1=30deg or joint_1=30deg,slider=0.1m (rad or m without a unit); "
        "repeatable, each joint once; overrides --q's value of a joint it names",
    )
    parser.add_argument(
        "--q",
        metavar="V1,V2,...",
        help=f"every joint's value, in order (units as --at, e.g. 30deg,-0.5,0.1m): {JOINT_ORDER}",
    )
    parser.add_argument("--json", action="store_true", help="print JSON")


def _warn(warnings: list[LimitWarning], given: Mapping[str, Given]) -> None:
    for warning in warnings:
        sys.stderr.write(f"gen-robot: warning: {given[warning.joint].said}: {warning.outside}\n")


def _joint_names(robot: ReadRobot) -> list[str]:
    """The joints one sets, in the file's order (what --q's values and a positional row follow)."""
    return [joint.name for joint in robot.kinematics.joints]


def _given(args: argparse.Namespace, robot: ReadRobot, at: dict[str, Given]) -> dict[str, Given]:
    """The joint values of --q, with --at's over them (--at names the joints it changes: it wins)."""
    return {**q_values(args.q, _joint_names(robot)), **at} if args.q is not None else at


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

    at = at_values(args.at)
    if args.configurations is not None:
        return _pose_rows(args, at)
    robot = read_robot_of(args)
    given = _given(args, robot, at)
    with kinematics_flags(args, given):
        found = pose(robot, args.frame, in_frame=args.in_frame, at=texts(given))
    _warn(found.warnings, given)
    described = _described(found, args, _joint_names(robot))
    if args.json:
        print_json(described)
        return 0
    sys.stdout.write(_pose_text(found, described, args, ""))
    return 0


def _pose_rows(args: argparse.Namespace, at: dict[str, Given]) -> int:
    """A pose per row of --configurations, on the robot read once (its kinematic model built once)."""
    from ..kinematics import pose  # (heavy: lxml)
    from .rows_file import read_rows  # (start-up: a command's work loads when it runs)

    if args.q is not None:
        raise XacrokitError("--q and --configurations: the file gives every row's values; give one of them")
    rows: list[Row] = read_rows(args.configurations)
    robot = read_robot_of(args)
    joints = _joint_names(robot)
    described, shown = [], []
    for row in rows:
        given = {**row_values(row, args.configurations, joints), **at}
        with kinematics_flags(args, given):
            found = pose(robot, args.frame, in_frame=args.in_frame, at=texts(given))
        _warn(found.warnings, given)
        described.append({"line": row.line, **_described(found, args, joints)})
        if not args.json:
            shown.append(_pose_text(found, described[-1], args, f"{comment_text(args.configurations)}:{row.line}: "))
    if args.json:
        print_json(described)
    else:
        sys.stdout.write("".join(shown))
    return 0


def _described(found: Pose, args: argparse.Namespace, joints: list[str]) -> dict[str, Any]:
    """A pose as --json prints it: the frames, the joints one sets (their order: --q's) and their values, the pose
    in every form, and --point's image."""
    described: dict[str, Any] = {"frame": found.frame, "in": found.in_frame, "joints": joints}
    described["values"] = {name: float(found.values.get(name, 0.0)) for name in joints}
    described |= pose_dict(found.matrix, args.rotation)
    if args.point is not None:
        described["point"] = _point(args.point, found.matrix)
    require_finite(described, "the pose")  # (in text too: never inf or NaN as an answer)
    return described


def _pose_text(found: Pose, described: dict[str, Any], args: argparse.Namespace, where: str) -> str:
    frame, in_frame = comment_text(found.frame), comment_text(found.in_frame)  # (names as text: no control codes)
    lines = [f"{where}pose of {frame} in {in_frame}{_at(found.values)}:"]
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
    return "\n".join(lines) + "\n"


def _wrench(args: argparse.Namespace) -> tuple[str, str] | None:
    """The wrench the tool exerts, with the flag it was given by (--exerts, or --wrench: deprecated, said)."""
    if args.exerts is not None and args.wrench is not None:
        raise XacrokitError("--exerts and --wrench: --wrench is --exerts' old name; give --exerts alone")
    if args.wrench is not None:
        sys.stderr.write(
            "gen-robot jacobian: warning: --wrench is deprecated: use --exerts (the same values: the wrench the tool "
            "exerts on the environment, tau = J^T w; size --load takes the opposite, the force on the robot)\n"
        )
        return "--wrench", args.wrench
    return None if args.exerts is None else ("--exerts", args.exerts)


def _cmd_jacobian(args: argparse.Namespace) -> int:
    from ..kinematics import jacobian, joint_torques  # (heavy: lxml)

    at = at_values(args.at)
    wrench = _wrench(args)
    robot = read_robot_of(args)
    given = _given(args, robot, at)
    with kinematics_flags(args, given):
        found = jacobian(robot, args.frame, in_frame=args.in_frame, at=texts(given))
    _warn(found.pose.warnings, given)
    torques = None
    if wrench is not None:
        flag, text = wrench
        said = f"{flag} {text!r}: give FX,FY,FZ or FX,FY,FZ,MX,MY,MZ (N, N*m)"
        kinds = ("force",) * 3 + ("torque",) * 3
        torques = joint_torques(found, _numbers(text, kinds, (3, 6), said))
    rows = [[float(v) for v in row] for row in found.matrix]
    out: dict[str, Any] = {"frame": found.pose.frame, "in": found.pose.in_frame, "joints": found.joints}
    out["jacobian"] = rows
    if torques is not None:
        out["torques"] = dict(zip(found.joints, map(float, torques), strict=True))
    require_finite(out, "the Jacobian")  # (in text too: never inf or NaN as an answer)
    if args.json:
        print_json(out)
        return 0
    sys.stdout.write(_jacobian_text(found, rows, torques))
    return 0


def _jacobian_text(found: Jacobian, rows: list[list[float]], torques: Any) -> str:
    frame, in_frame = comment_text(found.pose.frame), comment_text(found.pose.in_frame)  # (no control codes)
    if not found.joints:
        return f"{frame}: the robot has no joint to move: its Jacobian has no column\n"
    names = [comment_text(n) for n in found.joints]
    width = max([len(n) for n in names] + [12])
    lines = [f"jacobian of {frame}'s origin in {in_frame}'s axes{_at(found.pose.values)}:"]
    lines.append("  " + " " * 3 + " ".join(f"{n:>{width}}" for n in names))
    for label, row in zip(("vx", "vy", "vz", "wx", "wy", "wz"), rows, strict=True):
        lines.append(f"  {label} " + " ".join(f"{v:>{width}.6g}" for v in row))
    if torques is not None:
        lines.append("tau = J^T w (N*m, N for a prismatic joint; the torque each motor adds to exert the wrench):")
        lines += [f"  {name:<{width}} {float(t):.6g}" for name, t in zip(names, torques, strict=True)]
    return "\n".join(lines) + "\n"


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
    asked = "euler" if sequence else rotation
    # (only the forms printed: scipy, which rotvec and Euler angles need, is not loaded for the others)
    only = {"rpy", "quat_xyzw", asked}
    forms = rotation_forms(np.asarray(matrix)[:3, :3], only=only, **({"euler": sequence} if sequence else {}))
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
