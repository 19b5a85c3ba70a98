"""Composite links (``parts:``), capsules and tubes: the link's mass, centre of mass and inertia are the exact sum of
its parts' (each tensor rotated, then moved to the common centre of mass), judged against independent computations:
pinocchio's spatial-inertia algebra, trimesh's integration over meshes of the same solids, and 1-D quadrature of the
closed shapes' cross-sections (scipy)."""

from __future__ import annotations

import math
import re

import numpy as np
import pinocchio as pin
import pytest
import trimesh
import yaml
from hypothesis import example, given, settings
from hypothesis import strategies as st
from lxml import etree
from scipy.integrate import quad

from conftest import REPO, gen_robot, link_inertial, rpy_matrix
from xacrokit.emit import emit_urdf
from xacrokit.errors import SpecErrors
from xacrokit.pipeline import build_robot


def write(tmp_path, spec, name="c.yaml"):
    path = tmp_path / name
    path.write_text(yaml.safe_dump(spec, sort_keys=False), encoding="utf-8")
    return path


def one_link(link):
    return {"robot": "c", "links": {"body": link}}


def inertial_in_link(tmp_path, spec):
    """(mass, com, tensor about the com in the link's axes) of link 'body' as the emitted URDF writes it."""
    root = etree.fromstring(emit_urdf(build_robot(write(tmp_path, spec))).encode())
    mass, tensor, xyz, rot = link_inertial(root, "body")
    return mass, xyz, rot @ tensor @ rot.T


def assert_tensor(got, want, rel=1e-12):
    scale = np.abs(want).max()
    assert np.abs(got - want).max() <= rel * scale, f"\n{got}\n!=\n{want}"


# ------------------------------------------------------------------------------- closed shapes, by quadrature
def quadrature(radius_at, z_range, mass):
    """(axial, transverse) moments of a solid of revolution about z through its centre (z = 0), from its
    cross-section's radii (outer, inner) at each z: Izz = rho int pi (R^4 - r^4) / 2 dz and
    Ixx = rho int (pi (R^4 - r^4) / 4 + z^2 pi (R^2 - r^2)) dz."""

    def area(z):
        outer, inner = radius_at(z)
        return math.pi * (outer**2 - inner**2)

    def fourth(z):
        outer, inner = radius_at(z)
        return math.pi * (outer**4 - inner**4)

    opts = {"epsabs": 0, "epsrel": 1e-13, "limit": 200}
    volume = quad(area, *z_range, **opts)[0]
    density = mass / volume
    axial = density * quad(lambda z: fourth(z) / 2, *z_range, **opts)[0]
    transverse = density * quad(lambda z: fourth(z) / 4 + z * z * area(z), *z_range, **opts)[0]
    return axial, transverse


@settings(max_examples=20, deadline=None)
@given(radius=st.floats(0.005, 0.5), length=st.floats(0.001, 1.0), mass=st.floats(0.01, 50.0))
def test_capsule_inertia_equals_quadrature(tmp_path_factory, radius, length, mass):
    spec = one_link({"shape": {"capsule": {"radius": radius, "length": length}}, "mass": mass})
    got_mass, com, tensor = inertial_in_link(tmp_path_factory.mktemp("cap"), spec)

    def radii(z):
        beyond = max(abs(z) - length / 2, 0.0)
        return math.sqrt(max(radius**2 - beyond**2, 0.0)), 0.0

    half = length / 2 + radius
    # (split at the joints between cylinder and caps, where the integrand has a kink)
    axial = transverse = 0.0
    pieces = [(-half, -length / 2), (-length / 2, length / 2), (length / 2, half)]
    volumes = [quad(lambda z: math.pi * radii(z)[0] ** 2, a, b, epsrel=1e-13, epsabs=0)[0] for a, b in pieces]
    for (a, b), volume in zip(pieces, volumes, strict=True):
        part_axial, part_transverse = quadrature(radii, (a, b), mass * volume / sum(volumes))
        axial, transverse = axial + part_axial, transverse + part_transverse
    assert got_mass == mass
    assert np.allclose(com, 0.0, atol=0)
    assert_tensor(tensor, np.diag([transverse, transverse, axial]), rel=1e-11)


