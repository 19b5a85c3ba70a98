"""A robot's collision matrix as the SRDF says it, without the sampling that finds it (``collision_pairs``, which
needs pinocchio and numpy): the pairs and their reasons, how they are sampled, the adjacent pairs (read off the
URDF alone), and the matrices kept in the user's cache folder.

A matrix is kept under the SHA-256 digest of everything its sampling reads: the URDF's text, the package's name and
its meshes' bytes, the home pose, the ``Sampling``, the installs of pinocchio and coal (whose collision checks
decide it) and the sampling's own module (an edit of it samples again). A package generated again with the same
robot (a second run, a changed description or launch file, a test) takes it from there in milliseconds; a changed
link, joint, limit or mesh samples again. The cached file is JSON, read as data only.
"""

from __future__ import annotations

import copy
import hashlib
import itertools
import json
import os
from collections.abc import Callable, Iterable, Mapping
from dataclasses import asdict, dataclass
from pathlib import Path
from typing import TYPE_CHECKING

from lxml import etree

from .. import __version__
from ..shared.ros_packages import mesh_file
from ..shared.user_cache import kept, source_stamp
from ..shared.xml_parse import read_urdf_root

if TYPE_CHECKING:
    from ..shared.urdf_view import UrdfView

Pair = tuple[str, str]  # two link names, in alphabetical order (as MoveIt writes them)
REASONS = ("Adjacent", "Default", "Never", "Always")


@dataclass(frozen=True)
class Sampling:
    """How the configurations are drawn: how many, from which seed, the share of them in collision that makes a pair
    ``Always``, how close (m) a pair may come in them and still be ``Never``, and how many pair checks it may take
    (a robot of many pairs within reach of each other gets fewer samples, and none below 1,000)."""

    samples: int = 10_000
    seed: int = 0
    always: float = 0.95
    margin: float = 0.05
    budget: int = 40_000_000  # pair checks it may take (about 5 s): fewer samples for a robot of more pairs
    meshes: bool = False  # sample a robot whose collision geometry holds meshes (coal on meshes: minutes for TIAGo)


@dataclass(frozen=True)
class Judged:
    """The disabled pairs (pair -> reason), the configurations sampled to judge them (0: none, ``pairs`` being too
    many: Never and Always then only where the robot's reach proves it) and the pairs left to sample."""

    disabled: dict[Pair, str]
    samples: int
    pairs: int
    meshes: bool = False  # (not sampled: the collision geometry holds meshes and the sampling did not ask for them)


def pair(first: str, second: str) -> Pair:
    """Two link names in MoveIt's order."""
    return (first, second) if first < second else (second, first)


def links_and_joints(urdf: str, where: str) -> tuple[list[str], list[tuple[str | None, str | None]]]:
    """The links of a URDF text that have collision geometry, and its joints' parent and child links: all the SRDF
    needs of a robot it does not sample (read without the typed view, whose every origin and shape a 1,000-link
    fleet's SRDF would pay for)."""
    root = read_urdf_root(urdf, where)
    solid = [link.get("name", "") for link in root.iterfind("link") if link.find("collision") is not None]
    joints = []
    for joint in root.iterfind("joint"):
        parent, child = joint.find("parent"), joint.find("child")
        joints.append((None if parent is None else parent.get("link"), None if child is None else child.get("link")))
    return solid, joints


def adjacent_pairs(joints: Iterable[tuple[str | None, str | None]], solid: set[str]) -> frozenset[Pair]:
    """Links with collision geometry (``solid``) that a joint (its parent and child) joins, directly or through links
    without any (the setup assistant's connection graph, computeConnectionGraph: a link without geometry joins all
    its neighbours, until nothing changes). That closure, found at once: two solid links a joint joins, and every two
    solid links that touch one group of links without geometry joined to each other (a fleet's world link and the
    bases fixed to it: one group)."""
    graph: dict[str, set[str]] = {}
    for parent, child in joints:
        if parent and child:
            graph.setdefault(parent, set()).add(child)
            graph.setdefault(child, set()).add(parent)
    found = {pair(link, other) for link, others in graph.items() if link in solid for other in others if other in solid}
    seen: set[str] = set()
    for start in graph:
        if start in solid or start in seen:
            continue
        group, touched, left = {start}, set(), [start]  # (links without geometry joined; the solid ones they touch)
        while left:
            for other in graph[left.pop()]:
                if other in solid:
                    touched.add(other)
                elif other not in group:
                    group.add(other)
                    left.append(other)
        seen |= group
        found.update(itertools.combinations(sorted(touched), 2))
    return frozenset(found)


Meshes = tuple[tuple[str, str | bytes], ...]


