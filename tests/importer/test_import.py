"""gen-robot import, proven by round trip (issue 19, first part): every example robot's URDF is imported, the spec
generated again, and the new URDF has the same links and joints, the same forward kinematics at 20 random joint
values (pinocchio, 1e-9), the same mass, centre of mass and inertia per link (1e-9 relative), the same limits and the
same visual geometry; what the spec cannot hold is reported, not dropped silently."""

from __future__ import annotations

import math

import numpy as np
import pytest
import yaml
from hypothesis import HealthCheck, given, settings
from lxml import etree

import xacrokit
from conftest import ROBOT_EXAMPLES, budget, gen_robot
from xacrokit.emit import emit_urdf, urdf_differences
from xacrokit.importer.urdf_to_spec import URDF_JOINT_ATTRIBUTES, import_text, spec_yaml
from xacrokit.pipeline import build_robot, spec_urdf
from xacrokit.shared.transforms import rpy_matrix
from xacrokit.testing import valid_specs


def urdf_of(path) -> str:
    from xacrokit.reader.robot_input import RobotInput
    from xacrokit.reader.robot_source import read_source

    return read_source(RobotInput(path)).text


def floats(text, count, default):
    return [float(v) for v in text.split()] if text is not None else [default] * count


def transform(origin) -> np.ndarray:
    matrix = np.eye(4)
    if origin is not None:
        matrix[:3, :3] = rpy_matrix(*floats(origin.get("rpy"), 3, 0.0))
        matrix[:3, 3] = floats(origin.get("xyz"), 3, 0.0)
    return matrix


def inertias(root) -> dict[str, tuple[float, np.ndarray, np.ndarray]]:
    """Per link with mass or moments: mass, centre of mass and the tensor about it, both in the link's frame."""
    found = {}
    for link in root.findall("link"):
        inertial = link.find("inertial")
        if inertial is None or inertial.find("mass") is None:
            continue
        at = transform(inertial.find("origin"))
        given = inertial.find("inertia")  # (none: zeros, as the importer reads it)
        i = {k: float(given.get(k, 0) if given is not None else 0) for k in ("ixx", "ixy", "ixz", "iyy", "iyz", "izz")}
        tensor = np.array(
            [[i["ixx"], i["ixy"], i["ixz"]], [i["ixy"], i["iyy"], i["iyz"]], [i["ixz"], i["iyz"], i["izz"]]]
        )
        mass = float(inertial.find("mass").get("value"))
        if mass == 0 and not tensor.any():
            continue  # (an inertial of nothing: the same as none, which the spec writes for it)
        found[link.get("name")] = (mass, at[:3, 3], at[:3, :3] @ tensor @ at[:3, :3].T)
    return found


def geometries(root) -> dict[str, list[tuple[str, str, list, np.ndarray]]]:
    """Per link, every visual then every collision, in order: (visual or collision, shape, sizes, pose in the link).
    A mesh is named by its file's base name (a relative mesh comes back as the copy under meshes/)."""
    found = {}
    for link in root.findall("link"):
        for kind in ("visual", "collision"):
            for element in link.findall(kind):
                shape = next(element.find("geometry").iterchildren(etree.Element))
                sizes = sorted(
                    (k, v.rsplit("/", 1)[-1] if k == "filename" else floats(v, len(v.split()), 0.0))
                    for k, v in shape.attrib.items()
                    if not (k == "scale" and floats(v, 3, 1.0) == [1.0, 1.0, 1.0])
                )  # (scale 1 1 1 is URDF's default: said or not, the same mesh)
                found.setdefault(link.get("name"), []).append(
                    (kind, shape.tag, sizes, transform(element.find("origin")))
                )
    return found


def fk_robot(urdf: str):
    """yourdfpy's model of ``urdf``, loaded once for :func:`poses` (every link, whether or not it has an inertial;
    mimic joints follow their leaders)."""
    import io

    import yourdfpy

    return yourdfpy.URDF.load(
        io.BytesIO(urdf.encode()), load_meshes=False, build_scene_graph=True, build_collision_scene_graph=False
    )


