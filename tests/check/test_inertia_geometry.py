"""I008 (issue 30, item 1): a link's inertia against its own geometry. The lecture's Link A is flagged with the box's
own values and passes with them; a uniform solid's own tensor is never flagged, in any pose, and five times it always
is (the bounds are 2.5 to 3 times the uniform solid's); a mesh is judged by its convex hull; placeholders in several
forms and a tensor copied from a larger part are caught."""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from conftest import REPO
from xacrokit.check import check

BRACKET = REPO / "examples" / "robots" / "cad" / "motor_bracket.stl"


def _urdf(geometry: str, mass: float, tensor, *, origin: str = "", inertial_origin: str = "") -> str:
    (ixx, ixy, ixz), (_, iyy, iyz), (_, _, izz) = np.asarray(tensor, dtype=float).tolist()
    entries = " ".join(
        f'{k}="{v!r}"'
        for k, v in zip(("ixx", "ixy", "ixz", "iyy", "iyz", "izz"), (ixx, ixy, ixz, iyy, iyz, izz), strict=True)
    )
    return f"""<?xml version="1.0"?>
<robot name="r">
  <link name="base_link"/>
  <link name="part">
    <visual>{origin}<geometry>{geometry}</geometry></visual>
    <collision>{origin}<geometry>{geometry}</geometry></collision>
    <inertial>{inertial_origin}<mass value="{mass!r}"/><inertia {entries}/></inertial>
  </link>
  <joint name="j" type="revolute"><parent link="base_link"/><child link="part"/><axis xyz="0 0 1"/>
    <limit lower="-1" upper="1" effort="1" velocity="1"/><dynamics damping="0.1"/></joint>
</robot>
"""


def _i008(tmp_path, text: str):
    path = tmp_path / "r.urdf"
    path.write_text(text, encoding="utf-8")
    return [f for f in check(path, consumers=[]).findings if f.rule == "I008"]


def test_the_lectures_link_a_is_flagged_with_the_box_values_and_passes_with_them(tmp_path):
    box = '<box size="0.5 0.5 0.1"/>'
    (finding,) = _i008(tmp_path, _urdf(box, 0.5, np.eye(3) * 0.005))
    assert finding.element == "part" and "along the link's z axis" in finding.message
    assert "a uniform box of 0.5 kg filling its collision geometry has ixx, iyy, izz = 0.0108, 0.0108, 0.0208" in (
        finding.message
    )
    right = np.diag([0.5 * (0.25 + 0.01) / 12, 0.5 * (0.25 + 0.01) / 12, 0.5 * (0.25 + 0.25) / 12])
    assert _i008(tmp_path, _urdf(box, 0.5, right)) == []


def _solid(kind: str, a: float, b: float, c: float, mass: float) -> tuple[str, np.ndarray]:
    if kind == "box":
        return f'<box size="{a!r} {b!r} {c!r}"/>', mass / 12 * np.diag([b * b + c * c, a * a + c * c, a * a + b * b])
    if kind == "cylinder":
        side = mass * (3 * a * a + b * b) / 12
        return f'<cylinder radius="{a!r}" length="{b!r}"/>', np.diag([side, side, mass * a * a / 2])
    return f'<sphere radius="{a!r}"/>', np.eye(3) * 0.4 * mass * a * a


def _rpy(roll: float, pitch: float, yaw: float) -> np.ndarray:
    cr, sr, cp, sp, cy, sy = (f(v) for v in (roll, pitch, yaw) for f in (math.cos, math.sin))
    return np.array(
        [
            [cy * cp, cy * sp * sr - sy * cr, cy * sp * cr + sy * sr],
            [sy * cp, sy * sp * sr + cy * cr, sy * sp * cr - cy * sr],
            [-sp, cp * sr, cp * cr],
        ]
    )


sizes = st.floats(0.01, 2.0)
turns = st.tuples(*[st.floats(-math.pi, math.pi)] * 3)


