"""I008: is a link's inertia possible for its own geometry?

A body whose mass m lies within the link's geometry (every visual and collision shape, where it sits) obeys two
bounds for every direction n through its centre of mass c, with the maxima over the geometry's points x:

- its moment about the axis along n is at most m * max |(x - c) x n|^2 (all the mass at the farthest points from the
  axis);
- its second moment along n, sum(m ((x - c).n)^2) = trace(I)/2 - n.I.n, is at most m * max ((x - c).n)^2 (all the
  mass at the farthest points along n): a thin plate's moments must add up as a plate's do (ixx + iyy - izz =
  2 sum(m z^2) for a plate in xy), so a flat box cannot have three equal moments.

Both are exact for any mass distribution; they are asked along the tensor's principal axes, the link's axes, each
shape's own axes and the principal axes of the geometry's points. A tensor beyond either by more than TOLERANCE needs
mass outside everything the link draws: a units or copy mistake, a placeholder, or the inertia of another part. The
finding names what a uniform solid of the stated mass filling the link's collision geometry (else its visual) would
have.

Points of the geometry: a box's corners, a cylinder's two rims (RIM points each), a sphere's surface (SPHERE points),
the vertices of a mesh's convex hull (after its scale: the maxima over them are those over every vertex). A link whose
mesh cannot be read is not judged. No lower bound is applied: a body whose mass sits near its centre (a motor in a
light housing) has moments far below the uniform solid's, and a point mass none at all.
"""

from __future__ import annotations

import functools
import io
import math
import os
from collections.abc import Callable, Iterator, Mapping, Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import TYPE_CHECKING, Any

from ..errors import XacrokitError
from ..reader.mesh_copies import MeshCopyRefused, mesh_reader, mesh_root, require_mesh
from ..shared.ros_packages import mesh_file
from ..shared.solid_inertia import box_moments, combine, cylinder_moments, sphere_moment, tensor
from ..shared.transforms import rpy_matrix
from ..shared.urdf_view import Geometry, Link, Origin, Shape
from .findings import rule_table
from .kept_meshes import facts_kept, kept_facts, kept_values
from .urdf_document import Doc, number_of, triple_of

if TYPE_CHECKING:
    import numpy as np

RULES = rule_table(
    {
        "I008": (
            "inertia-fits-geometry",
            "warning",
            "the inertia is one a body of its mass within the link's own geometry (visuals and collisions, meshes by "
            "their convex hull) can have: no moment beyond all the mass at the geometry's farthest points from the "
            "axis, no spread along an axis beyond the geometry's reach (1.5 times, for sampled rims and rounding); the "
            "message gives a uniform solid's values",
        ),
    }
)

TOLERANCE = 1.5  # a bound exceeded by more than this factor is a finding (the bounds are exact; see the docs)
RIM = 128  # points on each rim of a cylinder: the farthest point is missed by at most 1 - cos(pi / RIM) = 0.03%
SPHERE = 512  # points on a sphere (Fibonacci lattice): its reach is missed by about 1%
MARKER = 0.005  # m: geometry no larger than this is a marker, not the body's shape (I004 too)
MAX_TURNS = 32  # distinct shape turns whose axes are asked (beyond, the tensor's, link's and points' axes remain)
DIRECTIONS_AT_ONCE = 8  # directions taken in one product with the points (bounds its memory)


@dataclass(frozen=True)
class Solid:
    """A uniform solid: its volume (m^3), centre and tensor per unit mass (m^2) in the geometry's frame, and what it
    is called in a message (a box, a cylinder, ...)."""

    volume: float
    center: np.ndarray
    unit_tensor: np.ndarray
    kind: str