@settings(max_examples=20, deadline=None)
@given(
    inner=st.floats(0.001, 0.2),
    thickness=st.floats(0.0005, 0.3),
    length=st.floats(0.001, 1.0),
    density=st.floats(100.0, 20_000.0),
)
def test_tube_inertia_equals_quadrature_and_density(tmp_path_factory, inner, thickness, length, density):
    outer = inner + thickness
    shape = {"tube": {"inner_radius": inner, "outer_radius": outer, "length": length}}
    got_mass, _, tensor = inertial_in_link(
        tmp_path_factory.mktemp("tube"), one_link({"shape": shape, "density": density})
    )
    assert got_mass == pytest.approx(density * math.pi * (outer**2 - inner**2) * length, rel=1e-12)
    axial, transverse = quadrature(lambda z: (outer, inner), (-length / 2, length / 2), got_mass)
    assert_tensor(tensor, np.diag([transverse, transverse, axial]), rel=1e-11)


def test_capsule_is_drawn_as_a_cylinder_and_two_spheres_and_a_tube_as_a_mesh_of_its_solid(tmp_path):
    spec = one_link(
        {
            "parts": [
                {
                    "shape": {"capsule": {"radius": 0.02, "length": 0.1}},
                    "origin": {"xyz": [0.1, 0.2, 0.3], "rpy": [0.3, -0.7, 1.1]},
                    "mass": 1.0,
                },
                {"shape": {"tube": {"inner_radius": 0.01, "outer_radius": 0.02, "length": 0.2}}, "mass": 1.0},
            ]
        }
    )
    result = gen_robot(write(tmp_path, spec), "-o", tmp_path / "out")
    assert result.returncode == 0, result.stderr
    root = etree.parse(str(tmp_path / "out" / "urdf" / "c.urdf")).getroot()
    visuals = root.findall("link/visual")
    assert [len(v.find("geometry")) for v in visuals] == [1, 1, 1, 1]
    kinds = [v.find("geometry")[0].tag for v in visuals]
    assert kinds == ["cylinder", "sphere", "sphere", "mesh"]
    axis = rpy_matrix(0.3, -0.7, 1.1)[:, 2]
    centres = [np.array([float(x) for x in v.find("origin").get("xyz").split()]) for v in visuals[1:3]]
    assert np.allclose(centres[0], [0.1, 0.2, 0.3] + 0.05 * axis, atol=1e-15)
    assert np.allclose(centres[1], [0.1, 0.2, 0.3] - 0.05 * axis, atol=1e-15)
    assert len(root.findall("link/collision")) == 4
    uri = visuals[3].find("geometry/mesh").get("filename")
    assert uri == "package://c_description/meshes/xacrokit/tube_0.01_0.02_0.2.obj"
    made = trimesh.load(tmp_path / "out" / "meshes" / "xacrokit" / "tube_0.01_0.02_0.2.obj", force="mesh")
    assert made.is_watertight and made.is_winding_consistent
    exact = math.pi * (0.02**2 - 0.01**2) * 0.2
    sides = 64  # (a 64-gon's area is sin(2 pi / 64) 64 / (2 pi) of its circle's)
    assert made.volume == pytest.approx(exact * math.sin(2 * math.pi / sides) * sides / (2 * math.pi), rel=1e-9)
    check = gen_robot("check", "--strict", tmp_path / "out" / "urdf" / "c.urdf")
    assert check.returncode == 0, check.stdout


# ------------------------------------------------------------------------------- composites, two oracles
SHAPES = st.sampled_from(["box", "cylinder", "sphere", "capsule", "tube"])
sizes = st.floats(0.005, 0.5)
coordinates = st.floats(-1.0, 1.0)
angles = st.floats(-math.pi, math.pi)


@st.composite
def parts(draw, shapes=SHAPES):
    result = []
    for _ in range(draw(st.integers(1, 4))):
        kind = draw(shapes)
        if kind == "box":
            shape = {"box": {"size": [draw(sizes), draw(sizes), draw(sizes)]}}
        elif kind == "cylinder":
            shape = {"cylinder": {"radius": draw(sizes), "length": draw(sizes)}}
        elif kind == "sphere":
            shape = {"sphere": {"radius": draw(sizes)}}
        elif kind == "capsule":
            shape = {"capsule": {"radius": draw(sizes), "length": draw(sizes)}}
        else:
            inner = draw(sizes)
            shape = {"tube": {"inner_radius": inner, "outer_radius": inner + draw(sizes), "length": draw(sizes)}}
        xyz = [draw(coordinates) for _ in range(3)]
        rpy = [draw(angles) for _ in range(3)]
        result.append({"shape": shape, "origin": {"xyz": xyz, "rpy": rpy}, "mass": draw(st.floats(0.01, 20.0))})
    return result