def matrix_key(urdf: str, package: str, meshes: Meshes, home: tuple[tuple[str, float], ...], sampling: Sampling) -> str:
    """The digest a matrix is kept under (see the module's docstring)."""
    digest = hashlib.sha256()
    installs = source_stamp("pinocchio", "coal", "xacrokit.moveit.collision_pairs")
    header = {"urdf": urdf, "package": package, "home": home, "sampling": asdict(sampling), "installs": installs}
    digest.update(json.dumps(header, sort_keys=True).encode("utf-8"))
    for path, content in meshes:
        digest.update(b"\0" + path.encode("utf-8") + b"\0")
        digest.update(content if isinstance(content, bytes) else content.encode("utf-8"))
    return digest.hexdigest()


def cached_matrix(key: str, judge: Callable[[], Judged]) -> Judged:
    """The matrix kept under ``key`` in the user's cache folder, or ``judge()``'s, kept there for the next run."""
    return kept("collisions", __version__, f"{key}.json", judge, _as_json, _from_json)


def _as_json(judged: Judged) -> str:
    rows = [[first, second, reason] for (first, second), reason in judged.disabled.items()]
    return json.dumps({"disabled": rows, "samples": judged.samples, "pairs": judged.pairs, "meshes": judged.meshes})


def _from_json(text: str) -> Judged:
    """The matrix a cached file holds. Raises ValueError when it is not one (damaged, or written by hand)."""
    try:
        data = json.loads(text)
        disabled = {pair(first, second): reason for first, second, reason in data["disabled"]}
        judged = Judged(disabled, int(data["samples"]), int(data["pairs"]), bool(data["meshes"]))
    except (TypeError, KeyError) as exc:
        raise ValueError(f"not a kept matrix: {exc}") from exc
    names_ok = all(isinstance(name, str) for both in disabled for name in both)
    if not names_ok or not set(disabled.values()) <= set(REASONS):
        raise ValueError("not a kept matrix: names or reasons")
    return judged


def collision_text(
    view: UrdfView, base: Path, packages: Mapping[str, str | os.PathLike[str]] | None
) -> tuple[str, list[Path]]:
    """The URDF text pinocchio reads for a robot's collision geometry (``view``: its parse): its collision meshes
    named by their files (found from ``base`` and ``packages``), its visuals left out (nor their meshes read); and
    those mesh files, in the document's order.

    Raises:
        LookupError, ValueError: a collision mesh whose file cannot be found.
    """
    root = copy.deepcopy(view.root)
    files = []
    for mesh in root.iterfind("link/collision/geometry/mesh"):
        files.append(mesh_file(mesh.get("filename", ""), base, packages))
        mesh.set("filename", str(files[-1]))
    for visual in root.findall("link/visual"):  # (not read: nor its meshes)
        visual.getparent().remove(visual)
    return etree.tostring(root, encoding="unicode"), files


def home_pairs_key(text: str, meshes: Iterable[Path], home: Mapping[str, float]) -> str:
    """The digest G007's pairs in collision at ``home`` are kept under: the text pinocchio reads
    (:func:`collision_text`), its mesh files' bytes, the home pose, and the installs of pinocchio and coal and of the
    module that poses them. Raises OSError: a mesh file cannot be read."""
    digest = hashlib.sha256()
    installs = source_stamp("pinocchio", "coal", "xacrokit.moveit.collision_pairs")
    header = {"urdf": text, "home": sorted(home.items()), "installs": installs}
    digest.update(json.dumps(header, sort_keys=True).encode("utf-8"))
    for path in meshes:
        digest.update(b"\0" + str(path).encode("utf-8") + b"\0")
        digest.update(hashlib.sha256(Path(path).read_bytes()).digest())
    return digest.hexdigest()


def kept_home_pairs(key: str, pose: Callable[[], frozenset[Pair]]) -> frozenset[Pair]:
    """The pairs kept under ``key`` (:func:`home_pairs_key`) in the user's cache folder, or ``pose()``'s, kept there
    for the next check of the same robot."""
    return kept("collisions", __version__, f"home-{key}.json", pose, _pairs_json, _pairs_from_json)


def _pairs_json(pairs: frozenset[Pair]) -> str:
    return json.dumps({"pairs": sorted(pairs)})


def _pairs_from_json(text: str) -> frozenset[Pair]:
    """The pairs a kept file holds. Raises ValueError when it is not such a file."""
    try:
        rows = json.loads(text)["pairs"]
        found = frozenset(pair(first, second) for first, second in rows)
    except (TypeError, KeyError) as exc:
        raise ValueError(f"not kept pairs: {exc}") from exc
    if not all(isinstance(name, str) for both in found for name in both):
        raise ValueError("not kept pairs: names")
    return found
