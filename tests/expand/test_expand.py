"""The expand stage and the CLI around it: $(find) without ROS, declared arguments, located errors, exit codes."""

from __future__ import annotations

import pytest
from lxml import etree

import xacrokit
from conftest import XACRO_HEADER, gen_robot, xacro_doc

ARG_DOC = (
    XACRO_HEADER
    + """  <xacro:arg name="prefix" default=""/>
  <xacro:arg name="use_gripper" default="false"/>
  <link name="$(arg prefix)base_link"/>
  <xacro:if value="$(arg use_gripper)"><link name="$(arg prefix)gripper"/></xacro:if>
</robot>
"""
)


def test_find_xacrokit_resolves_to_the_installed_library(expand):
    root = expand(xacro_doc('<link name="a"><xacro:sphere_inertial mass="1" radius="0.5"/></link>'))
    assert float(root.find("link/inertial/inertia").get("ixx")) == pytest.approx(0.1)


def test_declared_arguments_are_applied(expand):
    root = expand(ARG_DOC, mappings={"prefix": "r1_", "use_gripper": "true"})
    assert [link.get("name") for link in root.iter("link")] == ["r1_base_link", "r1_gripper"]


def test_undeclared_argument_is_rejected_with_the_declared_ones_listed(expand):
    with pytest.raises(xacrokit.ExpandError) as caught:
        expand(ARG_DOC, mappings={"prefx": "r1_"})
    assert "prefx" in str(caught.value) and "declares: prefix, use_gripper" in str(caught.value)


def test_unknown_package_says_how_to_provide_it(expand):
    doc = xacro_doc('<xacro:include filename="$(find no_such_pkg)/urdf/x.xacro"/>', includes=())
    with pytest.raises(xacrokit.ExpandError, match=r"no_such_pkg.*--package no_such_pkg=PATH"):
        expand(doc)


def test_package_paths_resolve_other_packages(tmp_path):
    share = tmp_path / "my_robot_description"
    (share / "urdf").mkdir(parents=True)
    (share / "urdf" / "part.xacro").write_text(XACRO_HEADER + '<link name="from_package"/></robot>\n', encoding="utf-8")
    doc = tmp_path / "top.urdf.xacro"
    doc.write_text(
        xacro_doc('<xacro:include filename="$(find my_robot_description)/urdf/part.xacro"/>', ()), encoding="utf-8"
    )
    root = etree.fromstring(xacrokit.expand(doc, package_paths={"my_robot_description": share}).encode())
    assert root.find("link").get("name") == "from_package"


def test_find_resolution_is_restored_after_expansion(expand):
    import xacro.substitution_args as sa

    before = sa._eval_find
    expand(xacro_doc(""))
    assert sa._eval_find is before


@pytest.mark.parametrize(
    ("doc", "words"),
    [
        (XACRO_HEADER + "<link name='a'>\n", "not well-formed XML"),
        (xacro_doc('<link name="${undefined_property}"/>', ()), "undefined_property"),
        (xacro_doc("<xacro:no_such_macro/>", ()), "unknown macro name: xacro:no_such_macro"),
        (
            XACRO_HEADER + '<link name="$(arg ur_type)"/><xacro:arg name="ur_type" default="ur5e"/></robot>\n',
            r"Undefined substitution argument ur_type: \$\(arg ur_type\) has no value where the document uses it "
            r"\(no default declared before that use; .*\): give it as ur_type:=VALUE",
        ),
    ],
)
def test_bad_documents_raise_expand_error(expand, doc, words):
    with pytest.raises(xacrokit.ExpandError, match=words):
        expand(doc)


def test_missing_file_is_an_expand_error(tmp_path):
    with pytest.raises(xacrokit.ExpandError) as caught:
        xacrokit.expand(tmp_path / "missing.xacro")
    assert caught.value.message == "cannot read the document: No such file or directory"
    assert str(caught.value) == f"{tmp_path / 'missing.xacro'}: cannot read the document: No such file or directory"


def test_error_names_the_public_macro_stack(expand):
    doc = xacro_doc(
        '<xacro:macro name="my_part" params="m"><link name="p"><xacro:box_inertial mass="${m}" x="1" y="1" z="1"/>'
        '</link></xacro:macro><xacro:my_part m="-1"/>'
    )
    with pytest.raises(xacrokit.ExpandError) as caught:
        expand(doc)
    err = caught.value
    assert err.macro_stack == ("box_inertial", "my_part")  # innermost first, private helpers hidden
    assert "box_inertial: parameter mass must be > 0 (kg), got -1" in err.message


def test_cli_expand_writes_the_urdf(tmp_path):
    doc = tmp_path / "a.urdf.xacro"
    doc.write_text(ARG_DOC, encoding="utf-8")
    out = tmp_path / "out" / "a.urdf"
    result = gen_robot("expand", str(doc), "prefix:=x_", "-o", str(out))
    assert result.returncode == 0, result.stderr
    assert etree.parse(str(out)).getroot().find("link").get("name") == "x_base_link"


def test_cli_errors_exit_2_with_a_message_and_no_traceback(tmp_path):
    doc = tmp_path / "a.urdf.xacro"
    doc.write_text(ARG_DOC, encoding="utf-8")
    for args in (
        ["expand", str(doc), "nope:=1"],
        ["expand", str(doc), "notamapping"],
        ["expand", str(tmp_path / "missing.xacro")],
        ["expand", str(doc), "--package", "nopath"],
    ):
        result = gen_robot(*args)
        assert result.returncode == 2, args
        assert result.stderr.startswith("gen-robot: error: ") and "Traceback" not in result.stderr, result.stderr
        assert not (tmp_path / "out").exists()


def test_cli_usage_errors_exit_2():
    assert gen_robot().returncode == 2
    assert gen_robot("no-such-command").returncode == 2


def test_cli_help_lists_the_commands():
    result = gen_robot("--help")
    assert result.returncode == 0
    assert "expand" in result.stdout and "macros" in result.stdout


def test_cli_macros_prints_the_library_folder():
    result = gen_robot("macros", "-v")
    assert result.returncode == 0
    lines = result.stdout.splitlines()
    assert lines[0] == str(xacrokit.macros_dir())
    assert any(line.strip().startswith("$(find xacrokit)/macros/dh.xacro") for line in lines)


def test_a_missing_block_says_which_kind_of_thing_is_missing(tmp_path):
    document = tmp_path / "w.xacro"
    document.write_text(
        '<robot name="w" xmlns:xacro="http://www.ros.org/wiki/xacro">'
        '<xacro:include filename="$(find xacrokit)/macros/wheel.xacro"/><link name="base"/>'
        '<xacro:wheel prefix="" name="left_wheel" parent="base" radius="0.1" width="0.05" mass="1"/></robot>',
        encoding="utf-8",
    )
    with pytest.raises(xacrokit.ExpandError) as caught:
        xacrokit.expand(document)
    assert "block parameter (*origin, say)" in caught.value.message and caught.value.macro_stack == ("wheel",)
