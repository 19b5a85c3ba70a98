"""The write stage and the gen-robot generate / new / schema commands."""

from __future__ import annotations

import ast
import hashlib
import json
import os
import re
import sys
from pathlib import Path, PurePosixPath

import jsonschema
import pytest
import yaml
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st
from lxml import etree

import xacrokit
from conftest import REPO, ROBOT_EXAMPLES, gen_robot
from xacrokit.check import check
from xacrokit.render import RenderedFile
from xacrokit.starter import KINDS as STARTER_KINDS
from xacrokit.starter import starter_text, write_starter
from xacrokit.write import MANIFEST, ConflictError, plan, write

SPEC = REPO / "examples" / "robots" / "two_dof_arm.yaml"


def snapshot(root):
    return {
        p.relative_to(root).as_posix(): (p.read_bytes(), p.stat().st_mtime_ns) for p in root.rglob("*") if p.is_file()
    }


def test_first_run_creates_everything_and_a_second_changes_nothing(tmp_path):
    out = tmp_path / "pkg"
    first = xacrokit.generate(SPEC, out)
    assert {a.action for a in first.actions} == {"create"}
    before = snapshot(out)
    second = xacrokit.generate(SPEC, out)
    assert {a.action for a in second.actions} == {"identical"}
    assert snapshot(out) == before  # same bytes and same mtimes: nothing was rewritten


def test_an_edited_file_is_a_conflict_kept_and_nothing_is_written(tmp_path):
    out = tmp_path / "pkg"
    xacrokit.generate(SPEC, out)
    edited = out / "README.md"
    edited.write_text("my notes\n", encoding="utf-8")
    spec = tmp_path / "two_dof_arm.yaml"
    spec.write_text(SPEC.read_text(encoding="utf-8").replace("mass: 0.3", "mass: 0.35"), encoding="utf-8")
    before = snapshot(out)
    with pytest.raises(ConflictError) as caught:
        xacrokit.generate(spec, out)
    assert [c.path for c in caught.value.conflicts] == ["README.md"]
    assert "edited since it was generated" in str(caught.value)
    assert snapshot(out) == before  # not even the files that would merely have been updated


def test_updates_replace_only_what_changed_and_force_overwrites_edits(tmp_path):
    out = tmp_path / "pkg"
    xacrokit.generate(SPEC, out)
    spec = tmp_path / "two_dof_arm.yaml"
    spec.write_text(SPEC.read_text(encoding="utf-8").replace("mass: 0.3", "mass: 0.35"), encoding="utf-8")
    (out / "README.md").write_text("my notes\n", encoding="utf-8")
    result = xacrokit.generate(spec, out, force=True)
    actions = {a.path: a.action for a in result.actions}
    assert actions["README.md"] == "overwrite"
    assert actions["urdf/two_dof_arm_macro.xacro"] == actions["urdf/two_dof_arm.urdf"] == "update"
    assert actions["package.xml"] == "identical"
    assert "0.35" in (out / "urdf" / "two_dof_arm.urdf").read_text(encoding="utf-8")


def test_dry_run_writes_nothing(tmp_path):
    out = tmp_path / "pkg"
    result = xacrokit.generate(SPEC, out, dry_run=True)
    assert {a.action for a in result.actions} == {"create"} and not out.exists()


def test_files_not_written_by_us_are_conflicts(tmp_path):
    out = tmp_path / "pkg"
    (out / "urdf").mkdir(parents=True)
    (out / "package.xml").write_text("<package/>", encoding="utf-8")
    with pytest.raises(ConflictError, match="not written by xacrokit"):
        xacrokit.generate(SPEC, out)
    assert sorted(p.name for p in out.rglob("*")) == ["package.xml", "urdf"]


