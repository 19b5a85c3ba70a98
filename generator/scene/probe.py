"""Learning a third-party macro's names: expand its instance alone, before the scene is written, and check what it
makes against the scene's rules (every name holds the prefix, it hangs from its parent link, it does not make that
link itself)."""

from __future__ import annotations

import contextlib
import io
import re
import tempfile
from pathlib import Path

from ..errors import ExpandError, SpecError
from ..load import PathKey, RawSpec
from ..model import Instance, Origin, ThirdPartyMacro
from ..shared.urdf_view import read_view

Found = tuple[tuple[str, ...], tuple[str, ...]]  # (links, joints)


def probe_names(
    raw: RawSpec, name: str, macro: ThirdPartyMacro, prefix: str, parent: str
) -> tuple[Found | None, list[SpecError]]:
    """The links (all but ``parent``) and joints instance ``name`` makes on the link ``parent``, or None and the error
    (located at the instance's ``xacro`` entry) that says why the scene cannot use it."""

    from ..expansion.xacro_expand import expand_file  # (heavy: xacro)
    from ..render import render_probe  # (heavy: jinja2)

    where: PathKey = ("instances", name, "xacro")
    instance = Instance(name=name, prefix=prefix, parent=parent, origin=Origin(), links=(), joints=(), macro=macro)
    with tempfile.TemporaryDirectory(prefix="xacrokit-probe-") as folder:
        probe = Path(folder) / "probe.urdf.xacro"
        probe.write_text(render_probe(instance), encoding="utf-8")
        try:
            with contextlib.redirect_stderr(io.StringIO()):  # (xacro's warnings come once, from the real expansion)
                urdf = expand_file(probe)
        except ExpandError as exc:
            message = f"expanding {macro.macro} from {macro.file} failed: {exc.message}{_hint(exc, macro)}"
            return None, [raw.error(where, message)]
    view = read_view(urdf, f"{macro.file} (expanded)")
    every_link = [link.name for link in view.links]
    links = tuple(n for n in every_link if n != parent)
    joints = tuple(joint.name for joint in view.joints)
    problems = []
    if every_link.count(parent) > 1:
        problems.append(f"it makes a link {parent!r} itself, the name of the link it is mounted on")
    unprefixed = [n for n in (*links, *joints) if prefix not in n]  # (world_to_${prefix}base carries it too)
    if unprefixed:
        shown = ", ".join(unprefixed[:6]) + (f" and {len(unprefixed) - 6} more" if len(unprefixed) > 6 else "")
        problems.append(
            f"its names {shown} do not hold the prefix {prefix!r} (if its prefix parameter is not called "
            f"{macro.prefix_param!r}, set prefix_param)"
        )
    hanging = [joint.parent for joint in view.joints]
    if parent not in hanging:
        problems.append(
            f"no joint of it hangs from the link it is mounted on, {parent!r} (if its parent parameter is not called "
            f"{macro.parent_param!r}, set parent_param)"
        )
    if problems:
        return None, [raw.error(where, f"macro {macro.macro} from {macro.file}: " + "; ".join(problems))]
    return (links, joints), []


def _hint(exc: ExpandError, macro: ThirdPartyMacro) -> str:
    """What to change when xacro refused a parameter the scene passed."""
    invalid = re.search(r'Invalid parameter "([^"]*)"', exc.message)
    if invalid and invalid[1] in (macro.prefix_param, macro.parent_param):  # (UR's macro says tf_prefix)
        return (
            f" (the scene passes {macro.prefix_param!r} and {macro.parent_param!r}: set prefix_param and "
            "parent_param to the macro's own names for them)"
        )
    if invalid:
        return f" (the macro has no parameter {invalid[1]!r}: check the names under params)"
    return ""
