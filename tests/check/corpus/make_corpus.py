"""Writes the check corpus: for every rule, RULE_fail.urdf (the rule must fire) and RULE_pass.urdf (it must not).

Each file is the small valid robot below with one targeted change. Run from this folder: python make_corpus.py
"""

from pathlib import Path

HERE = Path(__file__).resolve().parent

BASE_LINK = """  <link name="base_link">
    <visual><geometry><box size="0.2 0.2 0.1"/></geometry><material name="gray"/></visual>
    <collision><geometry><box size="0.2 0.2 0.1"/></geometry></collision>
    <inertial><mass value="1.0"/><inertia ixx="0.004166666666666667" ixy="0" ixz="0" iyy="0.004166666666666667" iyz="0" izz="0.006666666666666667"/></inertial>
  </link>"""
ARM = """  <link name="arm">
    <visual><origin xyz="0 0 0.15"/><geometry><cylinder radius="0.02" length="0.3"/></geometry></visual>
    <collision><origin xyz="0 0 0.15"/><geometry><cylinder radius="0.02" length="0.3"/></geometry></collision>
    <inertial><origin xyz="0 0 0.15"/><mass value="0.5"/><inertia ixx="0.00380" ixy="0" ixz="0" iyy="0.00380" iyz="0" izz="0.0001"/></inertial>
  </link>"""
SHOULDER = """  <joint name="shoulder" type="revolute">
    <parent link="base_link"/><child link="arm"/>
    <origin xyz="0 0 0.05"/><axis xyz="0 1 0"/>
    <limit lower="-1" upper="1" effort="10" velocity="1"/>
    <dynamics damping="0.1" friction="0"/>
  </joint>"""
MATERIAL = """  <material name="gray"><color rgba="0.5 0.5 0.5 1"/></material>"""


def robot(*parts: str, name: str = "corpus") -> str:
    return f'<?xml version="1.0"?>\n<robot name="{name}">\n' + "\n".join(parts) + "\n</robot>\n"


def base(**replace: str) -> str:
    text = robot(MATERIAL, BASE_LINK, ARM, SHOULDER)
    for old, new in replace.items():
        assert old in text, old
        text = text.replace(old, new)
    return text


def link(name: str) -> str:
    return ARM.replace('"arm"', f'"{name}"')


def joint(name: str, parent: str, child: str, kind: str = "revolute", extra: str = "") -> str:
    return (
        SHOULDER.replace('"shoulder"', f'"{name}"')
        .replace('<parent link="base_link"/>', f'<parent link="{parent}"/>')
        .replace('<child link="arm"/>', f'<child link="{child}"/>')
        .replace('"revolute"', f'"{kind}"')
        .replace("</joint>", extra + "</joint>")
    )


B, S = BASE_LINK, SHOULDER


WHEEL = """  <link name="wheel">
    <visual><origin rpy="1.5707963267948966 0 0"/><geometry><cylinder radius="0.05" length="0.02"/></geometry></visual>
    <collision><origin rpy="1.5707963267948966 0 0"/><geometry><cylinder radius="0.05" length="0.02"/></geometry></collision>
    <inertial><origin rpy="1.5707963267948966 0 0"/><mass value="0.2"/><inertia ixx="0.00013166666666666665" ixy="0" ixz="0" iyy="0.00013166666666666665" iyz="0" izz="0.00025"/></inertial>
  </link>
  <joint name="wheel_joint" type="continuous">
    <parent link="base_link"/><child link="wheel"/>
    <origin xyz="0 0 -0.05"/><axis xyz="0 1 0"/>
    <limit effort="1" velocity="10"/>
    <dynamics damping="0.01" friction="0"/>
  </joint>
"""


def link_a(ixx: str, izz: str) -> str:
    """The arm as the linkage lecture's Link A, with the given moments (ixx = iyy)."""
    return f"""  <link name="arm">
    <visual><geometry><box size="0.5 0.5 0.1"/></geometry></visual>
    <collision><geometry><box size="0.5 0.5 0.1"/></geometry></collision>
    <inertial><mass value="0.5"/><inertia ixx="{ixx}" ixy="0" ixz="0" iyy="{ixx}" iyz="0" izz="{izz}"/></inertial>
  </link>"""


