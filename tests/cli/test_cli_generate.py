"""gen-robot generate from the command line: the plan it prints, its exit codes, its default output folder; and
every command's help."""

from __future__ import annotations

from conftest import REPO, gen_robot

SPEC = REPO / "examples" / "robots" / "two_dof_arm.yaml"


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


def test_help_of_every_command():
    for args in (["--help"], ["generate", "--help"], ["new", "--help"], ["schema", "--help"], ["expand", "--help"]):
        result = gen_robot(*args)
        assert result.returncode == 0 and "usage: gen-robot" in result.stdout, args
    assert "gen-robot SPEC.yaml" in gen_robot("--help").stdout
