"""Every command that writes a file writes it through the write stage (xacrokit.write.outputs): a file it did not
write is kept (exit 2, unless --force), a symbolic link, FIFO or device given as -o is refused and left as it was, and
running a command again replaces its own output. The importer copies a mesh only when it is a plain file inside the
robot's folder that reads as a mesh."""

from __future__ import annotations

import contextlib
import io
import os
import stat
from pathlib import Path

import pytest

import xacrokit.cli.app
from conftest import REPO

ARM = REPO / "examples" / "robots" / "two_dof_arm.yaml"
URDF = """<robot name="r">
  <link name="base_link"><inertial><mass value="1"/><inertia ixx="0.01" iyy="0.01" izz="0.01"/></inertial></link>
  <joint name="j" type="revolute"><parent link="base_link"/><child link="arm"/><axis xyz="0 1 0"/>
    <limit lower="-1" upper="1" effort="10" velocity="1"/></joint>
  <link name="arm"><inertial><origin xyz="0.1 0 0"/><mass value="0.5"/><inertia ixx="0.001" iyy="0.001" izz="0.001"/>
  </inertial><visual><geometry><box size="0.2 0.05 0.05"/></geometry></visual></link>
</robot>
"""


def run(*argv: object) -> tuple[int, str]:
    """gen-robot in this process: (exit code, stderr)."""
    err = io.StringIO()
    with contextlib.redirect_stderr(err), contextlib.redirect_stdout(io.StringIO()):
        try:
            code = xacrokit.cli.app.main([str(word) for word in argv])
        except SystemExit as exc:
            code = exc.code if isinstance(exc.code, int) else 2
    return code, err.getvalue()


@pytest.fixture
def robot(tmp_path):
    path = tmp_path / "src" / "r.urdf"
    path.parent.mkdir()
    path.write_text(URDF, encoding="utf-8")
    return path


# command -> (the words before -o, the file name written); {robot} is the URDF
COMMANDS = {
    "expand": (["expand", "{robot}"], "out.urdf"),
    "import": (["import", "{robot}"], "out.yaml"),
    "export": (["export", "{robot}", "--mjcf"], "out.xml"),
    "view": (["view", "{robot}"], "out.html"),
    "render": (["render", "{robot}", "--size", "64x48"], "out.png"),
    "graph": (["graph", "{robot}"], "out.dot"),
    "report": (["report", str(ARM)], "out.md"),
}


def words_of(command: str, robot: Path, output: Path) -> list[str]:
    words, _ = COMMANDS[command]
    return [w.format(robot=robot) for w in words] + ["-o", str(output)]


@pytest.mark.parametrize("command", sorted(COMMANDS))
def test_a_file_the_command_did_not_write_is_kept_unless_forced(robot, tmp_path, command):
    output = tmp_path / COMMANDS[command][1]
    output.write_text("a file of the user's", encoding="utf-8")
    code, err = run(*words_of(command, robot, output))
    assert code == 2 and "it exists and was not written by gen-robot" in err and "--force" in err, err
    assert output.read_text(encoding="utf-8") == "a file of the user's"
    code, err = run(*words_of(command, robot, output), "--force")
    assert code == 0, err
    assert output.read_bytes() != b"a file of the user's"


@pytest.mark.parametrize("command", sorted(COMMANDS))
def test_running_a_command_again_replaces_its_own_output(robot, tmp_path, command):
    output = tmp_path / COMMANDS[command][1]
    assert run(*words_of(command, robot, output))[0] == 0
    first = output.read_bytes()
    robot.write_text(URDF.replace('value="0.5"', 'value="0.6"').replace("0.2 0.05", "0.3 0.05"), encoding="utf-8")
    code, err = run(*words_of(command, robot, output))
    assert code == 0, err
    if command != "report":  # (report reads the example spec, not the URDF: the same output, left alone)
        assert output.read_bytes() != first


@pytest.mark.parametrize("command", sorted(COMMANDS))
def test_a_link_a_fifo_or_a_device_as_output_is_refused_and_left_as_it_was(robot, tmp_path, command):
    target = tmp_path / "precious.txt"
    target.write_text("precious", encoding="utf-8")
    link = tmp_path / COMMANDS[command][1]
    link.symlink_to(target)
    code, err = run(*words_of(command, robot, link), "--force")
    assert code == 2 and "it is a symbolic link" in err, err
    assert link.is_symlink() and target.read_text(encoding="utf-8") == "precious"
    link.unlink()
    os.mkfifo(link)
    code, err = run(*words_of(command, robot, link), "--force")
    assert code == 2 and "device, FIFO or socket" in err, err
    assert stat.S_ISFIFO(os.lstat(link).st_mode)
    code, err = run(*words_of(command, robot, Path("/dev/full")), "--force")
    said = "-o /dev/full: write FILE.dot" if command == "graph" else "/dev/full: it is a device, FIFO or socket"
    assert code == 2 and said in err, err
    assert stat.S_ISCHR(os.lstat("/dev/full").st_mode)