def own_inertia(part):
    """The part's tensor about its centre in its own axes, from pinocchio's closed forms where it has them (box,
    cylinder, sphere) and from the docstring formulas of a capsule and a tube otherwise."""
    shape, mass = part["shape"], part["mass"]
    if "box" in shape:
        return pin.Inertia.FromBox(mass, *shape["box"]["size"]).inertia
    if "cylinder" in shape:
        return pin.Inertia.FromCylinder(mass, shape["cylinder"]["radius"], shape["cylinder"]["length"]).inertia
    if "sphere" in shape:
        return pin.Inertia.FromSphere(mass, shape["sphere"]["radius"]).inertia
    if "capsule" in shape:  # pinocchio's FromCapsule (a cylinder plus two hemispheres)
        return pin.Inertia.FromCapsule(mass, shape["capsule"]["radius"], shape["capsule"]["length"]).inertia
    tube = shape["tube"]
    big, small = tube["outer_radius"], tube["inner_radius"]
    volume_big, volume_small = big**2, small**2  # (pi l cancels)
    density = mass / (volume_big - volume_small)
    hollow = pin.Inertia.FromCylinder(density * volume_big, big, tube["length"]).inertia
    return hollow - pin.Inertia.FromCylinder(density * volume_small, small, tube["length"]).inertia


@settings(max_examples=30, deadline=None)
@given(drawn=parts())
def test_a_composite_equals_pinocchios_sum_of_spatial_inertias(tmp_path_factory, drawn):
    mass, com, tensor = inertial_in_link(tmp_path_factory.mktemp("comp"), one_link({"parts": drawn}))
    total = pin.Inertia.Zero()
    for part in drawn:
        rotation = rpy_matrix(*part["origin"]["rpy"])
        placed = pin.Inertia(part["mass"], np.array(part["origin"]["xyz"]), rotation @ own_inertia(part) @ rotation.T)
        total = total + placed
    assert mass == pytest.approx(total.mass, rel=1e-14)
    assert np.abs(com - total.lever).max() <= 1e-14 * max(1.0, np.abs(total.lever).max())
    assert_tensor(tensor, total.inertia)


@settings(max_examples=20, deadline=None)
@given(drawn=parts(shapes=st.just("box")), density=st.floats(100.0, 20_000.0))
@example(  # (the case CI found: a small box far from the link's origin)
    drawn=[
        {
            "shape": {"box": {"size": [0.03125, 0.0078125, 0.0078125]}},
            "origin": {"xyz": [0.0, 0.0, 0.9614694698816644], "rpy": [0.0, 0.0, 0.0]},
            "mass": 1.0,
        }
    ],
    density=100.0,
)
def test_a_composite_of_boxes_equals_trimeshs_integral_over_their_meshes(tmp_path_factory, drawn, density):
    for part in drawn:
        del part["mass"]
        part["density"] = density
    mass, com, tensor = inertial_in_link(tmp_path_factory.mktemp("boxes"), one_link({"parts": drawn}))
    meshes = []
    for part in drawn:
        box = trimesh.creation.box(extents=part["shape"]["box"]["size"])
        # (on the vertices: trimesh's apply_transform skips a placement within 1e-8 of the identity)
        box.vertices = box.vertices @ rpy_matrix(*part["origin"]["rpy"]).T + np.asarray(part["origin"]["xyz"])
        meshes.append(box)
    union = trimesh.util.concatenate(meshes)  # (overlaps count twice, as the sum of parts does)
    # integrated about the middle of its bounds: trimesh's sums over the faces of a small box far from the origin lose
    # digits (a 3 cm box 0.96 m away: 1.1e-10 relative; CI's hypothesis found it)
    middle = union.bounds.mean(axis=0)
    union.vertices = union.vertices - middle
    union.density = density
    assert mass == pytest.approx(union.mass, rel=1e-12)
    want_com = union.center_mass + middle
    assert np.abs(com - want_com).max() <= 1e-12 * max(1.0, np.abs(want_com).max())
    assert_tensor(tensor, union.moment_inertia, rel=1e-10)


def test_composite_parts_get_their_visuals_materials_and_collisions(tmp_path):
    spec = {
        "robot": "c",
        "materials": {"grey": [0.5, 0.5, 0.5, 1], "red": [1, 0, 0, 1]},
        "links": {
            "body": {
                "material": "grey",
                "parts": [
                    {"shape": {"box": {"size": [0.2, 0.1, 0.05]}}, "density": "aluminium"},
                    {"shape": {"sphere": {"radius": 0.02}}, "mass": "50 g", "material": "red", "collision": "none"},
                ],
            }
        },
    }
    root = etree.fromstring(emit_urdf(build_robot(write(tmp_path, spec))).encode())
    visuals = root.findall("link/visual")
    assert [v.find("material").get("name") for v in visuals] == ["c/grey", "c/red"]
    assert [c.find("geometry")[0].tag for c in root.findall("link/collision")] == ["box"]
    mass = float(root.find("link/inertial/mass").get("value"))
    assert mass == pytest.approx(2700.0 * 0.2 * 0.1 * 0.05 + 0.05, rel=1e-12)