@dataclass(frozen=True)
class Reach:
    """A link's geometry: its points (N x 3, link frame), and how to make the uniform solid filling its collision
    geometry (else its visual): each piece's solid (made only when a finding names it) and placement."""

    points: np.ndarray
    pieces: tuple[tuple[Callable[[], Solid | None], np.ndarray, np.ndarray], ...]
    axes: np.ndarray  # (the shapes' own axes in the link frame, each once: a turned box's face normals)
    filled: str = "collision"  # (which geometry the solid fills: collision, else visual)

    def solid(self) -> Solid | None:
        """The uniform solid (None when a piece has no volume to fill, or its mesh no longer reads)."""
        return _filling([(make(), turn, shift) for make, turn, shift in self.pieces])


# a mesh's reach: its vertices (mesh frame, scaled) and how to make the solid it encloses
MeshReach = Callable[[str, tuple[float, float, float]], "tuple[np.ndarray, Callable[[], Solid | None]] | None"]


def placement(origin: Origin | None) -> tuple[np.ndarray, np.ndarray]:
    """An ``<origin>`` of the view as its rotation and translation (the identity without one): where a visual, a
    collision, an inertial or a joint's child sits in its link (the geometry rules' one reading of it)."""
    import numpy as np  # (heavy: numpy)

    if origin is None:
        return np.eye(3), np.zeros(3)
    return rpy_matrix(*triple_of(origin.rpy)), np.array(triple_of(origin.xyz))


def _primitive(shape: Shape) -> tuple[np.ndarray, Callable[[], Solid | None]] | None:
    """A box's, cylinder's or sphere's points and solid in its own frame (None: not one, or its sizes do not read)."""
    found = _primitive_solid(shape)
    if found is None:
        return None
    points, solid = found
    return points, lambda: solid


def _primitive_solid(shape: Shape) -> tuple[np.ndarray, Solid] | None:
    import numpy as np  # (heavy: numpy)

    if shape.kind == "box":
        x, y, z = triple_of(shape.get("size"))
        corners = np.array([[a * x, b * y, c * z] for a in (-0.5, 0.5) for b in (-0.5, 0.5) for c in (-0.5, 0.5)])
        return corners, Solid(x * y * z, np.zeros(3), np.diag(box_moments(1.0, x, y, z)), "box")
    if shape.kind == "cylinder":
        r, length = number_of(shape.attributes, "radius", math.nan), number_of(shape.attributes, "length", math.nan)
        assert r is not None and length is not None  # (a default is given)
        turn = np.linspace(0.0, 2.0 * math.pi, RIM, endpoint=False)
        rim = np.stack([r * np.cos(turn), r * np.sin(turn), np.zeros(RIM)], axis=1)
        points = np.concatenate([rim + [0.0, 0.0, -length / 2], rim + [0.0, 0.0, length / 2]])
        about, across = cylinder_moments(1.0, r, length)
        return points, Solid(math.pi * r * r * length, np.zeros(3), np.diag([across, across, about]), "cylinder")
    if shape.kind == "sphere":
        r = number_of(shape.attributes, "radius", math.nan)
        assert r is not None
        index = np.arange(SPHERE) + 0.5
        polar, around = np.arccos(1.0 - 2.0 * index / SPHERE), math.pi * (1.0 + math.sqrt(5.0)) * index
        points = r * np.stack([np.cos(around) * np.sin(polar), np.sin(around) * np.sin(polar), np.cos(polar)], 1)
        return points, Solid(4.0 / 3.0 * math.pi * r**3, np.zeros(3), np.eye(3) * sphere_moment(1.0, r), "sphere")
    return None


