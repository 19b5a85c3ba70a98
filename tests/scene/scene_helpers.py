"""What the scene tests share: the example scenes, a third-party macro, writing a scene spec, reading its URDF."""

from __future__ import annotations

import yaml
from lxml import etree

from conftest import REPO

SCENES = REPO / "examples" / "scenes"


THIRD_PARTY = """<?xml version="1.0"?>
<robot xmlns:xacro="http://www.ros.org/wiki/xacro">
  <xacro:macro name="acme_arm" params="prefix parent *origin length:=0.5">
    <joint name="${prefix}acme_mount" type="fixed">
      <parent link="${parent}"/><child link="${prefix}acme_base"/><xacro:insert_block name="origin"/>
    </joint>
    <link name="${prefix}acme_base">
      <visual><geometry><box size="0.1 0.1 0.1"/></geometry></visual>
      <inertial><mass value="1"/><inertia ixx="0.01" ixy="0" ixz="0" iyy="0.01" iyz="0" izz="0.01"/></inertial>
    </link>
    <joint name="${prefix}acme_joint" type="revolute">
      <parent link="${prefix}acme_base"/><child link="${prefix}acme_link"/>
      <origin xyz="0 0 0.1"/><axis xyz="0 0 1"/><limit lower="-1" upper="1" effort="1" velocity="1"/>
      <dynamics damping="0.1" friction="0"/>
    </joint>
    <link name="${prefix}acme_link">
      <visual><geometry><cylinder radius="0.02" length="${length}"/></geometry></visual>
      <inertial><mass value="0.5"/><inertia ixx="0.01" ixy="0" ixz="0" iyy="0.01" iyz="0" izz="0.001"/></inertial>
    </link>
  </xacro:macro>
</robot>
"""


def urdf_root(result) -> etree._Element:
    text = {f.path: f.content for f in result.files}[f"urdf/{result.name}.urdf"]
    return etree.fromstring(text.encode())


class NoAliases(yaml.SafeDumper):
    """Specs reject YAML aliases; write shared values out in full."""

    def ignore_aliases(self, data):
        return True


def scene_file(folder, instances, name="s", extra=None):
    data = {"scene": name, "instances": instances, **(extra or {})}
    path = folder / f"{name}.yaml"
    path.write_text(yaml.dump(data, Dumper=NoAliases, sort_keys=False), encoding="utf-8")
    return path