def test_writes_never_leave_the_output_folder(tmp_path):
    with pytest.raises(xacrokit.XacrokitError, match="outside"):
        plan([RenderedFile("../escape.txt", "x")], tmp_path / "pkg")
    (tmp_path / "pkg").mkdir()
    (tmp_path / "elsewhere").mkdir()
    (tmp_path / "pkg" / "link").symlink_to(tmp_path / "elsewhere")
    with pytest.raises(xacrokit.XacrokitError, match="outside"):
        write([RenderedFile("link/file.txt", "x")], tmp_path / "pkg")
    assert not any((tmp_path / "elsewhere").iterdir())


def test_manifest_records_what_was_generated(tmp_path):
    out = tmp_path / "pkg"
    result = xacrokit.generate(SPEC, out)
    manifest = json.loads((out / MANIFEST).read_text(encoding="utf-8"))
    assert sorted(manifest["files"]) == sorted(f.path for f in result.files)


def test_the_default_package_needs_no_macro_library(tmp_path):
    # inline by default: plain links and joints, no copied macros, no DH tables for xacro to read
    arm = REPO / "examples" / "robots" / "industrial_arm_std_dh.yaml"
    result = gen_robot(arm, "-o", tmp_path / "pkg")
    assert result.returncode == 0, result.stderr
    paths = {p.relative_to(tmp_path / "pkg").as_posix() for p in (tmp_path / "pkg").rglob("*") if p.is_file()}
    assert not any(p.startswith("urdf/xacrokit/") or p.endswith(".dh.yaml") for p in paths), paths
    macro = (tmp_path / "pkg" / "urdf" / "ur5_macro.xacro").read_text(encoding="utf-8")
    assert "xacrokit/" not in macro and "<xacro:dh_arm" not in macro
    assert '<link name="${prefix}shoulder_link">' in macro


def test_switching_modes_removes_what_is_no_longer_generated_and_keeps_edits(tmp_path):
    arm = REPO / "examples" / "robots" / "industrial_arm_std_dh.yaml"
    out = tmp_path / "pkg"
    copied = {f.path for f in xacrokit.generate(arm, out, macros="copy").files}
    stale = sorted(p for p in copied if p.startswith("urdf/xacrokit/") or p.endswith(".dh.yaml"))
    assert "urdf/xacrokit/dh.xacro" in stale and "config/ur5.dh.yaml" in stale
    edited = out / "urdf" / "xacrokit" / "links.xacro"
    edited.write_text(edited.read_text(encoding="utf-8") + "<!-- mine -->\n", encoding="utf-8")
    before = snapshot(out)
    dry = gen_robot(arm, "-o", out, "--dry-run")
    plan_lines = {" ".join(line.split()) for line in dry.stdout.splitlines()}
    assert dry.returncode == 0 and "remove urdf/xacrokit/dh.xacro (no longer generated)" in plan_lines, dry.stdout
    assert "would remove 5 no longer generated; would keep 1" in dry.stdout
    assert snapshot(out) == before
    result = gen_robot(arm, "-o", out)
    assert result.returncode == 0, result.stderr
    assert "removed 5 no longer generated; kept 1 no longer generated (edited, or not removable)" in result.stdout, (
        result.stdout
    )
    assert "keep urdf/xacrokit/links.xacro (no longer generated, but edited since: kept)" in {
        " ".join(line.split()) for line in result.stdout.splitlines()
    }
    left = {p.relative_to(out).as_posix() for p in out.rglob("*")}
    assert [p for p in stale if p in left] == ["urdf/xacrokit/links.xacro"]
    assert "urdf/xacrokit/_inc" not in left  # the folder it emptied went too
    assert "urdf/xacrokit/links.xacro" not in json.loads((out / MANIFEST).read_text(encoding="utf-8"))["files"]
    again = xacrokit.generate(arm, out)
    assert {a.action for a in again.actions} == {"identical"}  # the kept file is no longer ours


def add_to_manifest(out, path, content: bytes):
    manifest = json.loads((out / MANIFEST).read_text(encoding="utf-8"))
    manifest["files"][path] = hashlib.sha256(content).hexdigest()
    (out / MANIFEST).write_text(json.dumps(manifest), encoding="utf-8")