@settings(max_examples=40, deadline=None)
@given(
    kind=st.sampled_from(["box", "cylinder", "sphere"]),
    a=sizes,
    b=sizes,
    c=sizes,
    mass=st.floats(0.01, 50),
    turn=turns,
    shift=st.tuples(*[st.floats(-1, 1)] * 3),
)
def test_a_uniform_solids_tensor_passes_and_five_times_it_fails(tmp_path_factory, kind, a, b, c, mass, turn, shift):
    """The solid placed anywhere, turned any way, its tensor written in the link frame about its centre: never
    flagged; five times it always is (beyond 1.5 times the bound: the uniform solid's moments are 1/3 of the box's
    bound, 2/5 of the sphere's, 1/2 of the cylinder's about its axis)."""
    tmp_path = tmp_path_factory.mktemp("i008")
    geometry, tensor = _solid(kind, a, b, c, mass)
    rotation = _rpy(*turn)
    origin = f'<origin xyz="{shift[0]!r} {shift[1]!r} {shift[2]!r}" rpy="{turn[0]!r} {turn[1]!r} {turn[2]!r}"/>'
    placed = f'<origin xyz="{shift[0]!r} {shift[1]!r} {shift[2]!r}"/>'
    in_link = rotation @ tensor @ rotation.T
    assert _i008(tmp_path, _urdf(geometry, mass, in_link, origin=origin, inertial_origin=placed)) == []
    assert len(_i008(tmp_path, _urdf(geometry, mass, 5 * in_link, origin=origin, inertial_origin=placed))) == 1


def test_a_mesh_is_judged_by_its_convex_hull(tmp_path):
    """The motor bracket (an STL in mm): its own uniform tensor passes, five times it fails, and the message gives the
    solid the mesh encloses (trimesh's, an independent computation of the same numbers)."""
    import trimesh

    mesh = trimesh.load(BRACKET)
    mesh.apply_scale(0.001)
    mass = 0.2
    tensor = mesh.moment_inertia / mesh.volume * mass
    centre = " ".join(repr(float(v)) for v in mesh.center_mass)
    (tmp_path / "bracket.stl").write_bytes(BRACKET.read_bytes())  # (beside the URDF: check reads meshes in its folder)
    geometry = '<mesh filename="bracket.stl" scale="0.001 0.001 0.001"/>'
    inertial = f'<origin xyz="{centre}"/>'
    assert _i008(tmp_path, _urdf(geometry, mass, tensor, inertial_origin=inertial)) == []
    (finding,) = _i008(tmp_path, _urdf(geometry, mass, 5 * tensor, inertial_origin=inertial))
    said = finding.message.split("ixx, iyy, izz = ")[1].split(" ")[:3]
    assert [float(v.rstrip(",")) for v in said] == pytest.approx(np.diag(tensor), rel=2e-3)  # (3 digits shown)


@pytest.mark.parametrize(
    ("geometry", "mass", "tensor", "why"),
    [
        ('<box size="0.04 0.02 0.01"/>', 0.02, np.eye(3) * 1e-3, "1e-3 * identity on a 2 cm finger link"),
        ('<cylinder radius="0.03" length="0.1"/>', 0.3, np.eye(3) * 0.01, "0.01 * identity on a small cylinder"),
        ('<box size="0.1 0.1 0.1"/>', 1.0, np.eye(3), "1 * identity (urdf tutorials' default)"),
        ('<sphere radius="0.05"/>', 0.4, np.diag([0.0015, 0.0015, 0.0016]), "a placeholder with odd digits"),
        (
            '<box size="0.1 0.06 0.03"/>',
            0.072,
            np.diag([0.00388, 0.000499, 0.00388]),
            "a 0.5 kg camera's tensor copied onto a 72 g one",
        ),
    ],
)
def test_planted_placeholders_and_copies_are_caught(tmp_path, geometry, mass, tensor, why):
    assert len(_i008(tmp_path, _urdf(geometry, mass, tensor))) == 1, why