def test_size_report_keeps_a_file_it_did_not_write_unless_overwrite(robot, tmp_path):
    report = tmp_path / "report"
    report.mkdir()
    (report / "size_report.md").write_text("my notes", encoding="utf-8")
    code, err = run("size", robot, "--report", report)
    assert code == 2 and "size_report.md: it exists and was not written by gen-robot" in err, err
    assert (report / "size_report.md").read_text(encoding="utf-8") == "my notes"
    code, err = run("size", robot, "--report", report, "--overwrite")
    assert code == 0, err
    assert (report / "size_report.md").read_text(encoding="utf-8").startswith("# Sizing report")


def box_stl(path: Path) -> bytes:
    import trimesh

    path.parent.mkdir(parents=True, exist_ok=True)
    trimesh.creation.box(extents=(0.1, 0.2, 0.3)).export(path)
    return path.read_bytes()


def mesh_robot(folder: Path, filename: str = "meshes/part.stl") -> Path:
    path = folder / "m.urdf"
    folder.mkdir(parents=True, exist_ok=True)
    path.write_text(
        '<robot name="m">\n<link name="base_link"><visual><geometry><mesh filename="'
        + filename
        + '"/></geometry></visual>\n<inertial><mass value="1"/><inertia ixx="0.1" iyy="0.1" izz="0.1"/></inertial>'
        "</link></robot>\n",
        encoding="utf-8",
    )
    return path


def test_import_refuses_a_mesh_that_links_out_of_the_robots_folder(tmp_path):
    urdf = mesh_robot(tmp_path / "src")
    (tmp_path / "src" / "meshes").mkdir()
    (tmp_path / "src" / "meshes" / "part.stl").symlink_to("/etc/passwd")
    code, err = run("import", urdf, "-o", tmp_path / "out" / "m.yaml")
    assert code == 2, err
    assert f"{urdf}:2: mesh 'meshes/part.stl': it is a symbolic link" in err, err
    assert not (tmp_path / "out").exists()


def test_import_refuses_a_mesh_reached_through_a_linked_folder(tmp_path):
    urdf = mesh_robot(tmp_path / "src")
    box_stl(tmp_path / "elsewhere" / "part.stl")
    (tmp_path / "src" / "meshes").symlink_to(tmp_path / "elsewhere")
    code, err = run("import", urdf, "-o", tmp_path / "out" / "m.yaml")
    assert code == 2 and "reached through a symbolic link" in err, err
    assert not (tmp_path / "out").exists()


def test_import_refuses_a_mesh_outside_the_robots_folder(tmp_path):
    box_stl(tmp_path / "part.stl")
    urdf = mesh_robot(tmp_path / "src", "../part.stl")
    code, err = run("import", urdf, "-o", tmp_path / "out" / "m.yaml")
    assert code == 2 and "it lies outside the robot's folder" in err, err
    assert not (tmp_path / "out").exists()


def test_import_refuses_a_file_that_is_not_the_mesh_its_name_says(tmp_path):
    urdf = mesh_robot(tmp_path / "src")
    (tmp_path / "src" / "meshes").mkdir()
    (tmp_path / "src" / "meshes" / "part.stl").write_text("root:x:0:0:root:/root:/bin/bash\n", encoding="utf-8")
    code, err = run("import", urdf, "-o", tmp_path / "out" / "m.yaml")
    assert code == 2 and "it does not read as a STL mesh" in err, err
    assert not (tmp_path / "out").exists()


def test_import_keeps_another_specs_mesh_and_a_hand_written_spec(tmp_path):
    urdf = mesh_robot(tmp_path / "src")
    box_stl(tmp_path / "src" / "meshes" / "part.stl")
    other = box_stl(tmp_path / "other" / "part.stl") + b"\0"  # another robot's part of that name
    (tmp_path / "out" / "meshes").mkdir(parents=True)
    (tmp_path / "out" / "meshes" / "part.stl").write_bytes(other)
    code, err = run("import", urdf, "-o", tmp_path / "out" / "m.yaml")
    assert code == 2 and "meshes/part.stl: it exists and was not written by gen-robot" in err, err
    assert (tmp_path / "out" / "meshes" / "part.stl").read_bytes() == other
    assert not (tmp_path / "out" / "m.yaml").exists()
    (tmp_path / "hand").mkdir()
    (tmp_path / "hand" / "m.yaml").write_text("robot: mine\n", encoding="utf-8")
    code, err = run("import", urdf, "-o", tmp_path / "hand" / "m.yaml")
    assert code == 2 and (tmp_path / "hand" / "m.yaml").read_text(encoding="utf-8") == "robot: mine\n"
    assert not (tmp_path / "hand" / "meshes").exists()


