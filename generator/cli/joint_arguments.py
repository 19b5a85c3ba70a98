"""Joint values as the kinematics commands take them: ``--at NAME=VALUE[,NAME=VALUE...]`` (repeatable), ``--q
V1,V2,...`` (a vector in the joints' order) and the rows of a ``--configurations`` file; each value kept as text
(the kinematics parse it, units and all) with where it was given, for the messages about it."""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from typing import TYPE_CHECKING, NamedTuple

from ..errors import XacrokitError
from ..shared.value_text import comment_text

if TYPE_CHECKING:
    from .rows_file import Row  # (the reader loads YAML: only a command that reads a file loads it)

JOINT_ORDER = (
    "the joints one sets (revolute, continuous and prismatic joints that mimic none) in the file's order; "
    "`gen-robot pose ROBOT FRAME --json` lists them as `joints`"
)


class Given(NamedTuple):
    """A joint's value as given: its text, ``where`` it was given (``--at joint_1``, ``--q value 2 (joint_2)``,
    ``traj.csv:3: joint_2``) and ``said``, the two together as messages quote them (``--at joint_1=30deg``). (A
    named tuple, not a dataclass: the command line starts without loading dataclasses' inspect.)"""

    text: str
    where: str
    said: str


def texts(given: Mapping[str, Given]) -> dict[str, str]:
    """The values' texts by joint name, as the kinematics take them."""
    return {name: value.text for name, value in given.items()}


def at_values(items: Sequence[str]) -> dict[str, Given]:
    """The ``--at`` values by joint name (each ``--at`` one pair or several, comma-separated); a joint given twice is
    refused (which one was meant is not for us to guess)."""
    given: dict[str, Given] = {}
    for item in items:
        for pair in item.split(","):
            name, sign, value = pair.partition("=")
            name, value = name.strip(), value.strip()
            if not sign or not name or not value:
                raise XacrokitError(
                    f"--at {comment_text(item)!r}: give NAME=VALUE, or several as NAME=VALUE,NAME=VALUE, e.g. "
                    "joint_1=30deg,joint_2=-0.5"
                )
            if name in given:
                raise XacrokitError(
                    f"--at {comment_text(name)}: the joint is given twice ({comment_text(given[name].text)} and "
                    f"{comment_text(value)}): give each joint once"
                )
            shown = comment_text(name)
            given[name] = Given(value, f"--at {shown}", f"--at {shown}={comment_text(value)}")
    return given


def _count_problem(count: int, joints: Sequence[str]) -> str:
    names = ", ".join(comment_text(n) for n in joints) if joints else "none"
    joint_s = "joint" if len(joints) == 1 else "joints"
    value_s = "value" if count == 1 else "values"
    return f"{count} {value_s} for the robot's {len(joints)} {joint_s} ({names}, in this order)"


def q_values(text: str, joints: Sequence[str]) -> dict[str, Given]:
    """``--q``'s values by joint name: one per joint one sets, in the file's order (``joints``)."""
    values = [v.strip() for v in text.split(",")]
    if len(values) != len(joints):
        raise XacrokitError(f"--q {comment_text(text)!r}: {_count_problem(len(values), joints)}")
    for index, value in enumerate(values):
        if not value:
            raise XacrokitError(f"--q {comment_text(text)!r}: value {index + 1} ({joints[index]}) is empty")
    return {
        name: Given(
            value,
            f"--q value {k + 1} ({comment_text(name)})",
            f"--q value {k + 1} ({comment_text(name)}={comment_text(value)})",
        )
        for k, (name, value) in enumerate(zip(joints, values, strict=True))
    }


def row_values(row: Row, file: str, joints: Sequence[str]) -> dict[str, Given]:
    """A ``--configurations`` row's values by joint name: named by its columns, or one per joint in ``joints``'
    order; each said with the file's line and the column (a name that is no joint: a CSV's header line)."""
    if row.names is None and len(row.values) != len(joints):
        raise XacrokitError(f"{file}:{row.line}: {_count_problem(len(row.values), joints)}")
    names = row.names if row.names is not None else joints
    given = {}
    for index, (name, value) in enumerate(zip(names, row.values, strict=True)):
        shown, place = comment_text(name), f"{file}:{row.line_of(index)}"
        if row.names is not None:
            named = f"{file}:{row.header_line}: column {shown}" if row.header_line is not None else f"{place}: {shown}"
            given[name] = Given(value, named, f"{place}: {shown}={comment_text(value)}")
        else:
            said = f"{place}: value {index + 1} ({shown}={comment_text(value)})"
            given[name] = Given(value, f"{place}: value {index + 1} ({shown})", said)
    return given
