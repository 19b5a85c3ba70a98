"""``gen-robot report SPEC``: the design report of a robot, the write-up the course asks students for. Per link its
shapes and dimensions, volume, density, mass, centre of mass and inertia tensor with its principal moments and the
formula it comes from (a primitive's closed form, the sum of a composite's parts, a mesh's surface, or given); the
whole robot's mass and centre of mass (all joints at 0).

Everything comes from the read robot: its validated spec and resolved model (the numbers the URDF holds), the volumes
from the same solids validation uses; the robot's centre of mass from pinocchio on its URDF (its free-flyer model, so
that the root link counts).
"""

from __future__ import annotations

import os
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

import numpy as np

from ..errors import XacrokitError
from ..model import Box, Cylinder, Inertia, Link, Mesh, Robot, Shape, Sphere, Visual
from ..reader.read_robot import ReadRobot, read_robot
from ..reader.robot_input import RobotInput
from ..resolve import origin
from ..shared.solid_inertia import tensor
from ..validate.bodies import bodies, parts
from ..validate.solids import body_solids

if TYPE_CHECKING:
    from ..shared.urdf_view import Link as ViewLink

FORMULAS = {
    "box": "solid box, m/12 (b^2 + c^2)",
    "cylinder": "solid cylinder, m r^2/2 axial, m (3r^2 + l^2)/12 transverse",
    "sphere": "solid sphere, 2 m r^2/5",
    "capsule": "capsule: cylinder and hemispheres by volume (docs/spec.md, Shapes)",
    "tube": "hollow cylinder, m (R^2 + r^2)/2 axial, m (3(R^2 + r^2) + l^2)/12 transverse",
    "mesh": "the mesh's closed surface (trimesh), scaled",
    "parts": "sum of the parts: each tensor rotated, then moved by the parallel-axis theorem",
    "explicit": "given in the spec",
}


@dataclass(frozen=True)
class LinkReport:
    name: str
    shapes: tuple[str, ...]
    volume: float | None  # m^3 of the body's solids (None where none is known: a given inertia without a shape)
    inertial: Inertia | None

    @property
    def density(self) -> float | None:
        if self.inertial is None or not self.volume:
            return None
        return self.inertial.mass / self.volume


@dataclass(frozen=True)
class DesignReport:
    robot: str
    links: tuple[LinkReport, ...]
    mass: float
    center: tuple[float, float, float]  # the robot's centre of mass in the root link's frame, joints at 0


def design_report(robot: ReadRobot | RobotInput | str | os.PathLike[str]) -> DesignReport:
    """The design report of a read robot spec (or what to read: a robot spec).

    Raises:
        XacrokitError: not a robot spec (a URDF, a xacro document or a scene has no spec to report).
        SpecErrors: an invalid spec (located).
    """
    import pinocchio as pin  # (heavy: the robot's centre of mass)

    read = read_robot(robot)
    spec, model = read.validated, read.spec
    if spec is None or model is None:
        what = "a scene" if read.kind == "spec" else f"a {read.kind} file"
        raise XacrokitError(f"{read.path}: the design report is of a robot spec (.yaml), not of {what}")
    items = list(bodies(spec.data)) + list(parts(spec.data))
    solids, _, _ = body_solids(spec.raw, spec.data, items)
    volumes: dict[str, float] = {}
    for kind, name, path, _ in items:
        if path in solids and kind != "tool":
            volumes[name] = volumes.get(name, 0.0) + solids[path].volume  # (a composite's parts add up)
    described = _spec_shapes(spec.data)
    links = [_link_report(link, volumes.get(link.name), described.get(link.name)) for link in _links(model, read)]
    free = read.free_floating
    center = pin.centerOfMass(free, free.createData(), pin.neutral(free))
    mass = float(sum(link.inertial.mass for link in links if link.inertial is not None))
    return DesignReport(model.name, tuple(links), mass, (float(center[0]), float(center[1]), float(center[2])))


def _links(robot: Robot, read: ReadRobot) -> list[Link]:
    """The robot's links as the model holds them (arms and wheels through their URDF form, the read robot's view)."""
    by_name = {link.name: link for link in robot.links}
    return [by_name.get(link.name) or _from_urdf(link) for link in read.view.links]


def _from_urdf(link: ViewLink) -> Link:
    """A generated link (an arm's, a wheel's) read back from the emitted URDF, with its shapes and inertial."""

    def floats(text: str | None) -> list[float]:
        return [float(v) for v in (text or "0 0 0").split()]

    shapes: list[Shape] = []
    for visual in link.visuals:
        shape = visual.shape
        if shape is not None and shape.kind == "cylinder":
            shapes.append(Cylinder(float(shape.get("radius") or ""), float(shape.get("length") or "")))
        elif shape is not None and shape.kind == "sphere":
            shapes.append(Sphere(float(shape.get("radius") or "")))
    found = None
    inertial = link.inertial
    if inertial is not None and inertial.inertia is not None:
        place = inertial.origin
        xyz, rpy = (floats(place.xyz), floats(place.rpy)) if place is not None else ([0.0] * 3, [0.0] * 3)
        found = Inertia(
            mass=float(inertial.mass or ""),
            **{k: float(inertial.inertia[k]) for k in ("ixx", "ixy", "ixz", "iyy", "iyz", "izz")},
            origin=origin({"xyz": xyz, "rpy": rpy}),
            kind="cylinder" if any(isinstance(s, Cylinder) for s in shapes) else "sphere",
        )
    return Link(name=link.name, visuals=tuple(Visual(shape=s) for s in shapes), inertial=found)