def link_reach(link: Link, meshes: MeshReach | None) -> Reach | None:
    """The link's geometry as :class:`Reach`, None when it has none, a shape does not read, or a mesh cannot be read."""
    every = [g for g in (*link.visuals, *link.collisions) if g.shape is not None]
    if not every:
        return None
    import numpy as np  # (heavy: numpy)

    placed = [shape_in_link(g, meshes) for g in every]
    if not every or any(p is None for p in placed):
        return None
    filling = {id(g) for g in (link.collisions or link.visuals)}
    pieces = tuple(p[1:] for g, p in zip(every, placed, strict=True) if p is not None and id(g) in filling)
    # each distinct turn's axes once (a CAD link of 300 parts placed unturned adds three directions, not 900)
    turns = {np.round(p[2], 9).tobytes(): p[2] for p in placed if p is not None}
    axes = np.concatenate([turn.T for turn in list(turns.values())[:MAX_TURNS]])
    points = np.concatenate([p[0] for p in placed if p is not None])
    return Reach(points, pieces, axes, "collision" if link.collisions else "visual")


def geometry_key(link: Link) -> tuple[Any, ...]:
    """What the geometry rules read of a link, without its name or lines: links of equal keys (a fleet's copies of
    one robot, a hand's fingers) have the same reach, and with the same inertial the same I008 and I009 verdicts."""

    def placed(geometry: Geometry) -> tuple[Any, ...]:
        origin, shape = geometry.origin, geometry.shape
        return (
            None if origin is None else (origin.xyz, origin.rpy),
            None if shape is None else (shape.kind, tuple(sorted(shape.attributes.items()))),
        )

    return tuple(map(placed, link.visuals)), tuple(map(placed, link.collisions))


class ReachMemo:
    """Each distinct geometry's :class:`Reach` in one document, made once (:func:`geometry_key`): a fleet of 100
    copies of a robot reads its links' shapes once, not 100 times."""

    def __init__(self, meshes: MeshReach | None) -> None:
        self.meshes = meshes
        self.reaches: dict[tuple[Any, ...], Reach | None] = {}

    def reach(self, link: Link) -> Reach | None:
        key = geometry_key(link)
        if key not in self.reaches:
            self.reaches[key] = link_reach(link, self.meshes)
        return self.reaches[key]


def shape_in_link(
    geometry: Geometry, meshes: MeshReach | None
) -> tuple[np.ndarray, Callable[[], Solid | None], np.ndarray, np.ndarray] | None:
    """A visual's or collision's points in the link frame, how to make its solid, and its placement (turn, shift);
    None when it has no shape, its sizes do not read, or its mesh cannot be read."""
    import numpy as np  # (heavy: numpy)

    if geometry.shape is None:
        return None
    found = _primitive(geometry.shape)
    if found is None and geometry.shape.kind == "mesh" and meshes is not None:
        found = meshes(geometry.shape.get("filename") or "", triple_of(geometry.shape.get("scale"), "1 1 1"))
    if found is None or not np.isfinite(found[0]).all():
        return None
    turn, shift = placement(geometry.origin)
    return found[0] @ turn.T + shift, found[1], turn, shift


def _filling(solids: Sequence[tuple[Solid | None, np.ndarray, np.ndarray]]) -> Solid | None:
    """The solids of a link's collision geometry (else visual) as one uniform solid in the link frame, each weighing
    its volume (overlaps counted twice: a message's approximation), None when one of them has no volume."""
    if not solids or any(s is None or not s.volume > 0 for s, _, _ in solids):
        return None
    pieces = [(s.volume, turn @ s.center + shift, turn, s.volume * s.unit_tensor) for s, turn, shift in solids if s]
    volume, centre, tensor = combine(pieces)
    kind = solids[0][0].kind if len(solids) == 1 and solids[0][0] is not None else "solid"
    return Solid(volume, centre, tensor / volume, kind)