def poses(robot, values: dict[str, float]) -> dict[str, np.ndarray]:
    """Every link's world pose at ``values`` (every moving joint's value: none is left from an earlier call): yourdfpy's
    joint transforms (its scene graph's edges, parent link to child link) composed down the tree once. (Its
    get_transform composes each link's whole path again with numpy's multi_dot, which spent most of the real-robot
    corpus's import tests choosing a multiplication order for 4x4 matrices.)"""
    robot.update_cfg({name: value for name, value in values.items() if name in robot.actuated_joint_names})
    forest = robot.scene.graph.transforms
    found = {robot.scene.graph.base_frame: np.eye(4)}

    def pose(link: str) -> np.ndarray:
        if link not in found:
            parent = forest.parents[link]
            found[link] = pose(parent) @ forest.edge_data[(parent, link)]["matrix"]
        return found[link]

    return {name: pose(name) for name in robot.link_map}


@pytest.mark.parametrize("example", ROBOT_EXAMPLES, ids=lambda p: p.stem)
def test_an_examples_urdf_comes_back_as_the_same_robot(example, tmp_path):
    """...and regenerates it identically: every element, name and number exactly (emit.urdf_differences with rel 0;
    element order and formatting aside), its wheels as wheels and its Gazebo and ros2_control blocks through the
    extension file, as `gen-robot import -o` writes them."""
    original = urdf_of(example)
    imported = import_text(original)
    assert imported.unsupported == []
    assert imported.wheels == WHEELS.get(example.stem, [])
    spec = tmp_path / "imported.yaml"
    if imported.extension:
        (tmp_path / "imported_extension.xacro").write_text(imported.extension, encoding="utf-8")
        imported.spec["extension"] = "imported_extension.xacro"
    spec.write_text(spec_yaml(imported, str(example)), encoding="utf-8")
    xacrokit.generate(spec, tmp_path / "pkg")
    (again_path,) = (tmp_path / "pkg" / "urdf").glob("*.urdf")
    again = again_path.read_text(encoding="utf-8")
    compare(original, again)
    assert urdf_differences(original, again, rel=0.0) == []


WHEELS = {"diff_drive": ["left_wheel", "right_wheel"], "rover": ["wheel_left_link", "wheel_right_link"]}


def compare(original: str, again: str) -> None:
    """The same robot: links (in order) and joints, joint attributes, FK at 20 random values, per-link inertia
    about the centre of mass, and visual geometry."""
    a, b = etree.fromstring(original.encode()), etree.fromstring(again.encode())
    assert [x.get("name") for x in a.findall("link")] == [x.get("name") for x in b.findall("link")]
    assert sorted(x.get("name") for x in a.findall("joint")) == sorted(x.get("name") for x in b.findall("joint"))
    for joint in a.findall("joint"):
        other = b.find(f"joint[@name='{joint.get('name')}']")
        assert other.get("type") == joint.get("type")
        for tag in ("limit", "dynamics", "mimic", "safety_controller"):
            if joint.get("type") not in ("revolute", "continuous", "prismatic"):
                continue  # (URDF readers ignore a fixed joint's limit and dynamics; the spec writes none)
            mine, theirs = joint.find(tag), other.find(tag)
            assert (mine is None) == (theirs is None), (joint.get("name"), tag)
            if mine is not None:
                for key, value in mine.attrib.items():
                    if joint.get("type") == "continuous" and key in ("lower", "upper"):
                        continue  # (URDF readers ignore a continuous joint's range; the spec writes none)
                    if key not in URDF_JOINT_ATTRIBUTES[tag]:
                        continue  # (ANYmal's limit command_effort: no URDF reader's, named in the spec's header)
                    assert theirs.get(key) == value or float(theirs.get(key)) == float(value), (tag, key)
    moving = [j.get("name") for j in a.findall("joint") if j.get("type") in ("revolute", "continuous", "prismatic")]
    rng = np.random.default_rng(20)
    first, second = fk_robot(original), fk_robot(again)
    for _ in range(20):
        values = dict(zip(moving, rng.uniform(-1.5, 1.5, len(moving)), strict=True))
        want, got = poses(first, values), poses(second, values)
        assert set(want) == set(got)
        for link, pose in want.items():
            assert np.abs(got[link] - pose).max() < 1e-9, link
    mine, theirs = inertias(a), inertias(b)
    assert set(mine) == set(theirs)
    for link, (mass, com, tensor) in mine.items():
        other_mass, other_com, other_tensor = theirs[link]
        assert abs(other_mass - mass) <= 1e-9 * mass and np.abs(other_com - com).max() < 1e-9
        assert np.abs(other_tensor - tensor).max() <= 1e-9 * max(np.abs(tensor).max(), 1e-12), link
    mine_g, theirs_g = geometries(a), geometries(b)
    assert set(mine_g) == set(theirs_g)
    for link, drawn in mine_g.items():
        again = theirs_g[link]
        assert [d[:3] for d in again] == [d[:3] for d in drawn], link
        assert all(np.abs(x[3] - y[3]).max() < 1e-12 for x, y in zip(drawn, again, strict=True)), link