def test_export_keeps_a_different_mesh_beside_the_model(tmp_path):
    urdf = mesh_robot(tmp_path / "src", "meshes/part.obj")
    import trimesh

    (tmp_path / "src" / "meshes").mkdir()
    trimesh.creation.box(extents=(0.1, 0.2, 0.3)).export(tmp_path / "src" / "meshes" / "part.obj")
    (tmp_path / "out" / "meshes").mkdir(parents=True)
    (tmp_path / "out" / "meshes" / "part.obj").write_text("# another model's part\n", encoding="utf-8")
    code, err = run("export", urdf, "--mjcf", "-o", tmp_path / "out" / "m.xml")
    assert code == 2 and "part.obj: it exists and was not written by gen-robot" in err, err
    assert (tmp_path / "out" / "meshes" / "part.obj").read_text(encoding="utf-8") == "# another model's part\n"
    assert not (tmp_path / "out" / "m.xml").exists()
    code, err = run("export", urdf, "--mjcf", "-o", tmp_path / "fresh" / "m.xml")
    assert code == 0, err
    assert (tmp_path / "fresh" / "meshes").is_dir() and (tmp_path / "fresh" / "m.xml").is_file()


@pytest.mark.parametrize("marker", ["urdf folder", "package.xml"])
def test_import_copies_a_mesh_of_the_ros_layout_beside_the_urdfs_folder(tmp_path, marker):
    """The robot's folder is the package (package.xml) or, without one, the folder above urdf/: ../meshes is in it."""
    folder = tmp_path / "pkg" / ("urdf" if marker == "urdf folder" else "description")
    urdf = mesh_robot(folder, "../meshes/part.stl")
    if marker == "package.xml":
        (tmp_path / "pkg" / "package.xml").write_text("<package><name>pkg</name></package>", encoding="utf-8")
    part = box_stl(tmp_path / "pkg" / "meshes" / "part.stl")
    code, err = run("import", urdf, "-o", tmp_path / "out" / "m.yaml")
    assert code == 0, err
    assert (tmp_path / "out" / "meshes" / "part.stl").read_bytes() == part


def test_import_copies_a_sibling_robots_mesh_inside_the_python_package_that_ships_both(tmp_path):
    """A gripper of a robot-description distribution names its sibling's mesh (airo-models: ../schunk_egk40/...):
    the Python package (an __init__.py) is the robot's folder; a mesh outside it is still refused."""
    (tmp_path / "models").mkdir()
    (tmp_path / "models" / "__init__.py").write_text("", encoding="utf-8")
    part = box_stl(tmp_path / "models" / "grippers" / "finger" / "meshes" / "part.stl")
    urdf = mesh_robot(tmp_path / "models" / "grippers" / "hand", "../finger/meshes/part.stl")
    code, err = run("import", urdf, "-o", tmp_path / "out" / "m.yaml")
    assert code == 0, err
    assert (tmp_path / "out" / "meshes" / "part.stl").read_bytes() == part
    box_stl(tmp_path / "outside.stl")
    escaping = mesh_robot(tmp_path / "models" / "grippers" / "other", "../../../outside.stl")
    code, err = run("import", escaping, "-o", tmp_path / "out2" / "m.yaml")
    assert code == 2 and "it lies outside the robot's folder" in err, err


# how a robot's mesh may reach outside its folder (issue 28): each is refused by every command that reads meshes
OUTSIDE = {
    "a link out": lambda src, outside: (src / "meshes").mkdir() or (src / "meshes" / "part.stl").symlink_to(outside),
    "a linked folder": lambda src, outside: (src / "meshes").symlink_to(outside.parent),
    "a path out": lambda src, outside: (src / "m.urdf").write_text(
        (src / "m.urdf").read_text(encoding="utf-8").replace("meshes/part.stl", "../outside/part.stl")
    ),
    "a file:// URI": lambda src, outside: (src / "m.urdf").write_text(
        (src / "m.urdf").read_text(encoding="utf-8").replace("meshes/part.stl", outside.as_uri())
    ),
}