def geometry_message(origin: Origin | None, mass: float, entries: Sequence[float], reach: Reach) -> str | None:
    """What I008 says of a tensor at the inertial ``origin`` within ``reach`` (None: nothing)."""
    import numpy as np  # (heavy: numpy)

    turn, centre = placement(origin)
    stated = turn @ tensor(*entries) @ turn.T  # (in the link frame)
    with np.errstate(all="ignore"):  # (a size of 1e308 overflows: such a link is not judged, U002 says why)
        spans = reach.points.max(axis=0) - reach.points.min(axis=0)
        offsets = reach.points - centre
        spread = np.cov(reach.points.T) if len(reach.points) > 1 else np.eye(3)  # (the geometry's own axes)
        usable = all(np.isfinite(a).all() for a in (stated, offsets, spread, spans, mass * offsets * offsets))
        if not usable or max(spans) <= MARKER:
            return None
        # the tensor's principal axes, the link's, the shapes' own and the points' principal axes (a mesh's part)
        directions = np.array([*np.linalg.eigh(stated)[1].T, *np.eye(3), *reach.axes, *np.linalg.eigh(spread)[1].T])
        squared = np.square(offsets).sum(axis=1)
        worst = max(
            (
                _excess(stated, mass, n, mass * most_moment, mass * most_spread)
                for start in range(0, len(directions), DIRECTIONS_AT_ONCE)  # (memory: points x a few directions)
                for n, most_moment, most_spread in _bounds(
                    offsets, squared, directions[start : start + DIRECTIONS_AT_ONCE]
                )
            ),
            key=lambda e: e[0],
        )
    if worst[0] <= TOLERANCE:
        return None
    return worst[1]() + _solid_note(reach.solid(), mass, turn, reach.filled)


def _bounds(
    offsets: np.ndarray, squared: np.ndarray, directions: np.ndarray
) -> Iterator[tuple[np.ndarray, float, float]]:
    """For each direction n: n, the largest squared distance of the points from the axis along n, and the largest
    squared reach along n (m^2; times the mass they bound the moment and the spread)."""
    import numpy as np  # (heavy: numpy)

    along = np.square(offsets @ directions.T)
    farthest = (squared[:, None] - along).max(axis=0)
    for n, most_moment, most_spread in zip(directions, farthest, along.max(axis=0), strict=True):
        yield n, float(most_moment), float(most_spread)


def _ratio(value: float, most: float, scale: float) -> float:
    """How many times ``value`` is its bound ``most``: 0 for a value of nothing (to rounding of ``scale``), however
    small the bound (a flat plate's spread across itself, a rod's moment about itself)."""
    if value <= 1e-9 * scale:
        return 0.0
    return value / most if most > 0 else math.inf


def _excess(
    stated: np.ndarray, mass: float, n: np.ndarray, most_moment: float, most_spread: float
) -> tuple[float, Callable[[], str]]:
    """How far the tensor passes the larger of the two bounds along ``n`` (a ratio), and how to say it (worded for
    the worst direction alone): ``most_moment`` and ``most_spread`` are the bounds (kg*m^2) of the moment about the
    axis along ``n`` and of the spread along it."""
    import numpy as np  # (heavy: numpy)

    moment = float(n @ stated @ n)
    trace = float(np.trace(stated))
    spread = trace / 2.0 - moment
    ratio_moment, ratio_spread = _ratio(moment, most_moment, trace), _ratio(spread, most_spread, trace)
    if ratio_moment >= ratio_spread:
        return ratio_moment, functools.partial(_moment_said, n, mass, moment, ratio_moment, most_moment)
    return ratio_spread, functools.partial(_spread_said, n, mass, spread, most_spread)


def _moment_said(n: np.ndarray, mass: float, moment: float, ratio: float, most: float) -> str:
    return (
        f"its moment about {_axis_name(n)} through the centre of mass, {moment:.3g} kg*m^2, is {ratio:.3g} times "
        f"the most {mass:.4g} kg within the link's geometry can have ({most:.3g}: all of it at the "
        "points farthest from that axis); the tensor belongs to a larger or heavier body"
    )


def _spread_said(n: np.ndarray, mass: float, spread: float, most: float) -> str:
    reach = math.sqrt(most / mass)
    return (
        f"its moments spread the mass {math.sqrt(max(spread, 0.0) / mass):.3g} m (rms) along {_axis_name(n)} from the "
        f"centre of mass, but the link's geometry reaches at most {reach:.3g} m that way (the two moments across that "
        f"axis minus the one about it are 2 sum(m d^2), d along it: {2 * spread:.3g} kg*m^2 here, at most "
        f"{2 * most:.3g})"
    )