def test_what_the_spec_cannot_hold_is_reported(tmp_path):
    import trimesh

    trimesh.creation.box(extents=(0.1, 0.2, 0.3)).export(tmp_path / "m.stl")
    urdf = tmp_path / "odd.urdf"
    urdf.write_text(
        '<robot name="odd"><link name="base link"/><link name="a"><visual><geometry><box size="1 1 1"/></geometry>'
        '</visual><visual><geometry><sphere radius="1"/></geometry></visual></link>'
        '<link name="b"><visual><geometry><mesh filename="m.stl" scale="-1 1 1"/></geometry></visual></link>'
        '<link name="c"><visual><geometry><mesh filename="gone.stl"/></geometry></visual></link>'
        '<joint name="k" type="fixed"><parent link="a"/><child link="c"/></joint>'
        '<joint name="j" type="revolute"><parent link="a"/><child link="b"/><limit effort="1" velocity="1"/>'
        '<calibration rising="0.1"/></joint><gazebo reference="a"><mu1>1</mu1></gazebo>'
        '<transmission name="t"/></robot>',
        encoding="utf-8",
    )
    result = gen_robot("import", urdf, "-o", tmp_path / "odd.yaml")
    assert result.returncode == 1, result.stderr  # (written, with parts not imported: listed)
    said = result.stderr
    assert "link 'base link': the name is not a spec name" in said
    assert "calibration" not in said and "mirror" not in said  # (both imported: the spec has them)
    assert "not imported: mesh 'gone.stl': not found" in said
    text = (tmp_path / "odd.yaml").read_text(encoding="utf-8")
    assert '# kept in the extension file (not modelled by the spec): <gazebo reference="a">' in text
    assert '<transmission name="t">' in text
    spec = yaml.safe_load(text)
    assert spec["joints"]["j"]["limit"] == {"lower": 0.0, "upper": 0.0, "effort": 1.0, "velocity": 1.0}  # (as read)
    assert spec["joints"]["j"]["calibration"] == {"rising": 0.1}
    assert spec["links"]["b"]["shape"]["mesh"]["scale"] == [-1.0, 1.0, 1.0]