def test_a_manifest_naming_files_outside_the_folder_removes_nothing_there(tmp_path):
    out = tmp_path / "pkg"
    xacrokit.generate(SPEC, out)
    victim = tmp_path / "victim.txt"
    victim.write_text("x", encoding="utf-8")
    for name in ("../victim.txt", str(victim), "urdf/../../victim.txt", "./../victim.txt", "a\0b"):
        add_to_manifest(out, name, b"x")
    result = xacrokit.generate(SPEC, out)
    assert victim.exists() and {a.action for a in result.actions} == {"identical"}


def test_stale_files_behind_links_or_written_this_run_are_never_removed(tmp_path):
    out = tmp_path / "pkg"
    xacrokit.generate(SPEC, out)
    elsewhere = tmp_path / "elsewhere"
    elsewhere.mkdir()
    (elsewhere / "old.xacro").write_text("x", encoding="utf-8")
    (out / "linked").symlink_to(elsewhere)  # a folder link: the file behind it is not ours to delete
    add_to_manifest(out, "linked/old.xacro", b"x")
    (out / "urdf" / "alias.xacro").symlink_to(elsewhere / "old.xacro")  # a file link
    add_to_manifest(out, "urdf/alias.xacro", b"x")
    (out / "real").mkdir()  # a link to a folder inside the package: the user's file behind it is not ours either
    (out / "real" / "f.txt").write_text("x", encoding="utf-8")
    (out / "inner").symlink_to(out / "real")
    add_to_manifest(out, "inner/f.txt", b"x")
    entry = out / "urdf" / "two_dof_arm.urdf.xacro"
    os.link(entry, out / "urdf" / "OLD.urdf.xacro")  # another name for a file this run writes
    add_to_manifest(out, "urdf/OLD.urdf.xacro", entry.read_bytes())
    result = xacrokit.generate(SPEC, out)
    assert (elsewhere / "old.xacro").exists() and (out / "urdf" / "alias.xacro").is_symlink()
    assert (out / "real" / "f.txt").exists() and entry.exists()
    stale = {a.path: a for a in result.actions if a.action in ("remove", "keep")}
    assert {p: a.action for p, a in stale.items()} == dict.fromkeys(
        ["inner/f.txt", "linked/old.xacro", "urdf/OLD.urdf.xacro", "urdf/alias.xacro"], "keep"
    )
    assert all("symbolic link" in stale[p].reason for p in ("inner/f.txt", "linked/old.xacro", "urdf/alias.xacro"))


def test_a_removal_the_file_system_refuses_is_reported_as_kept(tmp_path, monkeypatch):
    arm = REPO / "examples" / "robots" / "industrial_arm_std_dh.yaml"
    out = tmp_path / "pkg"
    xacrokit.generate(arm, out, macros="copy")

    def refuse(path, *, dir_fd=None):
        raise PermissionError(13, "Permission denied", str(path))

    monkeypatch.setattr(os, "unlink", refuse)
    result = xacrokit.generate(arm, out)
    kept = [a for a in result.actions if a.action == "keep"]
    assert kept and all("could not remove it: Permission denied" in a.reason for a in kept)
    assert not any(a.action == "remove" for a in result.actions)
    monkeypatch.undo()
    again = xacrokit.generate(arm, out)  # the manifest was written: the next run is not stuck on them
    assert {a.action for a in again.actions} == {"identical"}
    assert (out / "urdf" / "xacrokit" / "dh.xacro").exists()  # left for the user, no longer ours


def test_a_folder_that_cannot_be_written_is_an_error_not_a_traceback(tmp_path):
    blocker = tmp_path / "a_file"
    blocker.write_text("x", encoding="utf-8")
    result = gen_robot(SPEC, "-o", blocker / "pkg")
    assert result.returncode != 0 and "Traceback" not in result.stderr
    assert f"cannot write the package in {blocker / 'pkg'}" in result.stderr and "nothing was written" in result.stderr