def twin(size: str) -> str:
    """The arm as a box of ``size`` carrying base_link's inertial (1 kg, the 0.2 x 0.2 x 0.1 box's tensor)."""
    inertial = BASE_LINK.splitlines()[3].strip()
    return f"""  <link name="arm">
    <visual><geometry><box size="{size}"/></geometry></visual>
    <collision><geometry><box size="{size}"/></geometry></collision>
    {inertial}
  </link>"""


def ball(collision: str) -> str:
    """The arm as a ball of 0.05 m drawn by ball_detailed.stl (1,280 triangles), colliding with ``collision``."""
    return f"""  <link name="arm">
    <visual><geometry><mesh filename="meshes/ball_detailed.stl"/></geometry></visual>
    <collision><geometry><mesh filename="{collision}"/></geometry></collision>
    <inertial><mass value="0.5"/><inertia ixx="0.0005" ixy="0" ixz="0" iyy="0.0005" iyz="0" izz="0.0005"/></inertial>
  </link>"""


def hand(xyz: str) -> str:
    """A second arm, ``hand``, fixed to the arm at ``xyz``: no joint joins it to the base."""
    return (
        link("hand")
        + f"""
  <joint name="wrist" type="fixed">
    <parent link="arm"/><child link="hand"/>
    <origin xyz="{xyz}"/>
  </joint>
"""
    )