def test_several_visuals_and_collisions_a_collision_alone_and_values_no_body_has_come_back(tmp_path):
    """A CAD export's link drawn in pieces, a link that only collides, a link of mass 0 with a flat tensor, a
    continuous joint without limit, and a limit attribute URDF does not define: imported (the spec's `visuals`, a
    collision list, `strict: false`), said in the spec's header, and generated back as the same robot."""
    urdf = tmp_path / "cad.urdf"
    box = '<geometry><box size="0.1 0.2 0.3"/></geometry>'
    ball = '<geometry><sphere radius="0.05"/></geometry>'
    original = (
        '<robot name="cad"><material name="red"><color rgba="1 0 0 1"/></material>'
        f'<link name="base"><visual>{box}<material name="red"/></visual>'
        f'<visual><origin xyz="0 0 0.2" rpy="0 1.5 0"/>{ball}<material name="blue"><color rgba="0 0 1 1"/></material>'
        f'</visual><collision>{box}</collision><collision><origin xyz="0 0 0.2"/>{ball}</collision>'
        '<inertial><mass value="2"/><inertia ixx="0.1" iyy="0.1" izz="0.1"/></inertial></link>'
        f'<link name="bumper"><collision><origin xyz="0.3 0 0"/>{ball}</collision></link>'
        '<link name="flat"><inertial><mass value="0"/><inertia ixx="1e-3" iyy="0" izz="0"/></inertial></link>'
        '<joint name="fix" type="fixed"><parent link="base"/><child link="bumper"/></joint>'
        '<joint name="spin" type="continuous"><parent link="base"/><child link="flat"/><axis xyz="0 0 1"/></joint>'
        '<joint name="lift" type="prismatic"><parent link="bumper"/><child link="lifted"/><axis xyz="0 0 1"/>'
        '<limit lower="0" upper="0.1" effort="0" velocity="0.5" current="3"/></joint>'
        '<link name="lifted"><inertial><mass value="1"/><inertia ixx="1" iyy="1" izz="1"/></inertial></link></robot>'
    )
    urdf.write_text(original, encoding="utf-8")
    result = gen_robot("import", urdf, "-o", tmp_path / "cad.yaml")
    assert result.returncode == 0, result.stderr
    assert "not imported" not in result.stderr
    assert "not URDF, ignored by its readers: joint 'lift' <limit> current" in result.stderr
    text = (tmp_path / "cad.yaml").read_text(encoding="utf-8")
    spec = yaml.safe_load(text)
    assert spec["strict"] is False
    said = [line for line in text.splitlines() if line.startswith("# as the file says it (strict: false): ")]
    assert len(said) == 4, said  # (flat's mass and tensor, spin's missing limit, lift's effort of 0)
    assert spec["links"]["base"]["visuals"] == [
        {
            "shape": {"sphere": {"radius": 0.05}},
            "origin": {"xyz": [0.0, 0.0, 0.2], "rpy": [0.0, 1.5, 0.0]},
            "material": "blue",
        }
    ]
    assert spec["links"]["base"]["collision"] == [
        {"shape": {"box": {"size": [0.1, 0.2, 0.3]}}},
        {"shape": {"sphere": {"radius": 0.05}}, "origin": {"xyz": [0.0, 0.0, 0.2]}},
    ]
    assert spec["links"]["bumper"] == {
        "collision": {"shape": {"sphere": {"radius": 0.05}}, "origin": {"xyz": [0.3, 0.0, 0.0]}}
    }
    generated = gen_robot(tmp_path / "cad.yaml", "-o", tmp_path / "pkg")
    assert generated.returncode == 0, generated.stderr
    compare(original, (tmp_path / "pkg" / "urdf" / "cad.urdf").read_text(encoding="utf-8"))
    strict = text.replace("strict: false\n", "")
    (tmp_path / "strict.yaml").write_text(strict, encoding="utf-8")
    refused = gen_robot(tmp_path / "strict.yaml", "-o", tmp_path / "refused")
    assert refused.returncode == 2 and not (tmp_path / "refused").exists()
    assert refused.stderr.count(f"{tmp_path / 'strict.yaml'}:") == 4, refused.stderr  # (one line per problem)
    assert refused.stderr.startswith("gen-robot: error: 4 problems in strict.yaml:\n"), refused.stderr


def test_a_relative_mesh_is_copied_beside_the_spec_and_into_the_package(tmp_path):
    import trimesh

    (tmp_path / "src" / "meshes").mkdir(parents=True)
    trimesh.creation.box(extents=(0.1, 0.2, 0.3)).export(tmp_path / "src" / "meshes" / "body.stl")
    urdf = tmp_path / "src" / "m.urdf"
    urdf.write_text(
        '<robot name="m"><link name="base_link"><visual><geometry><mesh filename="meshes/body.stl"/></geometry>'
        '</visual><inertial><mass value="1"/><inertia ixx="0.1" iyy="0.1" izz="0.1"/></inertial></link></robot>',
        encoding="utf-8",
    )
    result = gen_robot("import", urdf, "-o", tmp_path / "out" / "m.yaml")
    assert result.returncode == 0, result.stderr
    copied = tmp_path / "out" / "meshes" / "body.stl"
    assert copied.read_bytes() == (tmp_path / "src" / "meshes" / "body.stl").read_bytes()
    spec = yaml.safe_load((tmp_path / "out" / "m.yaml").read_text(encoding="utf-8"))
    assert spec["links"]["base_link"]["shape"] == {"mesh": {"filename": "meshes/body.stl"}}
    result = gen_robot(tmp_path / "out" / "m.yaml", "-o", tmp_path / "pkg")
    assert result.returncode == 0, result.stderr
    assert (tmp_path / "pkg" / "meshes" / "body.stl").read_bytes() == copied.read_bytes()
    assert "package://m_description/meshes/body.stl" in (tmp_path / "pkg" / "urdf" / "m.urdf").read_text()