def _axis_name(n: np.ndarray) -> str:
    for index, name in enumerate("xyz"):
        if abs(abs(float(n[index])) - 1.0) < 1e-9:
            return f"the link's {name} axis"
    return f"the axis ({n[0]:.3g}, {n[1]:.3g}, {n[2]:.3g})"


def _solid_note(solid: Solid | None, mass: float, turn: np.ndarray, filled: str) -> str:
    """'; a uniform box of 0.5 kg filling its collision geometry has ixx, iyy, izz = ...' in the inertial frame."""
    import numpy as np  # (heavy: numpy)

    if solid is None:
        return ""
    tensor = mass * turn.T @ solid.unit_tensor @ turn
    values = ", ".join(f"{v:.3g}" for v in np.diag(tensor))
    products = np.abs(tensor - np.diag(np.diag(tensor))).max()
    more = f" (and products up to {products:.3g})" if products > 1e-3 * np.abs(tensor).max() else ""
    said = f"a uniform {solid.kind} of {mass:.4g} kg filling its {filled} geometry"
    return f"; {said} has ixx, iyy, izz = {values}{more} kg*m^2"


class RobotMeshes:
    """A robot's meshes as the geometry rules read them: each mesh's vertices for :func:`link_reach` (calling it), its
    triangle count (:meth:`triangles`), and the uniform solid it encloses (closed and consistently wound: its own;
    else its convex hull's, made with trimesh only when a finding names it). Read as every mesh of a robot is read
    (:func:`~xacrokit.reader.mesh_copies.mesh_reader`: inside its package or the robot's folder, at most 32 MiB,
    never through a link), an STL with numpy-stl (trimesh takes five times as long to start), other kinds with
    trimesh; a mesh that cannot be read gives None (its link is not judged). A file read once is not read again while
    unchanged (its path, size and time: the robots of one package share their meshes), up to KEPT_BYTES of vertices.

    The maxima the bounds take over a mesh's points are those over its convex hull: a mesh is kept as its hull's
    vertices (:func:`_hull_vertices`). Its hull, triangle count and solid are kept across runs too, by the file's
    bytes (:mod:`.kept_meshes`)."""

    def __init__(self, urdf: Path, packages: Mapping[str, str | os.PathLike[str]] | None) -> None:
        self.urdf, self.packages = urdf, packages or {}
        self.read = mesh_reader(urdf, self.packages, parse=_mesh_points)
        self.read_solid = mesh_reader(urdf, self.packages, parse=lambda *read: read)  # (bytes, suffix, name, digest)
        self._where: dict[str, tuple[str, Path]] = {}

    def __call__(
        self, filename: str, scale: tuple[float, float, float]
    ) -> tuple[np.ndarray, Callable[[], Solid | None]] | None:
        import numpy as np  # (heavy: numpy)

        facts = self._facts(filename)
        if facts is None:
            return None
        return facts[0] * np.asarray(scale, dtype=float), lambda: self._solid(filename, scale)

    def _solid(self, filename: str, scale: tuple[float, float, float]) -> Solid | None:
        """The solid for a finding's message (None when trimesh cannot read the file numpy-stl read, or make it)."""
        import numpy as np  # (heavy: numpy)

        try:
            data, suffix, said, digest = self.read_solid(filename).mesh  # (its bytes: trimesh reads them if not kept)

            def work_out() -> list[float] | None:
                return _solid_values(require_mesh(data, suffix, said, process=False), scale)

            values = kept_values(data, f"solid:{suffix}:{scale!r}", work_out, digest)
        except XacrokitError:
            return None
        if values is None:
            return None
        return Solid(values[0], np.array(values[1:4]), np.array(values[4:13]).reshape(3, 3), "solid")

    def kept(self, filename: str) -> bool:
        """Whether the mesh's facts are kept from a run before (a file that cannot be read needs no reader: True)."""
        try:
            data, suffix, _, digest = self.read_solid(filename).mesh
        except XacrokitError:
            return True
        return facts_kept(data, suffix, digest)

    def triangles(self, filename: str) -> int | None:
        """How many triangles the mesh has (None: it cannot be read)."""
        facts = self._facts(filename)
        return None if facts is None else facts[1]

    def _located(self, filename: str) -> tuple[str, Path]:
        """The package or folder a mesh URI is read below, and its file (asked once a URI for this robot: the rules
        ask for each mesh several times, and finding a package costs a tenth of a millisecond)."""
        if filename not in self._where:
            root = str(mesh_root(self.urdf, filename, self.packages))
            self._where[filename] = (root, mesh_file(filename, self.urdf.parent, self.packages))
        return self._where[filename]

    def _facts(self, filename: str) -> tuple[np.ndarray, int] | None:
        try:
            root, path = self._located(filename)
            status = path.stat()
            key = (root, str(path), status.st_size, status.st_mtime_ns)
        except (OSError, LookupError, ValueError):
            return None
        if key not in _MESHES:
            try:
                _MESHES[key] = self.read(filename).mesh
            except XacrokitError:
                _MESHES[key] = None
            while sum(m[0].nbytes for m in _MESHES.values() if m is not None) > KEPT_BYTES and len(_MESHES) > 1:
                del _MESHES[next(iter(_MESHES))]
        return _MESHES[key]