CASES = {
    "U001": ('<robot name="x"><link name="a"></robot>\n', base()),
    "U003": (  # a prefix used without its declaration (Drake's exporters write drake: elements)
        base(**{"</robot>": "<drake:collision_filter_group/>\n</robot>"}),
        base(
            **{
                '<robot name="corpus">': '<robot name="corpus" xmlns:drake="http://drake.mit.edu">',
                "</robot>": "<drake:collision_filter_group/>\n</robot>",
            }
        ),
    ),
    "U004": (  # a xacro document read as a URDF, or an expression never expanded
        base(**{'<box size="0.2 0.2 0.1"/></geometry><material': '<box size="${width} 0.2 0.1"/></geometry><material'}),
        base(),
    ),
    "S007": (robot(MATERIAL, B, name=""), robot(MATERIAL, B)),
    "G001": (
        base(
            **{
                '<cylinder radius="0.02" length="0.3"/></geometry></collision>': '<cylinder radius="0" length="0.3"/></geometry></collision>'
            }
        ),
        base(),
    ),
    "S001": (robot(MATERIAL, B, link("arm")), base()),
    "S002": (
        robot(
            MATERIAL,
            B,
            link("arm"),
            link("a2"),
            S,
            joint("j2", "arm", "a2"),
            link("c1"),
            link("c2"),
            joint("c12", "c1", "c2"),
            joint("c21", "c2", "c1"),
        ),
        base(),
    ),
    "S003": (base(**{'<child link="arm"/>': '<child link="ghost"/>'}), base()),
    "S004": (robot(MATERIAL, B, link("arm"), link("arm"), S), base()),
    "S005": (robot(MATERIAL, B, link("arm"), link("a2"), S, joint("shoulder", "arm", "a2")), base()),
    "S006": (
        robot(MATERIAL, B, link("arm"), link("a2"), S, joint("j2", "a2", "arm"), joint("j3", "base_link", "a2")),
        base(),
    ),
    "J001": (base(**{'<limit lower="-1" upper="1" effort="10" velocity="1"/>': ""}), base()),
    "J002": (base(**{'lower="-1" upper="1"': 'lower="1" upper="-1"'}), base()),
    # a <limit> without effort or velocity (urdfdom rejects it); 0 is a warning (test_check_rules)
    "J003": (base(**{'effort="10" ': ""}), base()),
    "J004": (base(**{' velocity="1"': ""}), base()),
    "J005": (  # a <limit> without effort (urdfdom rejects it); none at all is fine (a passive continuous joint)
        base(**{'type="revolute"': 'type="continuous"', 'lower="-1" upper="1" effort="10" ': ""}),
        base(**{'type="revolute"': 'type="continuous"', '<limit lower="-1" upper="1" effort="10" velocity="1"/>': ""}),
    ),
    "J006": (base(**{'<axis xyz="0 1 0"/>': '<axis xyz="0 0 0"/>'}), base()),
    "J007": (base(**{'<axis xyz="0 1 0"/>': '<axis xyz="0 2 0"/>'}), base()),
    "J008": (
        robot(
            MATERIAL,
            B,
            link("arm"),
            link("a2"),
            S,
            joint("j2", "base_link", "a2", "prismatic", '<mimic joint="elbow"/>'),
        ),
        robot(
            MATERIAL,
            B,
            link("arm"),
            link("a2"),
            S,
            joint("j2", "base_link", "a2", "revolute", '<mimic joint="shoulder"/>'),
        ),
    ),
    "J009": (base(**{'<dynamics damping="0.1" friction="0"/>': ""}), base()),
    "J010": (
        base(
            **{"</joint>": '<safety_controller soft_lower_limit="-2" soft_upper_limit="0.9" k_velocity="10"/></joint>'}
        ),
        base(
            **{
                "</joint>": '<safety_controller soft_lower_limit="-0.9" soft_upper_limit="0.9" k_velocity="10"/></joint>'
            }
        ),
    ),
    "J011": (base(**{'type="revolute"': 'type="ball"'}), base()),
    "J013": (base(**{'lower="-1" upper="1"': 'lower="0.5" upper="0.5"'}), base()),
    "J012": (
        robot(MATERIAL, B, link("arm"), link("a2"), S, joint("j2", "arm", "a2", "floating")),
        robot(MATERIAL, B, link("arm"), link("a2"), S, joint("j2", "base_link", "a2", "floating")),
    ),
    "I001": (base(**{'<mass value="0.5"/>': '<mass value="-0.5"/>'}), base()),
    "I002": (
        base(**{'ixx="0.00380" ixy="0"': 'ixx="0.00380" ixy="0.005"'}),
        # a bare frame may write an all-zero inertial to say "massless"
        base(
            **{
                "</robot>": '<link name="tool0"><inertial><mass value="0"/><inertia ixx="0" ixy="0" ixz="0" iyy="0" iyz="0" izz="0"/></inertial></link>\n'
                '<joint name="tool0_joint" type="fixed"><parent link="arm"/><child link="tool0"/></joint>\n</robot>'
            }
        ),
    ),
    "I003": (base(**{'izz="0.0001"': 'izz="0.009"'}), base()),
    "I004": (
        base(
            **{
                'ixx="0.00380" ixy="0" ixz="0" iyy="0.00380" iyz="0" izz="0.0001"': 'ixx="3800" ixy="0" ixz="0" iyy="3800" iyz="0" izz="100"'
            }
        ),
        base(),
    ),
    "I005": (
        base(
            **{
                'ixx="0.00380" ixy="0" ixz="0" iyy="0.00380" iyz="0" izz="0.0001"': 'ixx="0.001" ixy="0" ixz="0" iyy="0.001" iyz="0" izz="0.001"'
            }
        ),
        base(),
    ),
    "I006": (  # urdfdom: "Inertial element must have inertia element"
        base(**{'<inertia ixx="0.00380" ixy="0" ixz="0" iyy="0.00380" iyz="0" izz="0.0001"/>': ""}),
        base(),
    ),
    "I007": (  # a base with geometry and no mass anywhere in its body; with mass on a link fixed to it, fine
        base(**{BASE_LINK.splitlines()[3] + "\n": ""}),
        base(
            **{
                BASE_LINK.splitlines()[3] + "\n": "",
                "</robot>": '<link name="ballast"><inertial><mass value="2"/><inertia ixx="0.01" ixy="0" ixz="0" '
                'iyy="0.01" iyz="0" izz="0.01"/></inertial></link>\n<joint name="ballast_joint" type="fixed">'
                '<parent link="base_link"/><child link="ballast"/></joint>\n</robot>',
            }
        ),
    ),
    "I008": (  # the linkage lecture's Link A: a 0.5 x 0.5 x 0.1 m box of 0.5 kg written with 0.005 * identity
        base(**{ARM: link_a("0.005", "0.005")}),
        base(**{ARM: link_a("0.010833333333333334", "0.020833333333333332")}),  # (the box's own tensor)
    ),
    "I009": (  # base_link's inertial copied onto an arm three times its size; on a twin of its size, rightly
        base(**{ARM: twin("0.6 0.6 0.3")}),
        base(**{ARM: twin("0.2 0.2 0.1")}),
    ),
    "G005": (  # the arm collides with its 1,280-triangle visual mesh; with an 80-triangle one, fine
        base(**{ARM: ball("meshes/ball_detailed.stl")}),
        base(**{ARM: ball("meshes/ball_coarse.stl")}),
    ),
    "G006": (  # a wheel that touches the ground, in a file with a <gazebo> block, without friction; then with it
        base(
            **{"</robot>": WHEEL + '<gazebo reference="base_link"><material>Gazebo/Grey</material></gazebo>\n</robot>'}
        ),
        base(**{"</robot>": WHEEL + '<gazebo reference="wheel"><mu1>1.0</mu1><mu2>1.0</mu2></gazebo>\n</robot>'}),
    ),
    "G007": (  # a hand fixed to the arm, reaching back into the base at home; then beyond the arm's end
        base(**{"</robot>": hand("0 0 -0.12") + "</robot>"}),
        base(**{"</robot>": hand("0 0 0.35") + "</robot>"}),
    ),
    "G008": (base(), robot(MATERIAL, BASE_LINK)),  # with its SRDF (G008_fail.srdf): counted; one link, none: nothing
    "R001": (
        base(**{"</robot>": '<gazebo reference="nowhere"><mu1>1</mu1></gazebo>\n</robot>'}),
        base(**{"</robot>": '<gazebo reference="arm"><mu1>1</mu1></gazebo>\n</robot>'}),
    ),
    "R002": (base(**{'<material name="gray"/>': '<material name="grey"/>'}), base()),
    "R003": (
        base(
            **{
                '<box size="0.2 0.2 0.1"/></geometry><material': '<mesh filename="meshes/missing.stl"/></geometry><material'
            }
        ),
        base(
            **{
                '<box size="0.2 0.2 0.1"/></geometry><material': '<mesh filename="meshes/cube.stl"/></geometry><material'
            }
        ),
    ),
    "P001": (
        base(**{'"arm"': '"r1_arm"', '"base_link"': '"r1_base_link"', '"shoulder"': '"shoulder"'}),
        base(**{'"arm"': '"r1_arm"', '"base_link"': '"r1_base_link"', '"shoulder"': '"r1_shoulder"'}),
    ),
    "C001": (
        base(
            **{
                '<visual><geometry><box size="0.2 0.2 0.1"/></geometry><material name="gray"/></visual>': '<visual><material name="gray"/></visual>'
            }
        ),
        base(),
    ),
}

