"""Structure rules: the links and joints form one tree (S001-S006), under plain names (N001)."""

from __future__ import annotations

import re
from collections.abc import Iterator, Sequence

from ..shared.kinematic_tree import Tree
from ..shared.urdf_view import Joint, Link
from .findings import Finding, rule_table
from .urdf_document import Doc

RULES = rule_table(
    {
        "S001": ("one-root", "error", "exactly one link has no parent"),
        "S002": ("no-cycle", "error", "no chain of joints leads back to where it started"),
        "S003": ("joint-links-exist", "error", "every joint's parent and child is a link of the document"),
        "S004": ("unique-link-names", "error", "no two links share a name"),
        "S005": ("unique-joint-names", "error", "no two joints share a name"),
        "S006": ("one-parent", "error", "no link is the child of two joints"),
        "S007": (
            "robot-named",
            "error",
            "the <robot> has a name and at least one link (urdfdom rejects a robot without either: an expanded macro "
            "file, say)",
        ),
        "U004": (
            "xacro-expanded",
            "error",
            "no xacro is left in the document (xacro: elements, ${...} or $(...) in names and values other than "
            "file names): consumers do not expand it",
        ),
        "N001": (
            "name-plain",
            "warning",
            "link and joint names are not empty, hold no whitespace or control characters and do not start with '/' "
            "(tf2 refuses such frame ids; ROS tools split on spaces)",
        ),
    }
)


def _duplicate_names(doc: Doc, parts: Sequence[Link | Joint], kind: str, rule: str) -> Iterator[Finding]:
    seen: dict[str, Link | Joint] = {}
    for part in parts:
        if part.name in seen:
            message = f"{kind} {part.name!r} is defined twice (also on line {seen[part.name].line}); rename one"
            yield doc.finding(rule, kind, part.name, message, part.element)
        seen[part.name] = part


XACRO_NAMESPACE = "http://www.ros.org/wiki/xacro"
_UNEXPANDED = re.compile(r"\$\{|\$\(")


def xacro_rules(doc: Doc) -> Iterator[Finding]:
    """U004: a xacro document read as a URDF (its xacro: elements are unknown to consumers, which then see another
    robot or none), or ${...}/$(...) left in a name or a value by an expansion that did not happen."""
    for element in doc.root.iter(f"{{{XACRO_NAMESPACE}}}*"):  # (lxml's walk, in document order, selects them)
        if isinstance(element.tag, str):
            local = element.tag.split("}", 1)[1]
            yield doc.finding(
                "U004",
                "robot",
                doc.root.get("name", ""),
                f"<xacro:{local}> in the document: it is xacro, not URDF; check the .xacro (gen-robot check FILE.xacro "
                "expands it) or expand it first (gen-robot expand)",
                element,
            )
            return  # (one says it; the rest would say it again)
    said = 0
    # (the attributes that hold "${" or "$(", in document order: one pass of lxml's XPath over the document)
    for found in doc.root.xpath("descendant-or-self::*/@*[contains(., '${') or contains(., '$(')]"):
        element, attribute, value = found.getparent(), found.attrname, str(found)
        # (a file name may really hold "${": a file that is not there is R003's, whatever its name)
        if attribute != "filename" and _UNEXPANDED.search(value) and said < 5:
            said += 1
            owner = (
                element
                if element.tag in ("link", "joint")
                else next((a for a in element.iterancestors() if a.tag in ("link", "joint")), doc.root)
            )
            kind = owner.tag if owner.tag in ("link", "joint") else "robot"
            yield doc.finding(
                "U004",
                kind,
                owner.get("name", ""),
                f'{element.tag} {attribute}="{value}" holds an unexpanded xacro expression; consumers read it as '
                "text: expand the document with its arguments",
                element,
            )


def structure_rules(doc: Doc) -> Iterator[Finding]:
    missing = [
        what for what, gone in (("name", not (doc.view.name or "").strip()), ("link", not doc.view.links)) if gone
    ]
    if missing:
        yield doc.finding(
            "S007",
            "robot",
            doc.root.get("name", ""),
            f"the <robot> has no {' and no '.join(missing)}; urdfdom rejects it (a macro file expanded without a call "
            "to its macro?)",
            doc.root,
        )
    yield from _duplicate_names(doc, doc.view.links, "link", "S004")
    yield from _duplicate_names(doc, doc.view.joints, "joint", "S005")
    tree: Tree[str] = Tree()  # child -> (parent, joint)
    yield from _joints_into(tree, doc)
    roots = tree.roots(doc.link_names)
    in_cycles = sorted(doc.link_names - tree.reachable(roots))
    if in_cycles:
        yield doc.finding(
            "S002",
            "link",
            in_cycles[0],
            f"links {', '.join(in_cycles)} form a cycle; break it by removing one of its joints",
        )
    if len(roots) != 1 and doc.view.links:
        what = "no link" if not roots else f"{len(roots)} links ({', '.join(roots)})"
        yield doc.finding(
            "S001",
            "robot",
            doc.root.get("name", ""),
            f"{what} have no parent; a robot has exactly one root: connect the trees with joints",
        )


def _joints_into(tree: Tree[str], doc: Doc) -> Iterator[Finding]:
    """Add every joint to ``tree``: S003 for a joint naming no link, S002 for one that closes a cycle, S006 for a
    second parent."""
    for joint in doc.view.joints:
        name, parent, child = joint.name, joint.parent or "", joint.child or ""
        missing = [
            f"{role} {value!r}" for role, value in (("parent", parent), ("child", child)) if value not in doc.link_names
        ]
        if missing:
            said = f"{' and '.join(missing)} not a link of this robot"
            yield doc.finding("S003", "joint", name, said, joint.element)
            continue
        first = tree.add(parent, child, name)
        if first is not None:
            loop = tree.path_up(parent, child)
            if loop:  # following this joint leads back to the child: a cycle hanging off the tree
                yield doc.finding(
                    "S002",
                    "joint",
                    name,
                    f"joint {name!r} closes a cycle {' -> '.join([*reversed(loop), child])}; remove it",
                    joint.element,
                )
            else:
                first_parent, first_joint = first
                yield doc.finding(
                    "S006",
                    "link",
                    child,
                    f"link {child!r} has two parents: {first_parent!r} (joint "
                    f"{first_joint!r}) and {parent!r} (joint {name!r}); a URDF is "
                    "a tree: remove one of the joints",
                    joint.element,
                )


_UNPLAIN = re.compile(r"[\s\x00-\x1f\x7f]")


def name_rules(doc: Doc) -> Iterator[Finding]:
    parts: tuple[tuple[str, Sequence[Link | Joint]], ...] = (("link", doc.view.links), ("joint", doc.view.joints))
    for kind, named in parts:
        for part in named:
            name, element = part.name, part.element
            if not name:
                problem = "has no name"
            elif _UNPLAIN.search(name):
                problem = "has whitespace or a control character in its name"
            elif name.startswith("/") and kind == "link":
                problem = "has a name starting with '/', which tf2 refuses as a frame id"
            else:
                continue
            yield doc.finding("N001", kind, name, f"{kind} {name!r} {problem}; use letters, digits and _", element)