def test_what_the_spec_does_not_model_is_kept_verbatim_in_the_extension_and_reaches_the_urdf(tmp_path):
    """<gazebo> and <transmission> (and a ${...} that is the vendor's text, not xacro's): gen-robot import -o writes
    them into SPEC_extension.xacro, the generated package starts its extension file with them, and the generated
    URDF holds them as the source had them."""
    source = tmp_path / "lo.urdf"
    leftovers = (
        '<gazebo reference="arm"><mu1>0.5</mu1><plugin name="p" filename="libx.so"><arg>${not_xacro}</arg></plugin>'
        "</gazebo>"
        '<transmission name="t1"><type>transmission_interface/SimpleTransmission</type><joint name="j">'
        "<hardwareInterface>hardware_interface/EffortJointInterface</hardwareInterface></joint></transmission>"
    )
    source.write_text(
        '<robot name="lo"><link name="base_link"/><link name="arm"><inertial><mass value="1"/>'
        '<inertia ixx="0.1" iyy="0.2" izz="0.25"/></inertial></link><joint name="j" type="revolute">'
        '<parent link="base_link"/><child link="arm"/><axis xyz="0 0 1"/>'
        f'<limit lower="-1" upper="1" effort="2" velocity="3"/></joint>{leftovers}</robot>',
        encoding="utf-8",
    )
    result = gen_robot("import", source, "-o", tmp_path / "spec" / "lo.yaml")
    assert result.returncode == 0, result.stderr
    assert yaml.safe_load((tmp_path / "spec" / "lo.yaml").read_text(encoding="utf-8"))["extension"] == (
        "lo_extension.xacro"
    )
    result = gen_robot(tmp_path / "spec" / "lo.yaml", "-o", tmp_path / "pkg")
    assert result.returncode == 0, result.stderr
    generated = etree.fromstring((tmp_path / "pkg" / "urdf" / "lo.urdf").read_bytes())
    original = etree.fromstring(source.read_bytes())
    for tag in ("gazebo", "transmission"):
        (want,) = original.findall(tag)
        (got,) = generated.findall(tag)
        canonical = etree.XMLParser(remove_blank_text=True)
        assert etree.tostring(etree.fromstring(etree.tostring(got), canonical), method="c14n") == etree.tostring(
            etree.fromstring(etree.tostring(want), canonical), method="c14n"
        )
    kept = (tmp_path / "pkg" / "urdf" / "lo_extension.xacro").read_text(encoding="utf-8")
    assert "<arg>$${not_xacro}</arg>" in kept  # (escaped: xacro copies it, evaluates nothing)


# (budget: an example builds and emits a robot, imports it and builds it again, about 0.3 s on the 2-core machine
# under load; 30 in CI, each profile raising it)
@settings(
    max_examples=budget(30), deadline=None, suppress_health_check=[HealthCheck.too_slow, HealthCheck.data_too_large]
)
@given(spec=valid_specs())
def test_a_random_specs_urdf_imports_to_a_spec_that_writes_it_again(tmp_path_factory, spec):
    """Any valid spec (shapes, parts, densities, collision lists, extra visuals, DH arms, wheels, frames): its URDF,
    imported, gives a spec whose URDF has every element, name and number of the first (to 1e-12: a composite link's
    summed tensor or a DH body's is written back as the explicit tensor it was)."""
    folder = tmp_path_factory.mktemp("again")
    (folder / "spec.yaml").write_text(yaml.safe_dump(spec, sort_keys=False), encoding="utf-8")
    first = emit_urdf(build_robot(folder / "spec.yaml"))
    imported = import_text(first)
    assert imported.unsupported == [], imported.unsupported
    if imported.extension:  # (its ros2_control and Gazebo blocks: through the extension file, as import -o does)
        (folder / "again_extension.xacro").write_text(imported.extension, encoding="utf-8")
        imported.spec["extension"] = "again_extension.xacro"
    (folder / "again.yaml").write_text(spec_yaml(imported, "first"), encoding="utf-8")
    again = (
        spec_urdf(folder / "again.yaml").urdf if imported.extension else emit_urdf(build_robot(folder / "again.yaml"))
    )
    assert urdf_differences(first, again, rel=1e-12) == []