def _two_parts(tmp_path, left: str, right: str, tensor=(0.00125, 0.00125, 0.0005), mass=1.0) -> list[str]:
    entries = 'ixx="{!r}" ixy="0" ixz="0" iyy="{!r}" iyz="0" izz="{!r}"'.format(*tensor)
    links = "".join(
        f'<link name="{name}"><visual><geometry>{geometry}</geometry></visual><inertial><mass value="{mass!r}"/>'
        f"<inertia {entries}/></inertial></link>"
        f'<joint name="{name}_joint" type="revolute"><parent link="base_link"/><child link="{name}"/>'
        '<axis xyz="0 0 1"/><limit lower="-1" upper="1" effort="1" velocity="1"/><dynamics damping="0.1"/></joint>'
        for name, geometry in (("left", left), ("right", right))
    )
    path = tmp_path / "two.urdf"
    path.write_text(f'<?xml version="1.0"?><robot name="r"><link name="base_link"/>{links}</robot>', encoding="utf-8")
    return [f"{f.rule} {f.element}" for f in check(path, consumers=[]).findings if f.rule == "I009"]


def test_a_copied_inertial_is_named_and_mirrored_parts_share_theirs(tmp_path):
    """I009: a left and a right part of one size (a mirrored mesh, a turned box) rightly share their inertial; the same
    inertial on a part twice the size is a copy, named on the second link."""
    (tmp_path / "bracket.stl").write_bytes(BRACKET.read_bytes())
    mesh, mirrored = (f'<mesh filename="bracket.stl" scale="{s} 0.001 0.001"/>' for s in ("0.001", "-0.001"))
    assert _two_parts(tmp_path, mesh, mirrored) == []
    assert _two_parts(tmp_path, '<box size="0.1 0.1 0.03"/>', '<box size="0.03 0.1 0.1"/>') == []
    assert _two_parts(tmp_path, '<box size="0.1 0.1 0.03"/>', '<box size="0.2 0.2 0.06"/>') == ["I009 right"]
    assert _two_parts(tmp_path, '<cylinder radius="0.05" length="0.1"/>', '<sphere radius="0.2"/>') == ["I009 right"]


def test_a_flat_plates_own_tensor_passes_and_many_shapes_are_judged_in_bounded_memory(tmp_path):
    """A plate of no thickness (box 1 x 1 x 0) with a plate's tensor: its spread across itself is 0 and so is its
    bound, which is no excess. A link of 400 spheres (200,000 points) is judged as one of a few."""
    plate = np.diag([1 / 12, 1 / 12, 1 / 6])
    assert _i008(tmp_path, _urdf('<box size="1 1 0"/>', 1.0, plate)) == []
    spheres = "".join(
        f'<visual><origin xyz="{0.01 * k!r} 0 0"/><geometry><sphere radius="0.05"/></geometry></visual>'
        for k in range(400)
    )
    text = _urdf('<sphere radius="0.05"/>', 1.0, np.eye(3) * 1e-3).replace("<visual>", spheres + "<visual>", 1)
    assert _i008(tmp_path, text) == []  # (a row of spheres 4 m long: 1e-3 fits)


def test_a_mesh_is_kept_as_its_hulls_distinct_vertices(monkeypatch):
    """What the rules keep of a mesh (its convex hull's vertices, each once) gives the maxima every vertex gives, along
    any direction and of the squared distance from any axis; two distinct vertices that share a hash are both kept."""
    import numpy as np

    from xacrokit.check import inertia_geometry

    rng = np.random.default_rng(7)
    corners = rng.normal(size=(400, 3)).astype(np.float32)
    triangles = corners[rng.integers(0, 400, size=(3000, 3))].reshape(-1, 3)  # (an STL's vertex copies)
    kept = inertia_geometry._hull_vertices(triangles)
    assert len(kept) < 400 and len(np.unique(kept, axis=0)) == len(kept)

    def bounds(points: np.ndarray, n: np.ndarray, centre: np.ndarray) -> tuple[float, float]:
        along = ((points - centre) @ n) ** 2
        return float(along.max()), float((((points - centre) ** 2).sum(axis=1) - along).max())

    for n in rng.normal(size=(50, 3)):
        n /= np.linalg.norm(n)
        centre = rng.normal(size=3)
        assert np.allclose(bounds(kept, n, centre), bounds(triangles, n, centre), rtol=1e-12)
    monkeypatch.setattr(inertia_geometry, "_MIX", (np.uint64(0), np.uint64(0), np.uint64(0)))  # (every key equal)
    assert len(inertia_geometry._distinct(triangles)) == len(triangles)