def preload_mesh_readers(doc: Doc, meshes: RobotMeshes) -> None:
    """Import trimesh now when our rules will read a mesh with it: one other than STL (which numpy-stl reads) whose
    facts no run before kept (:mod:`.kept_meshes`). A check forks yourdfpy's child next (the other consumers started
    already), which loads trimesh too, so the import (0.7 s) is paid once, before the fork, instead of once in our
    rules and once in the child; when every such mesh is kept, the child imports it alone, while our rules run."""
    names = {
        g.shape.get("filename") or ""
        for link in doc.view.links
        for g in (*link.visuals, *link.collisions)
        if g.shape is not None and g.shape.kind == "mesh"
    }
    if any(not meshes.kept(name) for name in sorted(names) if not name.lower().endswith(".stl")):
        # (heavy: trimesh)
        import trimesh  # noqa: F401


KEPT_BYTES = 128 * 1024 * 1024  # vertices kept read across robots (float32: 10 million vertices)
_MESHES: dict[tuple[str, str, int, int], tuple[np.ndarray, int] | None] = {}


def _mesh_points(data: bytes, suffix: str, said: str, digest: bytes) -> tuple[np.ndarray, int]:
    """A mesh file's hull vertices (float32, N x 3: :func:`_hull_vertices`) and triangle count, as a run before kept
    them (:mod:`.kept_meshes`: by the file's bytes) or read now. Raises MeshCopyRefused when it holds no triangle."""
    return kept_facts(data, suffix, lambda: _read_mesh_points(data, suffix, said), digest)


def _read_mesh_points(data: bytes, suffix: str, said: str) -> tuple[np.ndarray, int]:
    """A mesh file's hull vertices and triangle count: an STL's with numpy-stl, another kind's with trimesh. Raises
    MeshCopyRefused when it holds no triangle."""
    import numpy as np  # (heavy: numpy)

    if suffix != ".stl":
        mesh = require_mesh(data, suffix, said, process=False)
        return _hull_vertices(np.asarray(mesh.vertices, dtype=np.float32)), len(mesh.faces)
    from stl import mesh as stl_mesh  # (heavy: stl)

    try:
        vectors = stl_mesh.Mesh.from_file(said, fh=io.BytesIO(data), calculate_normals=False).vectors
    except Exception:  # noqa: BLE001  (numpy-stl raises what its reader meets: every one means "not an STL")
        vectors = np.zeros((0, 3, 3), dtype=np.float32)
    if not len(vectors):
        raise MeshCopyRefused(
            f"{said}: it does not read as an STL mesh with a triangle; a file read as a mesh must be one"
        )
    return _hull_vertices(np.asarray(vectors, dtype=np.float32).reshape(-1, 3)), len(vectors)