def _wheel_urdf(wheel="left_wheel", joint="left_wheel_joint", gazebo=True):
    """A base with one wheel exactly as the spec's `wheels:` writes it (optionally without its friction block)."""
    rpy = f"{math.pi / 2!r} 0 0"
    cylinder = '<geometry><cylinder radius="0.05" length="0.02"/></geometry>'
    axial, transverse = 0.5 * 0.05**2 / 2, 0.5 * (3 * 0.05**2 + 0.02**2) / 12
    return (
        '<robot name="w"><link name="base"><inertial><mass value="1"/><inertia ixx="1" iyy="1" izz="1"/></inertial>'
        f'</link><link name="{wheel}"><visual><origin rpy="{rpy}"/>{cylinder}</visual><collision><origin rpy="{rpy}"/>'
        f'{cylinder}</collision><inertial><mass value="0.5"/><inertia ixx="{transverse!r}" iyy="{axial!r}" '
        f'izz="{transverse!r}"/></inertial></link><joint name="{joint}" type="continuous"><parent link="base"/>'
        f'<child link="{wheel}"/><origin xyz="0 0.1 0"/><axis xyz="0 1 0"/><limit effort="2" velocity="3"/>'
        '<dynamics damping="0.01" friction="0"/></joint>'
        + (f'<gazebo reference="{wheel}"><mu1>0.8</mu1><mu2>0.7</mu2></gazebo>' if gazebo else "")
        + "</robot>"
    )


@pytest.mark.parametrize(
    ("case", "wheels"),
    [({}, ["left_wheel"]), ({"gazebo": False}, []), ({"wheel": "wheel-left"}, []), ({"joint": "wheel/joint"}, [])],
    ids=["wheel", "no-friction-block", "link-name", "joint-name"],
)
def test_a_wheel_is_recognised_only_when_the_spec_writes_it_the_same(case, wheels, tmp_path):
    """Without its own mu1/mu2 block a wheel would gain one (MuJoCo's export would give it friction and priority), and
    a wheel's names are identifiers: such links stay links; each case comes back as the same URDF."""
    original = _wheel_urdf(**case)
    imported = import_text(original)
    assert imported.wheels == wheels and imported.unsupported == []
    if wheels:
        assert imported.spec["wheels"]["left_wheel"]["mu1"] == 0.8 and "extension" not in imported.spec
        assert imported.extension == ""  # (the friction block said by the wheel, not kept twice)
    if imported.extension:
        (tmp_path / "w_extension.xacro").write_text(imported.extension, encoding="utf-8")
        imported.spec["extension"] = "w_extension.xacro"
    (tmp_path / "w.yaml").write_text(spec_yaml(imported, "w.urdf"), encoding="utf-8")
    compare(original, spec_urdf(tmp_path / "w.yaml").urdf)


def test_a_line_break_in_a_name_does_not_reach_the_specs_keys(tmp_path):
    """A carriage return is a line break to YAML: in a comment line of the header it would start a key."""
    urdf = tmp_path / "cr.urdf"
    urdf.write_text(
        '<robot name="cr"><link name="a"><visual><geometry><mesh filename="package://p/a&#13;strict: false&#13;#.stl"/>'
        '</geometry></visual><inertial><mass value="1"/><inertia ixx="1" iyy="1" izz="1"/></inertial></link>'
        '<gazebo reference="a&#13;robot: evil&#13;"><mu1>1</mu1></gazebo></robot>',
        encoding="utf-8",
    )
    result = gen_robot("import", urdf, "-o", tmp_path / "cr.yaml")
    assert result.returncode == 0, result.stderr
    spec = yaml.safe_load((tmp_path / "cr.yaml").read_text(encoding="utf-8"))
    assert list(spec) == ["robot", "links", "extension"] and spec["robot"] == "cr"
    assert spec["links"]["a"]["shape"]["mesh"]["filename"] == "package://p/a\rstrict: false\r#.stl"


def test_a_robot_name_the_spec_cannot_take_is_made_one_and_said(tmp_path):
    for name, written in (("my-robot", "my_robot"), ("if", "if_robot"), ("9" * 300, ("robot_" + "9" * 300)[:200])):
        imported = import_text(f'<robot name="{name}"><link name="a"/></robot>')
        assert imported.spec["robot"] == written and imported.unsupported == []
        assert imported.renamed.startswith(f"robot name {name!r} written {written!r}")
        (tmp_path / "r.yaml").write_text(spec_yaml(imported, "r.urdf"), encoding="utf-8")
        build_robot(tmp_path / "r.yaml")  # (valid)