def test_invalid_spec_writes_nothing_and_exits_2(tmp_path):
    spec = tmp_path / "bad.yaml"
    spec.write_text(
        SPEC.read_text(encoding="utf-8").replace("parent: upper_arm", "parent: upper_ram"), encoding="utf-8"
    )
    result = gen_robot(spec, "-o", tmp_path / "out")
    assert result.returncode == 2, result.stderr
    assert f"{spec}:" in result.stderr and "did you mean 'upper_arm'" in result.stderr
    assert "Traceback" not in result.stderr and not (tmp_path / "out").exists()


def test_cli_generate_reports_the_plan_and_conflicts_exit_1(tmp_path):
    out = tmp_path / "pkg"
    result = gen_robot(SPEC, "-o", out)
    assert result.returncode == 0, result.stderr
    assert "create  urdf/two_dof_arm.urdf" in result.stdout
    (out / "package.xml").write_text("edited", encoding="utf-8")
    again = gen_robot(SPEC, "-o", out)
    assert again.returncode == 1 and "package.xml: edited since it was generated" in again.stderr
    assert (out / "package.xml").read_text(encoding="utf-8") == "edited"
    dry = gen_robot("generate", SPEC, "-o", out, "--dry-run", "--force")
    assert dry.returncode == 0 and "overwrite  package.xml" in dry.stdout and "nothing written" in dry.stdout
    assert (out / "package.xml").read_text(encoding="utf-8") == "edited"


def test_default_output_is_name_description_in_the_working_folder(tmp_path):
    result = gen_robot(SPEC, cwd=tmp_path)
    assert result.returncode == 0, result.stderr
    assert (tmp_path / "two_dof_arm_description" / "urdf" / "two_dof_arm.urdf").is_file()


def test_macros_find_includes_the_installed_library(tmp_path):
    out = tmp_path / "pkg"
    result = xacrokit.generate(SPEC, out, macros="find", via_xacro=True)  # xacro must find the installed library
    macro = (out / "urdf" / "two_dof_arm_macro.xacro").read_text(encoding="utf-8")
    assert '<xacro:include filename="$(find xacrokit)/macros/inertia.xacro"/>' in macro
    assert not (out / "urdf" / "xacrokit").exists()
    assert "<exec_depend>xacrokit</exec_depend>" in (out / "package.xml").read_text(encoding="utf-8")
    copy = xacrokit.generate(SPEC, tmp_path / "copy", macros="copy", via_xacro=True)
    urdf = {f.path: f.content for f in copy.files}["urdf/two_dof_arm.urdf"]
    assert {f.path: f.content for f in result.files}["urdf/two_dof_arm.urdf"] == urdf


@pytest.mark.parametrize("kind", STARTER_KINDS)
def test_new_writes_a_starter_that_generates(tmp_path, kind):
    result = gen_robot("new", f"my_{kind}", "--kind", kind, cwd=tmp_path)
    assert result.returncode == 0, result.stderr
    spec = tmp_path / f"my_{kind}.yaml"
    text = spec.read_text(encoding="utf-8")
    assert all(line.startswith("# ") for line in text.splitlines()[:3])  # opens with its comments
    generated = xacrokit.generate(spec, tmp_path / "out")
    assert generated.robot.name == f"my_{kind}"
    again = gen_robot("new", f"my_{kind}", cwd=tmp_path)
    assert again.returncode == 2 and "already exists" in again.stderr
    assert spec.read_text(encoding="utf-8") == text
    assert gen_robot("new", "bad name", cwd=tmp_path).returncode == 2


def test_plain_new_writes_the_arm_starter(tmp_path):
    assert gen_robot("new", "bot", cwd=tmp_path).returncode == 0
    assert (tmp_path / "bot.yaml").read_text(encoding="utf-8") == starter_text("bot", "arm")