def _parts_robot(prefix: str) -> str:
    """A robot's links (names with ``prefix``): one with a tensor five times its box's (I008), and two parts of
    different sizes sharing one inertial (I009 on the second)."""
    big = _solid("box", 0.1, 0.2, 0.3, 2.0)[1] * 5
    shared = _urdf_entries(_solid("box", 0.1, 0.1, 0.03, 1.0)[1])  # (the left part's own, copied to the right)
    parts = {
        "big": ('<box size="0.1 0.2 0.3"/>', 2.0, _urdf_entries(big)),
        "left": ('<box size="0.1 0.1 0.03"/>', 1.0, shared),
        "right": ('<box size="0.2 0.2 0.06"/>', 1.0, shared),
    }
    return f'<link name="{prefix}base_link"/>' + "".join(
        f'<link name="{prefix}{name}"><visual><geometry>{shape}</geometry></visual><inertial><mass value="{mass}"/>'
        f"<inertia {entries}/></inertial></link>"
        f'<joint name="{prefix}{name}_joint" type="revolute"><parent link="{prefix}base_link"/>'
        f'<child link="{prefix}{name}"/><axis xyz="0 0 1"/><limit lower="-1" upper="1" effort="1" velocity="1"/>'
        '<dynamics damping="0.1"/></joint>'
        for name, (shape, mass, entries) in parts.items()
    )


def _urdf_entries(tensor) -> str:
    names = ("ixx", "ixy", "ixz", "iyy", "iyz", "izz")
    values = (tensor[0][0], tensor[0][1], tensor[0][2], tensor[1][1], tensor[1][2], tensor[2][2])
    return " ".join(f'{k}="{float(v)!r}"' for k, v in zip(names, values, strict=True))


def _geometry_findings(tmp_path, monkeypatch, prefixes: list[str]) -> tuple[list[tuple[str, str, str]], int]:
    """I008 and I009 (rule, link, message) of the robot, or of a fleet of its copies fixed to a world link; and how
    many times a link's geometry was read."""
    from xacrokit.check import inertia_geometry

    reads = []
    read = inertia_geometry.link_reach
    monkeypatch.setattr(inertia_geometry, "link_reach", lambda *a: reads.append(a) or read(*a))
    if prefixes == [""]:
        body = _parts_robot("")
    else:
        body = '<link name="world"/>' + "".join(
            _parts_robot(p) + f'<joint name="{p}mount" type="fixed"><parent link="world"/><child link="{p}base_link"/>'
            f'<origin xyz="{i} 0 0"/></joint>'
            for i, p in enumerate(prefixes)
        )
    path = tmp_path / f"robots_{len(prefixes)}.urdf"
    path.write_text(f'<?xml version="1.0"?><robot name="r">{body}</robot>', encoding="utf-8")
    found = [(f.rule, f.element, f.message) for f in check(path, consumers=[]).findings if f.rule in ("I008", "I009")]
    return found, len(reads)


def test_a_fleets_copies_get_the_robots_findings_prefixed_and_each_geometry_is_read_once(tmp_path, monkeypatch):
    """A fleet's copies of one robot are judged once: the same geometry gives the same findings, each naming links of
    its own copy (I009 names the left part of the same copy, not another copy's), and the geometry rules read each
    distinct geometry once, however many copies there are."""
    alone, reads_alone = _geometry_findings(tmp_path, monkeypatch, [""])
    assert sorted((rule, link) for rule, link, _ in alone) == [("I008", "big"), ("I009", "right")]
    prefixes = [f"r{i}_" for i in range(6)]
    fleet, reads_fleet = _geometry_findings(tmp_path, monkeypatch, prefixes)
    expected = [
        (rule, p + link, message.replace("'left'", f"'{p}left'")) for p in prefixes for rule, link, message in alone
    ]
    assert sorted(fleet) == sorted(expected)
    assert reads_fleet == 3 == reads_alone  # (the three shapes, once each, however many copies)
