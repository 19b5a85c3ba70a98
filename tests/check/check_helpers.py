"""What the check tests share: the corpus, a robot whose moved link leaves its mass to a link fixed to it, and one
whose joints close a cycle hanging off its root."""

from __future__ import annotations

from conftest import REPO
from xacrokit.check import CheckReport

CORPUS = REPO / "tests" / "check" / "corpus"  # a failing and a passing URDF per rule (make_corpus.py writes them)


def rules_of(report: CheckReport) -> set[str]:
    return {f.rule for f in report.findings}


MOVED_MASSLESS = """<robot name="r">
  <link name="base_link"/>
  <joint name="j1" type="revolute"><parent link="base_link"/><child link="l1"/><axis xyz="0 0 1"/>
    <limit lower="-1" upper="1" effort="1" velocity="1"/><dynamics damping="0.1"/></joint>
  <link name="l1"/>
  <joint name="f1" type="fixed"><parent link="l1"/><child link="flange"/></joint>
  <link name="flange"/>
  <joint name="f2" type="fixed"><parent link="flange"/><child link="body"/></joint>
  <link name="body">BODY</link>
</robot>"""


BODY = (
    '<inertial><mass value="1"/><inertia ixx="0.0108333" iyy="0.0083333" izz="0.0041667" ixy="0" ixz="0" iyz="0"/>'
    "</inertial>"
    '<visual><geometry><box size="0.1 0.2 0.3"/></geometry></visual>'
)


# a cycle a -> b -> a hanging off the root: check reports S002 and sends no consumer anything (check_urdf loops on it)
ROOTED_CYCLE = (
    '<robot name="rc"><link name="root"/><link name="a"/><link name="b"/>'
    '<joint name="ra" type="fixed"><parent link="root"/><child link="a"/></joint>'
    '<joint name="ab" type="fixed"><parent link="a"/><child link="b"/></joint>'
    '<joint name="ba" type="fixed"><parent link="b"/><child link="a"/></joint></robot>'
)