@pytest.mark.parametrize("kind", STARTER_KINDS)
def test_every_starter_package_checks_clean_with_strict(tmp_path, kind):
    """`gen-robot new` then `gen-robot` then `gen-robot check --strict`: no errors and no warnings."""
    spec = write_starter(f"my_{kind}", kind=kind, output=tmp_path / f"my_{kind}.yaml")
    out = tmp_path / f"my_{kind}_description"
    xacrokit.generate(spec, out)
    reports = [
        check(out / "urdf" / f"my_{kind}.urdf"),
        check(spec, consumers=[]),
        # the entry xacro with a prefix, as a second instance would use it: still clean, every name prefixed
        check(
            out / "urdf" / f"my_{kind}.urdf.xacro",
            {"prefix": "left_"},
            prefix="left_",
            consumers=[],
            package_paths={f"my_{kind}_description": out},
        ),
    ]
    for report in reports:
        assert report.errors == [] and report.warnings == [], [str(f) for f in report.findings]
        assert report.exit_code(strict=True) == 0
    assert reports[0].consumers and all(c.status == "accepted" for c in reports[0].consumers)
    root = etree.parse(str(out / "urdf" / f"my_{kind}.urdf")).getroot()
    moving = [j for j in root.findall("joint") if j.get("type") in ("revolute", "continuous", "prismatic")]
    assert moving
    for joint in moving:  # every moving joint carries sensible, positive damping
        dynamics = joint.find("dynamics")
        assert dynamics is not None, joint.get("name")
        assert 0 < float(dynamics.get("damping")) <= 5 and 0 <= float(dynamics.get("friction", "0")) <= 5


@pytest.mark.parametrize("kind", STARTER_KINDS)
def test_starter_names_no_path_of_this_machine_and_says_how_to_get_the_schema(tmp_path, kind):
    text = starter_text("bot", kind)
    machine_paths = {str(REPO), sys.prefix, str(Path(xacrokit.__file__).resolve().parent), str(Path.home())}
    assert not [p for p in machine_paths if p in text]
    assert not re.search(r"(?m)^#\s*yaml-language-server", text)  # no modeline naming a file that is not there
    # ... but the comment's recipe works: the schema it writes validates the starter through the modeline it shows
    (hint,) = [line for line in text.splitlines() if "$schema=" in line]
    schema_file = hint.split("$schema=", 1)[1].strip()
    assert not PurePosixPath(schema_file).is_absolute() and "gen-robot schema > " + schema_file in text
    written = gen_robot("schema", cwd=tmp_path)
    assert written.returncode == 0
    (tmp_path / schema_file).write_text(written.stdout, encoding="utf-8")
    jsonschema.validate(yaml.safe_load(text), json.loads((tmp_path / schema_file).read_text(encoding="utf-8")))


def test_schema_command_prints_a_valid_2020_12_schema_with_descriptions():
    result = gen_robot("schema")
    schema = json.loads(result.stdout)
    jsonschema.Draft202012Validator.check_schema(schema)

    def walk(node, where):
        if isinstance(node, dict):
            if "properties" in node:
                for key, value in node["properties"].items():
                    assert "description" in value or "$ref" in value, f"{where}.{key} has no description"
            for key, value in node.items():
                walk(value, f"{where}.{key}")
        elif isinstance(node, list):
            for item in node:
                walk(item, where)

    walk(schema, "$")
    for name, definition in schema["$defs"].items():
        assert "description" in definition, name


def test_examples_carry_the_schema_modeline_and_validate_against_the_schema():
    from xacrokit.validate import robot_schema

    robots = [*ROBOT_EXAMPLES, *sorted((REPO / "examples" / "scenes" / "robots").glob("*.yaml"))]
    assert len(robots) == 11
    for path in robots:
        text = path.read_text(encoding="utf-8")
        schema = Path(os.path.relpath(REPO / "schemas" / "robot.schema.json", path.parent)).as_posix()
        assert text.startswith(f"# yaml-language-server: $schema={schema}\n"), path.name
        jsonschema.validate(yaml.safe_load(text), robot_schema())
        assert (path.parent / schema).is_file()


