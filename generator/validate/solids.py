"""The solids of a spec's bodies: the volume each body's shape encloses (closed forms for primitives, capsules, tubes,
a wheel's cylinder and a DH row's body; the mesh file's closed surface for a mesh), and what follows from it, on SI
values:

- the mass of a body that gives a density (density x volume);
- the centre of mass and inertia of a mesh body (computed from its surface, as an explicit tensor for resolve);
- the warnings on a mass no solid of its shape could have (grams written as kilograms, millimetres as metres), on a
  mass far from what a density gives, and on a mesh whose size suggests millimetres.

A mesh file that is missing, unreadable or does not enclose a solid is an error at its file name.
"""

from __future__ import annotations

import math
from collections.abc import Iterator, Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import TYPE_CHECKING, Any

from ..errors import SpecError
from ..load import PathKey, RawSpec
from ..model import DEFAULT_ROW_RADIUS
from ..shared.mesh_solids import (
    MESH_SUFFIXES,
    MeshError,
    MeshSolid,
    is_relative,
    mesh_hull,
    mesh_path,
    mesh_solid,
    package_mesh_path,
)
from ..shared.solid_inertia import capsule_volume, tube_volume
from ..shared.transforms import dh_body_end, exact_product, rpy_matrix
from .bodies import Body, geometries

if TYPE_CHECKING:
    pass

DENSEST = 22_590.0  # kg/m^3: osmium, the densest element
LIGHTEST = 1.0  # kg/m^3: less than air (1.2); no solid body in a robot is lighter
LONGEST_MESH = 10.0  # m: a mesh wider than this is most likely in millimetres (as plain lengths: quantities.LONGEST)

# A body given both a mass and a density: its mass may be below the solid's (pockets, shells, a 3D print's infill) but
# a part keeping less than a quarter of its envelope's material, or weighing more than the solid (beyond 10%: the
# shape is an approximation), is more likely a wrong number than a real part.
MASS_TO_SOLID = (0.25, 1.1)


@dataclass(frozen=True)
class Solid:
    """What a body's shape encloses: ``what`` names it in messages (box, cylinder, sphere, capsule, tube, mesh),
    ``volume`` in m^3; ``mesh`` for a mesh (its centre and tensor in the mesh's frame)."""

    what: str
    volume: float
    mesh: MeshSolid | None = None


def body_solids(
    raw: RawSpec, data: dict[str, Any], items: Sequence[Body]
) -> tuple[dict[PathKey, Solid], list[SpecError], list[SpecError]]:
    """The solid of every body (link, frame, part, wheel, DH row) whose shape has a volume, by the body's path; the
    errors (a mesh that cannot give one, a relative mesh file that is not there) and the warnings (a mesh wider than
    10 m). A mesh is read only where its volume is wanted (a mass or a density without an explicit inertia)."""
    found: dict[PathKey, Solid] = dict(_row_segments(data))
    errors: list[SpecError] = []
    warnings: list[SpecError] = []
    for kind, _, path, item in items:
        if kind == "wheel":
            found[path] = Solid("cylinder", math.pi * item["radius"] ** 2 * item["width"])
            continue
        shape = item.get("shape")
        if kind not in ("link", "frame", "part") or not isinstance(shape, dict):
            continue
        if "mesh" not in shape:
            primitive = _primitive(shape)
            if primitive is not None:
                found[path] = primitive
            continue
        where = (*path, "shape", "mesh", "filename")
        filename = shape["mesh"]["filename"]
        given = isinstance(item.get("inertia"), dict) and item["inertia"].get("kind") != "mesh"  # (not computed)
        wanted = ("mass" in item or "density" in item) and not given
        if not wanted:  # (a relative file that is not there: mesh_files_errors says so)
            continue
        if is_relative(filename) and _not_copyable(raw, filename):
            continue  # (mesh_files_errors says why)
        try:
            file = mesh_path(filename, raw.file)
            solid = mesh_solid(file, tuple(shape["mesh"].get("scale", (1.0, 1.0, 1.0))))
        except MeshError as exc:
            errors.append(raw.error(where, str(exc)))
            continue
        found[path] = Solid("mesh", solid.volume, solid)
        widest = max(solid.extents)
        if widest > LONGEST_MESH:
            warnings.append(
                raw.error(
                    (*path, "shape", "mesh"),
                    f"the mesh is {widest:g} m across (after its scale); no part of a robot is that large: if the "
                    "file is in millimetres, give scale: [0.001, 0.001, 0.001]",
                )
            )
    return found, errors, warnings


def _not_there(filename: str, file: Path) -> str:
    return f"mesh file {filename!r} is not there ({file}); a relative path is read from the spec's folder"