# ------------------------------------------------------------------------------- mistakes, located
@pytest.mark.parametrize(
    ("link", "path", "words"),
    [
        (
            {"mass": 1.0, "parts": [{"shape": {"sphere": {"radius": 0.1}}, "mass": 1.0}]},
            "$.links.body.mass",
            "move mass into a part",
        ),
        ({"parts": [{"shape": {"sphere": {"radius": 0.1}}}]}, "$.links.body.parts[0]", "needs a mass"),
        (
            {"parts": [{"shape": {"sphere": {"radius": 0.1}}, "density": "unobtainium"}]},
            "$.links.body.parts[0].density",
            "unknown material",
        ),
        (
            {"shape": {"tube": {"inner_radius": 0.02, "outer_radius": 0.02, "length": 0.1}}, "mass": 1.0},
            "$.links.body.shape.tube.inner_radius",
            "must be less than outer_radius",
        ),
        (
            {"shape": {"capsule": {"radius": 0.0, "length": 0.1}}, "mass": 1.0},
            "$.links.body.shape.capsule.radius",
            "must be > 0",
        ),
        (
            {"parts": [{"shape": {"box": {"size": [1, 1, 1]}}, "mass": -1.0}]},
            "$.links.body.parts[0].mass",
            "must be > 0",
        ),
    ],
)
def test_composite_and_shape_mistakes_are_located_and_write_nothing(tmp_path, link, path, words):
    spec_path = write(tmp_path, one_link(link))
    with pytest.raises(SpecErrors) as caught:
        build_robot(spec_path)
    assert [(e.path, words in e.message) for e in caught.value.errors] == [(path, True)]
    assert caught.value.errors[0].line is not None
    result = gen_robot(spec_path, "-o", tmp_path / "out")
    assert result.returncode == 2 and not (tmp_path / "out").exists()


def test_the_docs_composite_example_sums_its_parts(tmp_path):
    docs = (REPO / "docs" / "spec.md").read_text(encoding="utf-8")
    (block,) = [b for b in re.findall(r"```yaml\n(.*?)\n```", docs, flags=re.S) if "parts:" in b and "mast" in b]
    path = tmp_path / "doc.yaml"
    path.write_text("robot: d\nmaterials: {grey: [0.5, 0.5, 0.5, 1]}\nlinks:\n" + block + "\n", encoding="utf-8")
    (link,) = build_robot(path).links
    plate = 2700.0 * 0.30 * 0.20 * 0.004
    mast = 7850.0 * math.pi * (0.01**2 - 0.008**2) * 0.12
    assert link.inertial.mass == pytest.approx(plate + 0.6 + mast, rel=1e-12)
    centre_z = (0.6 * 0.022 + mast * 0.062) / (plate + 0.6 + mast)
    assert link.inertial.origin.xyz[2] == pytest.approx(centre_z, rel=1e-12)
    assert len(link.visuals) == 3 and len(link.collisions) == 3


def test_the_rover_example_chassis_is_the_sum_of_its_parts():
    """examples/robots/rover.yaml: its base_link's mass from the parts' formulas written out here, and its bracket
    STL the extruded L profile its script says (201 mm^2 x 20 mm)."""
    bracket = trimesh.load(REPO / "examples" / "robots" / "cad" / "motor_bracket.stl", force="mesh")
    assert bracket.is_watertight and bracket.volume == pytest.approx(201.0 * 20.0, rel=1e-6)  # mm^3 (32-bit STL)
    robot = build_robot(REPO / "examples" / "robots" / "rover.yaml")
    base = next(link for link in robot.links if link.name == "base_link")
    decks = 2 * 2700.0 * 0.160 * 0.140 * 0.004  # ASM 6061-T6
    standoffs = 4 * 8500.0 * math.pi * (0.003**2 - 0.0015**2) * 0.056  # C36000 brass
    brackets = 2 * 1240.0 * 4.02e-6  # PLA
    assert base.inertial.kind == "parts"
    assert base.inertial.mass == pytest.approx(decks + standoffs + 2 * 0.0572 + 0.180 + brackets, rel=1e-6)
    assert len(base.visuals) == 2 + 4 + 2 + 1 + 2
    assert {w.joint_name for w in robot.wheels} == {"wheel_left_joint", "wheel_right_joint"}
    assert "scan_joint" in robot.joint_names