def _hull_vertices(points: np.ndarray) -> np.ndarray:
    """The vertices of the points' convex hull (qhull), those as they are when it has none (a flat mesh): every bound
    the rules take is a maximum of a convex function of the points, reached at a hull vertex, so the hull's vertices
    give the same bounds from a fraction of the points (327,225 of the corpus' 11.2 million vertex copies), and a
    kept mesh costs that much less memory and time in every robot that uses it."""
    import numpy as np  # (heavy: numpy)
    from scipy.spatial import ConvexHull, QhullError  # (heavy: scipy)

    if len(points) < 5:
        return points
    distinct = _distinct(points)
    try:
        return distinct[ConvexHull(distinct.astype(np.float64)).vertices]
    except (QhullError, ValueError):
        return distinct


_MIX = (0x9E3779B97F4A7C15, 0xC2B2AE3D27D4EB4F, 0x165667B19E3779F9)  # (taken as numpy.uint64 by _distinct)


def _distinct(points: np.ndarray) -> np.ndarray:
    """The points (float32, N x 3) each once: an STL repeats every vertex for each triangle that has it (about six
    times), and qhull takes half the time without the copies. Told apart by a 64-bit mix of their bits (one sort of
    integers; np.unique on rows sorts them field by field, slower than qhull itself), then proven: should two distinct
    points share a mix, every point is kept."""
    import numpy as np  # (heavy: numpy)

    rows = np.ascontiguousarray(points, dtype=np.float32)
    bits = rows.view(np.uint32).astype(np.uint64)
    mix = np.array(_MIX, dtype=np.uint64)
    with np.errstate(over="ignore"):  # (the mix wraps around by design)
        key = (bits[:, 0] * mix[0]) ^ (bits[:, 1] * mix[1]) ^ (bits[:, 2] * mix[2])
    _, first, back = np.unique(key, return_index=True, return_inverse=True)
    kept = rows[first]
    return kept if np.array_equal(kept[back.reshape(-1)], rows) else rows


def _solid_values(mesh: Any, scale: tuple[float, float, float]) -> list[float] | None:
    """:func:`_enclosed`'s solid as numbers: its volume, centre (3) and tensor per unit mass (9, row by row)."""
    import numpy as np  # (heavy: numpy)

    solid = _enclosed(mesh, scale)
    if solid is None:
        return None
    return [solid.volume, *map(float, solid.center), *map(float, np.asarray(solid.unit_tensor).reshape(-1))]


def _enclosed(mesh: Any, scale: tuple[float, float, float]) -> Solid | None:
    """The uniform solid a mesh encloses (closed and consistently wound: its own, else its convex hull's; None when
    it has no volume, or qhull refuses its points)."""
    import numpy as np  # (heavy: numpy)

    body = mesh
    body.vertices = body.vertices * np.asarray(scale, dtype=float)
    if float(np.prod(scale)) < 0:
        body.invert()
    body.merge_vertices()
    try:
        if not (body.is_watertight and body.is_winding_consistent and body.volume > 0):
            body = body.convex_hull
    except Exception:  # noqa: BLE001  (qhull refuses a flat or degenerate set: no solid to name)
        return None
    if not body.volume > 0:
        return None
    body.density = 1.0
    unit = np.asarray(body.moment_inertia, dtype=float) / body.volume
    return Solid(float(body.volume), np.asarray(body.center_mass, dtype=float), unit, "solid")