def test_what_cannot_be_imported_is_said_at_its_line_in_the_file(tmp_path):
    urdf = tmp_path / "loc.urdf"
    urdf.write_text(
        '<robot name="x">\n<link name="a"/>\n<link name="b c"/>\n'
        '<joint name="j" type="fixed"><parent link="a"/><child link="zz"/></joint>\n</robot>\n',
        encoding="utf-8",
    )
    result = gen_robot("import", urdf)
    said = result.stderr.splitlines()
    assert result.returncode == 2 and said[0].endswith("loc.urdf: the robot cannot be imported, the spec refuses it:")
    assert f"  {urdf}:3: link 'b c': the name is not a spec name" in said[1]
    assert said[2] == f"  {urdf}:4: the spec refuses joints.j.child: child 'zz' is not in links"


@pytest.mark.parametrize(("name", "written"), [("__bot", "robot__bot"), ("if", "if_robot"), ("9lives", "robot_9lives")])
def test_a_robot_name_xacro_cannot_hold_is_renamed_to_one_the_package_expands_with(tmp_path, name, written):
    """The importer renames to a name the spec accepts and xacro holds: the package expands with the real xacro."""
    urdf = tmp_path / "r.urdf"
    urdf.write_text(
        f'<robot name="{name}"><link name="base_link"><inertial><mass value="1"/>'
        '<inertia ixx="0.1" iyy="0.1" izz="0.1"/></inertial></link></robot>',
        encoding="utf-8",
    )
    result = gen_robot("import", urdf, "-o", tmp_path / "r.yaml")
    assert result.returncode == 0, result.stderr
    assert yaml.safe_load((tmp_path / "r.yaml").read_text(encoding="utf-8"))["robot"] == written
    generated = gen_robot(tmp_path / "r.yaml", "--via-xacro", "-o", tmp_path / "pkg")
    assert generated.returncode == 0, generated.stderr


@pytest.mark.parametrize(
    ("body", "words"),
    [
        ('<link name="a"/><link name="b"/>'
         '<joint name="ab" type="fixed"><parent link="a"/><child link="b"/></joint>'
         '<joint name="ba" type="fixed"><parent link="b"/><child link="a"/></joint>', "the spec refuses"),
        ('<link name="a"/><joint name="aa" type="fixed"><parent link="a"/><child link="a"/></joint>',
         "the spec refuses"),
    ],
)  # fmt: skip
def test_a_robot_the_spec_refuses_is_exit_2_with_nothing_written(tmp_path, body, words):
    """A cycle, a joint from a link to itself: the spec written would not generate, so none is (it said exit 0)."""
    urdf = tmp_path / "r.urdf"
    urdf.write_text(f'<robot name="r">{body}</robot>', encoding="utf-8")
    result = gen_robot("import", urdf, "-o", tmp_path / "out" / "r.yaml")
    assert result.returncode == 2 and words in result.stderr, result.stderr
    assert not (tmp_path / "out").exists()


def test_parts_not_imported_are_exit_1_and_xacro_in_a_gazebo_block_is_left_out(tmp_path):
    urdf = tmp_path / "r.urdf"
    urdf.write_text(
        '<robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro"><link name="a">'
        '<visual><geometry><mesh filename="meshes/gone.stl"/></geometry></visual></link>'
        '<gazebo><xacro:if value="true"><plugin name="p" filename="x.so"/></xacro:if></gazebo>'
        "<gazebo><static>true</static></gazebo></robot>",
        encoding="utf-8",
    )
    result = gen_robot("import", urdf, "-o", tmp_path / "r.yaml")
    assert result.returncode == 1, result.stderr
    assert "mesh 'meshes/gone.stl': not found" in result.stderr
    extension = (tmp_path / "r_extension.xacro").read_text(encoding="utf-8")
    assert "<static>true</static>" in extension and "xacro:if" not in extension
    assert "left out: it holds xacro" in (tmp_path / "r.yaml").read_text(encoding="utf-8")