def test_help_of_every_command():
    for args in (["--help"], ["generate", "--help"], ["new", "--help"], ["schema", "--help"], ["expand", "--help"]):
        result = gen_robot(*args)
        assert result.returncode == 0 and "usage: gen-robot" in result.stdout, args
    assert "gen-robot SPEC.yaml" in gen_robot("--help").stdout


def test_generated_launch_file_is_python(tmp_path):
    result = xacrokit.generate(SPEC, tmp_path / "pkg")
    launch = {f.path: f.content for f in result.files}["launch/display.launch.py"]
    compile(launch, "display.launch.py", "exec")
    assert os.path.exists(tmp_path / "pkg" / "launch" / "display.launch.py")


def node_arguments(launch: str, package: str) -> list[ast.expr]:
    """The ``arguments=[...]`` elements of the one ``Node(package=PACKAGE, ...)`` call of a launch file."""
    calls = [
        node
        for node in ast.walk(ast.parse(launch))
        if isinstance(node, ast.Call) and getattr(node.func, "id", None) == "Node"
        for keyword in node.keywords
        if keyword.arg == "package" and isinstance(keyword.value, ast.Constant) and keyword.value.value == package
    ]
    assert len(calls) == 1, f"{len(calls)} Node calls for {package}"
    (arguments,) = [k.value for k in calls[0].keywords if k.arg == "arguments"]
    assert isinstance(arguments, ast.List)
    return arguments.elts


def root_link(urdf: str) -> str:
    root = etree.fromstring(urdf.encode())
    children = {j.find("child").get("link") for j in root.findall("joint")}
    (name,) = [e.get("name") for e in root.findall("link") if e.get("name") not in children]
    return name


@pytest.mark.parametrize("example", ["two_dof_arm", "diff_drive", "humanoid_upper_body"])
def test_rviz_fixed_frame_follows_the_prefix_launch_argument(tmp_path, example):
    result = xacrokit.generate(REPO / "examples" / "robots" / f"{example}.yaml", tmp_path / "pkg")
    files = {f.path: f.content for f in result.files}
    name = result.robot.name
    launch = files["launch/display.launch.py"]
    compile(launch, "display.launch.py", "exec")
    root = root_link(files[f"urdf/{name}.urdf"])
    assert root == result.robot.root
    arguments = node_arguments(launch, "rviz2")
    flags = [a.value for a in arguments if isinstance(a, ast.Constant)]
    assert flags.count("-f") == 1 and "-d" in flags
    frame = arguments[[getattr(a, "value", None) for a in arguments].index("-f") + 1]
    # [LaunchConfiguration("prefix"), "ROOT"]: launch concatenates a list of substitutions into one argument
    assert isinstance(frame, ast.List) and len(frame.elts) == 2
    prefix, link = frame.elts
    assert isinstance(prefix, ast.Call) and prefix.func.id == "LaunchConfiguration"
    assert [a.value for a in prefix.args] == ["prefix"]
    assert isinstance(link, ast.Constant) and link.value == root
    declared = [
        node.args[0].value
        for node in ast.walk(ast.parse(launch))
        if isinstance(node, ast.Call) and getattr(node.func, "id", None) == "DeclareLaunchArgument"
    ]
    assert "prefix" in declared
    # without a prefix the .rviz file agrees with the launch file (it is what rviz2 -d alone shows)
    rviz = yaml.safe_load(files[f"rviz/{name}.rviz"])
    assert rviz["Visualization Manager"]["Global Options"]["Fixed Frame"] == root


@pytest.fixture(scope="module")
def diff_drive_package(tmp_path_factory):
    out = tmp_path_factory.mktemp("dd") / "diff_drive_description"
    xacrokit.generate(REPO / "examples" / "robots" / "diff_drive.yaml", out)
    return out


