"""A link drawn in several pieces (`visuals:`), colliding as several shapes (a `collision` list) or only colliding
(collision without a shape), a mirrored mesh, a joint's calibration, and `strict: false`: what each writes in both
URDF writers, and the located errors of their mistakes."""

from __future__ import annotations

import numpy as np
import pytest
import trimesh
import yaml
from lxml import etree

import xacrokit
from conftest import link_inertial
from xacrokit.emit import urdf_differences
from xacrokit.errors import SpecErrors
from xacrokit.load import load_text
from xacrokit.validate import validate

SPEC = {
    "robot": "pieces",
    "materials": {"red": [1, 0, 0, 1], "blue": [0, 0, 1, 1]},
    "links": {
        "base": {
            "shape": {"box": {"size": [0.4, 0.3, 0.1]}},
            "mass": 3.0,
            "material": "red",
            "visuals": [
                {"shape": {"sphere": {"radius": 0.05}}, "origin": {"xyz": [0, 0, 0.1]}, "material": "blue"},
                {"shape": {"cylinder": {"radius": 0.02, "length": "40 mm"}}, "origin": {"rpy": [0, "90 deg", 0]}},
            ],
            "collision": [
                {"shape": {"box": {"size": [0.4, 0.3, 0.1]}}},
                {"shape": {"sphere": {"radius": 0.06}}, "origin": {"xyz": [0, 0, 0.1]}},
            ],
        },
        "bumper": {"collision": {"shape": {"sphere": {"radius": 0.1}}, "origin": {"xyz": [0.3, 0, 0]}}},
        "arm": {"shape": {"box": {"size": [0.1, 0.1, 0.1]}}, "mass": 1.0},
    },
    "joints": {
        "bumper_joint": {"type": "fixed", "parent": "base", "child": "bumper"},
        "arm_joint": {
            "type": "revolute",
            "parent": "base",
            "child": "arm",
            "limit": {"lower": -1, "upper": 1, "effort": 1, "velocity": 1},
            "calibration": {"rising": 0.25},
        },
    },
}


def generated(tmp_path, spec, *, via_xacro=False, name="pieces"):
    path = tmp_path / f"{name}.yaml"
    path.write_text(yaml.safe_dump(spec, sort_keys=False), encoding="utf-8")
    out = tmp_path / f"pkg_{name}_{via_xacro}"
    xacrokit.generate(path, out, via_xacro=via_xacro)
    return (out / "urdf" / f"{spec['robot']}.urdf").read_text(encoding="utf-8")


def drawn(link, kind):
    """(shape tag, its attributes, origin xyz, origin rpy, material) of each visual or collision, in order."""
    found = []
    for element in link.findall(kind):
        shape = next(element.find("geometry").iterchildren(etree.Element))
        origin = element.find("origin")
        material = element.find("material")
        found.append(
            (
                shape.tag,
                dict(shape.attrib),
                [float(v) for v in origin.get("xyz").split()],
                [float(v) for v in origin.get("rpy").split()],
                None if material is None else material.get("name"),
            )
        )
    return found


def test_visuals_and_collision_lists_are_written_in_order_by_both_writers(tmp_path):
    text = generated(tmp_path, SPEC)
    assert urdf_differences(text, generated(tmp_path, SPEC, via_xacro=True), rel=0.0) == []
    root = etree.fromstring(text.encode())
    base = root.find("link[@name='base']")
    half_pi = np.pi / 2
    assert drawn(base, "visual") == [
        ("box", {"size": "0.4 0.3 0.1"}, [0, 0, 0], [0, 0, 0], "pieces/red"),
        ("sphere", {"radius": "0.05"}, [0, 0, 0.1], [0, 0, 0], "pieces/blue"),
        ("cylinder", {"radius": "0.02", "length": "0.04"}, [0, 0, 0], [0, half_pi, 0], "pieces/red"),
    ]
    assert drawn(base, "collision") == [
        ("box", {"size": "0.4 0.3 0.1"}, [0, 0, 0], [0, 0, 0], None),
        ("sphere", {"radius": "0.06"}, [0, 0, 0.1], [0, 0, 0], None),
    ]
    # the extra visuals carry no mass: the base is its box's 3 kg, about the box's centre
    mass, tensor, xyz, _ = link_inertial(root, "base")
    assert mass == 3.0 and list(xyz) == [0, 0, 0]
    assert tensor[2, 2] == pytest.approx(3.0 * (0.4**2 + 0.3**2) / 12, rel=1e-15)
    bumper = root.find("link[@name='bumper']")
    assert bumper.find("visual") is None and bumper.find("inertial") is None
    assert drawn(bumper, "collision") == [("sphere", {"radius": "0.1"}, [0.3, 0, 0], [0, 0, 0], None)]
    calibration = root.find("joint[@name='arm_joint']/calibration")
    assert dict(calibration.attrib) == {"rising": "0.25"}