def _not_copyable(raw: RawSpec, filename: str) -> str | None:
    """Why the relative mesh path ``filename`` cannot be copied into the package, or None: a file that is not there,
    or one outside the spec's folder (through '..' or a symbolic link) or not a mesh file. (gen-robot copies it: a
    spec from elsewhere must not carry any other file of yours into a package you may publish.)"""
    folder = Path(raw.file).parent
    file = folder / filename
    if not file.is_file():
        return _not_there(filename, file)
    if not file.resolve().is_relative_to(folder.resolve()) or file.suffix.lower() not in MESH_SUFFIXES:
        return (
            f"a relative mesh path must name a mesh file ({', '.join(MESH_SUFFIXES)}) in the spec's folder or below "
            f"it, since gen-robot copies it into the package; {filename!r} is not one (use package:// or file:// for "
            "a mesh kept elsewhere)"
        )
    return None


def mesh_files_errors(raw: RawSpec, data: dict[str, Any]) -> list[SpecError]:
    """The relative mesh paths gen-robot cannot copy into the package: a file that is not there or that it must not
    copy, or two files that would land on one path in the package (``arm.stl`` and ``meshes/arm.stl``: both
    ``meshes/arm.stl``, :func:`~xacrokit.shared.mesh_solids.package_mesh_path`)."""
    errors: list[SpecError] = []
    copied: dict[str, Path] = {}
    for path, filename in _mesh_names(data):
        if not is_relative(filename):
            continue
        file = Path(raw.file).parent / filename
        where = (*path, "filename")
        refused = _not_copyable(raw, filename)
        if refused:
            errors.append(raw.error(where, refused))
            continue
        target = package_mesh_path(filename)
        first = copied.setdefault(target, file.resolve())
        if first != file.resolve():
            errors.append(
                raw.error(
                    where,
                    f"{filename!r} and {first} would both be copied to the package as {target}; rename or move one",
                )
            )
    return errors


def hull_errors(raw: RawSpec, data: dict[str, Any]) -> list[SpecError]:
    """``collision: hull`` on a link whose shape is not a mesh, or whose mesh gives no hull with a volume."""
    errors = []
    for name, link in data.get("links", {}).items():
        if link.get("collision") != "hull":
            continue
        shape = link.get("shape") or {}
        if "mesh" not in shape:
            what = next(iter(shape), "no shape")
            errors.append(
                raw.error(
                    ("links", name, "collision"),
                    f"collision: hull makes the convex hull of the link's mesh, and its shape is {what}: a box, "
                    "cylinder, sphere, capsule or tube collides as itself (collision: same)",
                )
            )
            continue
        filename = shape["mesh"]["filename"]
        if is_relative(filename) and not (Path(raw.file).parent / filename).is_file():
            continue  # (mesh_files_errors says the file is not there)
        try:
            mesh_hull(mesh_path(filename, raw.file))
        except MeshError as exc:
            errors.append(raw.error(("links", name, "shape", "mesh", "filename"), f"collision: hull: {exc}"))
    return errors


def _mesh_names(data: dict[str, Any]) -> Iterator[tuple[PathKey, str]]:
    """(path of the mesh mapping, file name) of every mesh of a spec's links, collisions, parts and frames."""
    holders: list[tuple[PathKey, Any]] = []
    for name, link in data.get("links", {}).items():
        holders.append((("links", name), link))
        holders += list(geometries(("links", name), link))
        holders += [(("links", name, "parts", i), part) for i, part in enumerate(link.get("parts", ()))]
    holders += [(("frames", name), frame) for name, frame in data.get("frames", {}).items()]
    for path, holder in holders:
        shape = holder.get("shape")
        if isinstance(shape, dict) and isinstance(shape.get("mesh"), dict):
            yield (*path, "shape", "mesh"), shape["mesh"]["filename"]


def _primitive(shape: dict[str, Any]) -> Solid | None:
    if "box" in shape:
        x, y, z = shape["box"]["size"]
        return Solid("box", x * y * z)
    if "cylinder" in shape:
        return Solid("cylinder", math.pi * shape["cylinder"]["radius"] ** 2 * shape["cylinder"]["length"])
    if "sphere" in shape:
        return Solid("sphere", 4.0 / 3.0 * math.pi * shape["sphere"]["radius"] ** 3)
    if "capsule" in shape:
        return Solid("capsule", capsule_volume(shape["capsule"]["radius"], shape["capsule"]["length"]))
    if "tube" in shape:
        tube = shape["tube"]
        return Solid("tube", tube_volume(tube["inner_radius"], tube["outer_radius"], tube["length"]))
    return None


def _row_segments(data: dict[str, Any]) -> Iterator[tuple[PathKey, Solid]]:
    """The solid of every DH row's body, by the row's path: as emit draws it (kinematics.dh_body_end)."""
    for name, arm in data.get("arms", {}).items():
        rows = arm["joints"]
        for index, row in enumerate(rows):
            after = rows[index + 1] if index + 1 < len(rows) else None
            following = (after["a"], after["alpha"], after["d"]) if after else None
            end = dh_body_end(arm.get("convention", "standard"), row["a"], row["alpha"], following)
            length = math.dist((0.0, 0.0, 0.0), end)
            radius = row.get("radius", DEFAULT_ROW_RADIUS)
            if length >= 1e-6:
                yield ("arms", name, "joints", index), Solid("cylinder", math.pi * radius**2 * length)
            else:
                yield ("arms", name, "joints", index), Solid("sphere", 4.0 / 3.0 * math.pi * radius**3)