def test_generated_entry_arguments_choose_the_hardware_and_prefix(diff_drive_package):
    from lxml import etree

    entry = diff_drive_package / "urdf" / "diff_drive.urdf.xacro"
    paths = {"diff_drive_description": diff_drive_package}

    def expand(**args):
        return etree.fromstring(xacrokit.expand(entry, args, package_paths=paths).encode())

    mock = expand()
    assert mock.findtext("ros2_control/hardware/plugin") == "mock_components/GenericSystem"
    assert [j.get("name") for j in mock.findall("ros2_control/joint")] == ["left_wheel_joint", "right_wheel_joint"]
    assert mock.find("ros2_control/joint/command_interface").get("name") == "velocity"
    gazebo = expand(ros2_control="gazebo", prefix="r1_")
    assert gazebo.findtext("ros2_control/hardware/plugin") == "gz_ros2_control/GazeboSimSystem"
    plugin = gazebo.find("gazebo/plugin")
    assert plugin.findtext("parameters") == f"{diff_drive_package}/config/diff_drive_controllers.yaml"
    names = [e.get("name") for e in gazebo.iter("link", "joint") if e.getparent().tag == "robot"]
    names += [j.get("name") for j in gazebo.findall("ros2_control/joint")]
    names += [g.get("reference") for g in gazebo.findall("gazebo") if g.get("reference")]
    assert names and all(n.startswith("r1_") for n in names)
    assert gazebo.find("ros2_control").get("name") == "r1_diff_drive"
    assert expand(ros2_control="none").find("ros2_control") is None
    with pytest.raises(xacrokit.ExpandError, match="ros2_control must be mock, gazebo or none, got 'gz'"):
        expand(ros2_control="gz")


def test_robot_macro_mounts_on_a_parent_with_an_origin(diff_drive_package, tmp_path):
    from lxml import etree

    scene = tmp_path / "scene.urdf.xacro"
    scene.write_text(
        '<?xml version="1.0"?>\n<robot name="scene" xmlns:xacro="http://www.ros.org/wiki/xacro">\n'
        f'  <xacro:include filename="{diff_drive_package}/urdf/diff_drive_macro.xacro"/>\n'
        '  <link name="world"/>\n'
        '  <xacro:diff_drive prefix="a_" parent="world"><origin xyz="1 2 0" rpy="0 0 0.5"/></xacro:diff_drive>\n'
        '  <xacro:diff_drive prefix="b_" parent="world"><origin xyz="-1 0 0" rpy="0 0 0"/></xacro:diff_drive>\n'
        "</robot>\n",
        encoding="utf-8",
    )
    root = etree.fromstring(xacrokit.expand(scene).encode())
    mount = root.find("joint[@name='a_base_footprint_mount_joint']")
    assert mount.find("parent").get("link") == "world" and mount.find("child").get("link") == "a_base_footprint"
    assert mount.find("origin").get("xyz") == "1 2 0"
    materials = [m.get("name") for m in root.findall("material")]
    assert len(materials) == len(set(materials)) == 3  # one definition, however many instances
    links = [e.get("name") for e in root.findall("link")]
    assert len(links) == len(set(links)) == 1 + 2 * 8  # world + two robots of 8 links


@pytest.mark.parametrize("kind", ["robot", "scene", "check-report"])
def test_schema_command_prints_each_schema(kind):
    result = gen_robot("schema", "--kind", kind)
    schema = json.loads(result.stdout)
    jsonschema.Draft202012Validator.check_schema(schema)
    assert schema["$id"] == f"urn:xacrokit:schema:{kind}:v1"


PATHS = [f"{folder}{name}" for folder in ("", "x/", "x/y/", "z/") for name in ("a.txt", "b.txt")]