def _link_report(link: Link, volume: float | None, shapes: list[str] | None) -> LinkReport:
    told = shapes if shapes is not None else [_describe(v.shape) for v in link.visuals]
    return LinkReport(link.name, tuple(told), volume, link.inertial)


def _spec_shapes(data: dict[str, Any]) -> dict[str, list[str]]:
    """How the spec gives each link's and frame's shapes (a composite's parts each with its mass or density)."""
    found: dict[str, list[str]] = {}
    for section in ("links", "frames"):
        for name, item in data.get(section, {}).items():
            if "parts" in item:
                found[name] = [_spec_shape(part["shape"]) + _amount(part) for part in item["parts"]]
            elif "shape" in item:
                found[name] = [_spec_shape(item["shape"])]
    return found


def _amount(part: dict[str, Any]) -> str:
    return f", {part['mass']:.6g} kg" if "mass" in part else ""


def _spec_shape(shape: dict[str, Any]) -> str:
    ((kind, sizes),) = shape.items()
    if kind == "box":
        return "box " + " x ".join(f"{v:g}" for v in sizes["size"]) + " m"
    if kind == "mesh":
        scale = " ".join(f"{v:g}" for v in sizes.get("scale", (1, 1, 1)))
        return f"mesh {sizes['filename']} (scale {scale})"
    return kind + " " + ", ".join(f"{key} {value:g} m" for key, value in sizes.items())


def _describe(shape: Any) -> str:
    if isinstance(shape, Box):
        return "box " + " x ".join(f"{v:g}" for v in shape.size) + " m"
    if isinstance(shape, Cylinder):
        return f"cylinder r {shape.radius:g} m, l {shape.length:g} m"
    if isinstance(shape, Sphere):
        return f"sphere r {shape.radius:g} m"
    if isinstance(shape, Mesh):
        return f"mesh {shape.filename} (scale {' '.join(f'{v:g}' for v in shape.scale)})"
    return str(shape)


def principal_moments(inertial: Inertia) -> list[float]:
    i = inertial
    return [float(v) for v in np.linalg.eigvalsh(tensor(i.ixx, i.ixy, i.ixz, i.iyy, i.iyz, i.izz))]


def to_markdown(report: DesignReport) -> str:
    """The report as Markdown: a summary table, then a section per link."""
    lines = [
        f"# Design report: {report.robot}",
        "",
        f"Total mass {report.mass:.6g} kg; centre of mass {_vec(report.center)} m in the root link's frame, every "
        "joint at 0. SI units: m, m^3, kg, kg/m^3, kg*m^2.",
        "",
        "| link | mass | volume | density | centre of mass | inertia from |",
        "|---|---|---|---|---|---|",
    ]
    for link in report.links:
        i = link.inertial
        lines.append(
            f"| {link.name} | {_num(i.mass if i else None)} | {_num(link.volume)} | {_num(link.density)} | "
            f"{_vec(i.origin.xyz) if i else '-'} | {i.kind if i else 'massless frame'} |"
        )
    for link in report.links:
        i = link.inertial
        lines += ["", f"## {link.name}", ""]
        if len(link.shapes) > 1:
            lines += ["- shapes:", *(f"  - {shape}" for shape in link.shapes)]
        else:
            lines.append(f"- shape: {link.shapes[0] if link.shapes else 'none (a frame)'}")
        if link.volume is not None:
            lines.append(f"- volume {link.volume:.6g} m^3; density {_num(link.density)} kg/m^3 (mass / volume)")
        if i is None:
            lines.append("- no mass (a frame)")
            continue
        lines.append(f"- mass {i.mass:.6g} kg; centre of mass {_vec(i.origin.xyz)} m, axes rpy {_vec(i.origin.rpy)}")
        lines.append(
            f"- inertia about the centre of mass: ixx {i.ixx:.6g}, ixy {i.ixy:.6g}, ixz {i.ixz:.6g}, iyy {i.iyy:.6g}, "
            f"iyz {i.iyz:.6g}, izz {i.izz:.6g} kg*m^2"
        )
        lines.append(f"- principal moments {_vec(tuple(principal_moments(i)))} kg*m^2")
        lines.append(f"- formula: {FORMULAS[i.kind]}")
    return "\n".join(lines) + "\n"


def _num(value: float | None) -> str:
    return "-" if value is None else f"{value:.6g}"


def _vec(values: tuple[float, ...]) -> str:
    return "[" + ", ".join(f"{v:.6g}" for v in values) + "]"