@pytest.mark.parametrize("how", sorted(OUTSIDE))
@pytest.mark.parametrize("command", ["export", "view", "render"])
def test_no_command_reads_a_mesh_from_outside_the_robots_folder(tmp_path, how, command):
    """A real box STL outside the robot's folder, reached four ways: export copies nothing of it (the visual left out
    with a note), view does not draw it (listed as not shown), render refuses; the outside file is named, not read."""
    src = tmp_path / "src"
    mesh_robot(src)
    outside = tmp_path / "outside" / "part.stl"
    secret = box_stl(outside)
    OUTSIDE[how](src, outside)
    words, name = COMMANDS[command]
    argv = [w.replace("{robot}", str(src / "m.urdf")) for w in words]
    code, err = run(*argv, "-o", tmp_path / "out" / name)
    assert ("outside the robot's folder" in err) or ("symbolic link" in err), err
    if command == "render":
        assert code == 2 and not (tmp_path / "out").exists()
        return
    assert code == 0, err
    written = [p for p in (tmp_path / "out").rglob("*") if p.is_file()]
    assert written and all(secret not in p.read_bytes() for p in written)
    assert not (tmp_path / "out" / "meshes").exists()


def test_a_mesh_over_the_size_limit_is_refused_before_it_is_read(tmp_path):
    from xacrokit.shared.mesh_solids import MAX_MESH_BYTES

    urdf = mesh_robot(tmp_path / "src")
    (tmp_path / "src" / "meshes").mkdir()
    with open(tmp_path / "src" / "meshes" / "part.stl", "wb") as handle:
        handle.truncate(MAX_MESH_BYTES + 1)  # (sparse: no disk, and it is never read)
    for command in ("import", "export"):
        words, name = COMMANDS[command]
        code, err = run(*[w.replace("{robot}", str(urdf)) for w in words], "-o", tmp_path / command / name)
        assert "larger than 33,554,432 bytes; a part's mesh is expected below 32 MiB" in err, err
        assert code == (2 if command == "import" else 0) and not (tmp_path / command / "meshes").exists()


def test_a_copied_mesh_is_streamed_and_never_written_once_it_changed(tmp_path):
    """export holds the robot's mesh as a file to stream, not its bytes; the copy equals the file; a file changed
    between the read and the write is not copied (and the model that names it is not written)."""
    from xacrokit.errors import XacrokitError
    from xacrokit.export.mjcf import export_mjcf, write_export
    from xacrokit.shared.input_files import CopiedFile

    urdf = mesh_robot(tmp_path / "src", "meshes/part.obj")
    import trimesh

    (tmp_path / "src" / "meshes").mkdir()
    trimesh.creation.box(extents=(0.1, 0.2, 0.3)).export(tmp_path / "src" / "meshes" / "part.obj")
    source = (tmp_path / "src" / "meshes" / "part.obj").read_bytes()
    model = export_mjcf(urdf)
    assert [type(v) for v in model.meshes.values()] == [CopiedFile]
    write_export(model, tmp_path / "out" / "m.xml")
    assert (tmp_path / "out" / "meshes" / "part.obj").read_bytes() == source
    changed = export_mjcf(urdf)
    (tmp_path / "src" / "meshes" / "part.obj").write_bytes(source.replace(b"0.05", b"0.07"))
    with pytest.raises(XacrokitError, match="changed after it was checked"):
        write_export(changed, tmp_path / "again" / "m.xml")
    assert not (tmp_path / "again" / "m.xml").exists()
    assert not list((tmp_path / "again").rglob("*.obj"))


def test_a_mesh_that_grows_after_its_check_is_not_copied_past_its_size(tmp_path):
    """A file appended to between the read and the streamed copy: at most one byte past the size checked is read, and
    the copy is refused (a review found the copy would run to the end of a growing file)."""
    from xacrokit.errors import XacrokitError
    from xacrokit.export.mjcf import export_mjcf, write_export

    urdf = mesh_robot(tmp_path / "src", "meshes/part.obj")
    import trimesh

    (tmp_path / "src" / "meshes").mkdir()
    part = tmp_path / "src" / "meshes" / "part.obj"
    trimesh.creation.box(extents=(0.1, 0.2, 0.3)).export(part)
    model = export_mjcf(urdf)
    with open(part, "ab") as handle:
        handle.write(b"# more" * 100_000)
    with pytest.raises(XacrokitError, match="changed after it was checked"):
        write_export(model, tmp_path / "out" / "m.xml")
    assert not (tmp_path / "out" / "m.xml").exists() and not list((tmp_path / "out").rglob("*.obj"))