@settings(suppress_health_check=[HealthCheck.function_scoped_fixture])
@given(
    old=st.dictionaries(st.sampled_from(PATHS), st.sampled_from(["1", "2"]), min_size=1),
    new=st.dictionaries(st.sampled_from(PATHS), st.sampled_from(["1", "3"]), min_size=1),
    edited=st.sets(st.sampled_from(PATHS)),
    foreign=st.sets(st.sampled_from(["x/mine.txt", "z/y/mine.txt", "mine.txt"])),
)
def test_regenerating_touches_only_what_we_generated_and_nobody_edited(tmp_path_factory, old, new, edited, foreign):
    out = tmp_path_factory.mktemp("regen") / "pkg"
    write([RenderedFile(p, c) for p, c in old.items()], out)
    edited = {p for p in edited if p in old}
    for path in edited:
        (out / path).write_text("edited", encoding="utf-8")
    for path in foreign:
        (out / path).parent.mkdir(parents=True, exist_ok=True)
        (out / path).write_text("mine", encoding="utf-8")
    files = [RenderedFile(p, c) for p, c in new.items()]
    conflicts = {p for p in edited if p in new and new[p] != "edited"}
    if conflicts:
        with pytest.raises(ConflictError):
            write(files, out)
        return
    actions = {a.path: a.action for a in write(files, out)}
    on_disk = {p.relative_to(out).as_posix() for p in out.rglob("*") if p.is_file()} - {MANIFEST}
    assert {p: (out / p).read_text(encoding="utf-8") for p in new} == new  # what we generate is there
    assert all((out / p).read_text(encoding="utf-8") == "mine" for p in foreign)  # never ours: untouched
    stale = set(old) - set(new)
    assert {p for p in stale if p in edited} <= on_disk  # edited: kept
    assert not ({p for p in stale if p not in edited} & on_disk)  # ours and unedited: removed
    assert {p: a for p, a in actions.items() if p in stale} == {p: "keep" if p in edited else "remove" for p in stale}
    assert on_disk == set(new) | set(foreign) | (stale & edited)
    emptied = {str(PurePosixPath(p).parent) for p in stale - edited} - {"."}
    for folder in emptied:  # a folder our removals emptied is gone; one with anything left stays
        left = [q for q in on_disk if q.startswith(folder + "/")]
        assert (out / folder).exists() == bool(left), folder
    assert set(json.loads((out / MANIFEST).read_text(encoding="utf-8"))["files"]) == set(new)


def test_a_folder_swapped_for_a_link_while_we_write_does_not_lead_removal_outside(tmp_path, monkeypatch):
    import xacrokit.write as write_module

    out, outside = tmp_path / "pkg", tmp_path / "outside"
    write([RenderedFile("x/f.txt", "1"), RenderedFile("a.txt", "1")], out)
    outside.mkdir()
    (outside / "f.txt").write_text("1", encoding="utf-8")  # the same bytes as the stale file
    original = write_module.write_text_atomic

    def write_then_swap(path, text):
        original(path, text)
        if (out / "x").is_dir() and not (out / "x").is_symlink():
            (out / "x").rename(tmp_path / "moved")
            (out / "x").symlink_to(outside)

    monkeypatch.setattr(write_module, "write_text_atomic", write_then_swap)
    actions = {a.path: a for a in write([RenderedFile("a.txt", "2")], out)}
    assert (outside / "f.txt").read_text(encoding="utf-8") == "1"
    assert actions["x/f.txt"].action == "keep" and "symbolic link" in actions["x/f.txt"].reason


def test_a_manifest_that_is_not_utf8_is_rewritten_without_a_traceback(tmp_path):
    out = tmp_path / "pkg"
    assert gen_robot(SPEC, "-o", out).returncode == 0
    (out / MANIFEST).write_bytes(b"\xff\xfe not json")
    again = gen_robot(SPEC, "-o", out)
    assert again.returncode == 0 and "Traceback" not in again.stderr, again.stderr
    assert json.loads((out / MANIFEST).read_text(encoding="utf-8"))["files"]