def masses_from_density(
    raw: RawSpec, items: Sequence[Body], solids: dict[PathKey, Solid]
) -> tuple[dict[PathKey, float], list[SpecError], list[SpecError]]:
    """The mass of every body that gives a density and no mass (density times its solid's volume), by the body's
    path; the errors (a density with no volume to fill) and the warnings (a mass far from what its density gives)."""
    masses: dict[PathKey, float] = {}
    errors: list[SpecError] = []
    warnings: list[SpecError] = []
    for kind, _, path, item in items:
        density = item.get("density")
        if density is None or kind not in ("link", "wheel", "frame", "row", "part"):
            continue
        found = solids.get(path)
        if found is None:
            if "mesh" not in item.get("shape", {}):  # (a mesh that cannot give a volume has its error said)
                errors.append(
                    raw.error((*path, "density"), "a density gives a mass only with a shape; give mass: instead")
                )
            continue
        solid = density * found.volume
        if "mass" not in item:
            if found.volume > 0:
                masses[path] = solid
            continue
        if found.volume > 0 and not MASS_TO_SOLID[0] <= item["mass"] / solid <= MASS_TO_SOLID[1]:
            warnings.append(
                raw.error(
                    (*path, "mass"),
                    f"mass {item['mass']:g} kg is {item['mass'] / solid:.3g} times that of a solid {found.what} of "
                    f"density {density:g} kg/m^3 ({solid:.3g} kg); a part keeps between a quarter and all of its "
                    "solid's mass: is the mass, the density or the size wrong?",
                )
            )
    return masses, errors, warnings


def mesh_inertias(items: Sequence[Body], solids: dict[PathKey, Solid]) -> dict[PathKey, dict[str | int, Any]]:
    """For every mesh body with a mass and no explicit inertia: its tensor about the centre of mass (the solid's, at
    the body's mass) with that centre in the link frame, as an explicit ``inertia`` mapping (its ``kind`` says where
    it came from), by the body's path. The tensor keeps the mesh's axes (the shape origin's rpy)."""
    found: dict[PathKey, dict[str | int, Any]] = {}
    for _, _, path, item in items:
        solid = solids.get(path)
        if solid is None or solid.mesh is None or "mass" not in item or "inertia" in item:
            continue
        mesh = solid.mesh
        scale = item["mass"] / mesh.volume
        (xx, xy, xz), (_, yy, yz), (_, _, zz) = (tuple(scale * v for v in row) for row in mesh.unit_inertia)
        origin = item.get("origin") or {}
        xyz, rpy = origin.get("xyz", (0.0, 0.0, 0.0)), origin.get("rpy", (0.0, 0.0, 0.0))
        import numpy as np  # (heavy: numpy, for a mesh body only)

        center = np.asarray(xyz, dtype=float) + exact_product(rpy_matrix(*rpy), np.asarray(mesh.center, dtype=float))
        found[path] = {
            "inertia": {
                "ixx": xx,
                "ixy": xy,
                "ixz": xz,
                "iyy": yy,
                "iyz": yz,
                "izz": zz,
                "origin": {"xyz": [float(v) + 0.0 for v in center], "rpy": list(rpy)},
                "kind": "mesh",
            }
        }
    return found


def density_warnings(raw: RawSpec, items: Sequence[Body], solids: dict[PathKey, Solid]) -> Iterator[SpecError]:
    """Masses that no solid filling their shape could have: grams written as kilograms, millimetres as metres. A DH
    row's body is the cylinder (a sphere when it is shorter than a micrometre) gen-robot draws from its joint's frame
    to the next one, with the row's radius."""
    for kind, _, path, item in items:
        mass = item.get("mass")
        found = solids.get(path)
        if mass is None or found is None or not (found.volume > 0 and mass > 0):
            continue
        density = mass / found.volume
        if LIGHTEST <= density <= DENSEST:
            continue
        hint = (
            "denser than osmium (22,590 kg/m^3); grams written as kilograms? e.g. '500 g'"
            if density > DENSEST
            else "lighter than air; a size in mm written as m? e.g. '150 mm'"
        )
        if kind == "row":  # (its body is drawn from the DH lengths and its radius: either may be what is off)
            radius = item.get("radius", DEFAULT_ROW_RADIUS)
            body = "a cylinder to the next joint frame" if found.what == "cylinder" else "a sphere: its frames coincide"
            fits = "too small" if density > DENSEST else "too large"
            hint += f"; or its radius ({radius:g} m; the row's body is {body}) is {fits} for its mass"
        yield raw.error(
            (*path, "mass"),
            f"mass {mass:g} kg in a {found.volume:.3g} m^3 {found.what} is {density:.3g} kg/m^3, {hint}",
        )