@pytest.mark.parametrize(
    ("change", "path", "words"),
    [
        (
            lambda s: s["links"]["base"]["visuals"][0].update(material="green"),
            "$.links.base.visuals[0].material",
            "material 'green' is not in materials",
        ),
        (
            lambda s: s["links"]["bumper"].update(collision="same"),
            "$.links.bumper.collision",
            "collision: same needs the link's shape",
        ),
        (
            lambda s: s["links"]["base"]["collision"][1]["shape"].update(sphere={"radius": 0}),
            "$.links.base.collision[1].shape.sphere.radius",
            "sizes must be > 0 m",
        ),
        (lambda s: s["links"]["base"].update(collision=[]), "$.links.base.collision", "or a list of them"),
        (
            lambda s: (
                s["links"]["arm"]["shape"].update(box={"size": [0.1, 0.1, 0.1]})
                or s["links"]["arm"].update(
                    shape={"mesh": {"filename": "package://p/m.stl", "scale": [1, 0, 1]}},
                    inertia={"ixx": 1, "iyy": 1, "izz": 1},
                )
            ),
            "$.links.arm.shape.mesh.scale[1]",
            "must not be",
        ),
    ],
    ids=["visual-material", "same-without-shape", "collision-size", "empty-list", "scale-zero"],
)
def test_mistakes_in_the_lists_are_located(change, path, words):
    spec = yaml.safe_load(yaml.safe_dump(SPEC))
    change(spec)
    with pytest.raises(SpecErrors) as caught:
        validate(load_text(yaml.safe_dump(spec, sort_keys=False), "s.yaml"))
    assert any(e.path == path and words in e.message for e in caught.value.errors), caught.value


def test_strict_false_writes_what_no_body_has_and_says_it_but_refuses_a_negative_mass(tmp_path):
    spec = yaml.safe_load(yaml.safe_dump(SPEC))
    spec["links"]["arm"] = {
        "shape": {"box": {"size": [0.1, 0.1, 0.1]}},
        "mass": 0,
        "inertia": {"ixx": 1, "iyy": 0, "izz": 0},
    }
    spec["joints"]["arm_joint"]["limit"]["effort"] = 0
    text = yaml.safe_dump(spec, sort_keys=False)
    with pytest.raises(SpecErrors) as caught:
        validate(load_text(text, "s.yaml"))
    said = {e.path for e in caught.value.errors}
    assert said == {"$.links.arm.mass", "$.links.arm.inertia", "$.joints.arm_joint.limit.effort"}, said
    lenient = validate(load_text(text.replace("robot: pieces\n", "robot: pieces\nstrict: false\n"), "s.yaml"))
    assert said <= {w.path for w in lenient.warnings}
    root = etree.fromstring(generated(tmp_path, {**spec, "strict": False}).encode())
    assert root.find("link[@name='arm']/inertial/mass").get("value") == "0.0"
    assert root.find("joint[@name='arm_joint']/limit").get("effort") == "0.0"
    spec["links"]["arm"]["mass"] = -1
    with pytest.raises(SpecErrors) as caught:
        validate(load_text(yaml.safe_dump({**spec, "strict": False}, sort_keys=False), "s.yaml"))
    assert any(e.path == "$.links.arm.mass" and "mass must be > 0 kg" in e.message for e in caught.value.errors)


def test_a_mirrored_mesh_has_the_mirrored_centre_of_mass(tmp_path):
    """An off-centre box mesh, scaled by -1 along y: its centre of mass is mirrored, its tensor the box's."""
    (tmp_path / "cad").mkdir()
    box = trimesh.creation.box(extents=(0.1, 0.2, 0.3))
    box.vertices = box.vertices + np.array([0.01, 0.02, 0.03])
    (tmp_path / "cad" / "part.obj").write_text(trimesh.exchange.obj.export_obj(box, include_normals=False, digits=17))
    spec = {
        "robot": "mirror",
        "links": {"part": {"shape": {"mesh": {"filename": "cad/part.obj", "scale": [1, -1, 1]}}, "mass": 2.0}},
    }
    root = etree.fromstring(generated(tmp_path, spec, name="mirror").encode())
    mass, tensor, xyz, rot = link_inertial(root, "part")
    assert mass == 2.0
    assert np.abs(np.array(xyz) - [0.01, -0.02, 0.03]).max() < 1e-15
    want = np.diag([2.0 * (0.2**2 + 0.3**2) / 12, 2.0 * (0.1**2 + 0.3**2) / 12, 2.0 * (0.1**2 + 0.2**2) / 12])
    assert np.abs(rot @ tensor @ rot.T - want).max() < 1e-15


def test_strict_false_keeps_a_links_mass_of_0_not_a_parts_and_takes_no_visuals_beside_parts():
    """Parts that all weigh nothing have no centre of mass (it would be written NaN): their 0 stays an error; a
    composite link's pieces are its parts, so `visuals:` beside them is refused, not dropped."""
    spec = {
        "robot": "comp",
        "strict": False,
        "links": {
            "base": {
                "parts": [{"shape": {"box": {"size": [1, 1, 1]}}, "mass": 0}],
                "visuals": [{"shape": {"sphere": {"radius": 0.1}}}],
            }
        },
    }
    with pytest.raises(SpecErrors) as caught:
        validate(load_text(yaml.safe_dump(spec, sort_keys=False), "s.yaml"))
    said = {e.path: e.message for e in caught.value.errors}
    assert said.keys() == {"$.links.base.parts[0].mass", "$.links.base.visuals"}, said
    assert "move visuals into a part" in said["$.links.base.visuals"]
