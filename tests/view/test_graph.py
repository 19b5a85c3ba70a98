"""gen-robot graph: the kinematic tree as DOT, read back with pydot (an independent parser): every link and joint a
node of its own (also when a link and a joint share a name), edges parent -> joint -> child, labels with joint type,
axis, limits and masses; names from the file escaped; SVG through Graphviz's dot."""

from __future__ import annotations

import shutil

import pydot
import pytest
from lxml import etree

from conftest import REPO, gen_robot
from xacrokit.shared.urdf_view import UrdfView, read_view
from xacrokit.view.tree_graph import tree_dot

ODD = (
    '<robot name="odd"><link name="a"><inertial><mass value="2"/><inertia ixx="1" ixy="0" ixz="0" iyy="1" iyz="0" '
    'izz="1"/></inertial></link><link name="q&quot;uo\\te"/><link name="line&#10;break"/>'
    '<joint name="a" type="revolute"><parent link="a"/><child link="q&quot;uo\\te"/><axis xyz="0 0 1"/>'
    '<limit lower="-1" upper="1" effort="3" velocity="4"/></joint>'
    '<joint name="j2" type="fixed"><parent link="q&quot;uo\\te"/><child link="line&#10;break"/></joint></robot>'
)


def parsed(dot: str) -> pydot.Dot:
    (graph,) = pydot.graph_from_dot_data(dot)
    return graph


def unquote(text: str) -> str:
    return text[1:-1].replace('\\"', '"').replace("\\\\", "\\") if text.startswith('"') else text


def test_links_and_joints_of_the_same_name_stay_two_nodes_and_odd_names_survive():
    graph = parsed(tree_dot(read_view(ODD)))
    names = {unquote(n.get_name()) for n in graph.get_nodes()} - {"node"}
    assert names == {"link:a", 'link:q"uo\\te', "link:line\\nbreak", "joint:a", "joint:j2"}
    edges = {(unquote(e.get_source()), unquote(e.get_destination())) for e in graph.get_edges()}
    assert edges == {
        ("link:a", "joint:a"),
        ("joint:a", 'link:q"uo\\te'),
        ('link:q"uo\\te', "joint:j2"),
        ("joint:j2", "link:line\\nbreak"),
    }
    joint = graph.get_node('"joint:a"')[0]
    assert unquote(joint.get_label()) == "a\\nrevolute\\naxis 0 0 1\\n[-1, 1]\\neffort 3, velocity 4"


def test_an_example_tree_has_every_link_and_joint_with_its_mass():
    result = gen_robot("graph", REPO / "examples" / "robots" / "two_dof_arm.yaml")
    assert result.returncode == 0, result.stderr
    graph = parsed(result.stdout)
    links = [n for n in graph.get_nodes() if unquote(n.get_name()).startswith("link:")]
    assert {unquote(n.get_name()) for n in links} == {"link:base_link", "link:upper_arm", "link:forearm"}
    assert unquote(graph.get_node('"link:upper_arm"')[0].get_label()) == "upper_arm\\n0.5 kg"


@pytest.mark.skipif(shutil.which("dot") is None, reason="Graphviz is not installed (.ci/run installs it)")
def test_svg_through_graphviz(tmp_path):
    out = tmp_path / "tree.svg"
    result = gen_robot("graph", REPO / "examples" / "robots" / "rover.yaml", "-o", out)
    assert result.returncode == 0, result.stderr
    svg = etree.parse(str(out)).getroot()
    texts = {t.text for t in svg.iter("{http://www.w3.org/2000/svg}text")}
    assert {"base_link", "wheel_left_joint", "scan_joint"} <= texts


def test_bad_graph_output_and_input_are_errors(tmp_path):
    result = gen_robot("graph", REPO / "examples" / "robots" / "rover.yaml", "-o", tmp_path / "tree.png")
    assert result.returncode == 2 and "FILE.dot" in result.stderr and not (tmp_path / "tree.png").exists()
    missing = gen_robot("graph", tmp_path / "nothing.urdf")
    assert missing.returncode == 2 and "Traceback" not in missing.stderr


@pytest.mark.skipif(shutil.which("dot") is None, reason="Graphviz's dot is not installed")
def test_a_layout_that_takes_too_long_is_stopped_and_said(monkeypatch):
    """dot laying out 20,000 links ran 100 s (issue 28): it is stopped at DOT_SECONDS, an error and not exit 70."""
    import xacrokit.view.tree_graph as tree_graph
    from xacrokit.errors import XacrokitError

    monkeypatch.setattr(tree_graph, "DOT_SECONDS", 1e-6)
    dot = tree_dot(_rover_view())
    with pytest.raises(XacrokitError, match="did not lay the tree out in 1e-06 s"):
        tree_graph.svg(dot)


def _rover_view() -> UrdfView:
    from xacrokit.reader.read_robot import read_robot

    return read_robot(REPO / "examples" / "robots" / "rover.yaml").view