CUBE_STL = """solid cube
facet normal 0 0 1
 outer loop
  vertex 0 0 0
  vertex 1 0 0
  vertex 1 1 0
 endloop
endfacet
endsolid cube
"""

# G008's robot's SRDF, found beside it: the arm and the base disabled as adjacent
G008_SRDF = """<?xml version="1.0"?>
<robot name="corpus">
  <disable_collisions link1="arm" link2="base_link" reason="Adjacent"/>
</robot>
"""

if __name__ == "__main__":
    for rule, (failing, passing) in CASES.items():
        (HERE / f"{rule}_fail.urdf").write_text(failing, encoding="utf-8")
        (HERE / f"{rule}_pass.urdf").write_text(passing, encoding="utf-8")
    (HERE / "meshes" / "cube.stl").write_text(CUBE_STL, encoding="utf-8")
    (HERE / "G008_fail.srdf").write_text(G008_SRDF, encoding="utf-8")
    import trimesh  # (icospheres of 0.05 m: 1,280 triangles, a visual's detail; 80, a collision mesh's)

    for name, divisions in (("ball_detailed", 3), ("ball_coarse", 1)):
        trimesh.creation.icosphere(subdivisions=divisions, radius=0.05).export(HERE / "meshes" / f"{name}.stl")
    print(f"wrote {2 * len(CASES)} files")
