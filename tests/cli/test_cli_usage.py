"""The gen-robot command line: how it reads its words, and what it says when they are wrong."""

from __future__ import annotations

from lxml import etree

from conftest import REPO, gen_robot, snapshot

SPEC = REPO / "examples" / "robots" / "two_dof_arm.yaml"


def test_a_dry_run_shows_the_whole_plan_with_its_conflicts(tmp_path):
    out = tmp_path / "pkg"
    assert gen_robot(SPEC, "-o", out).returncode == 0
    with (out / "README.md").open("a", encoding="utf-8") as readme:
        readme.write("my notes\n")
    before = snapshot(out)
    dry = gen_robot(SPEC, "-o", out, "--dry-run")
    assert dry.returncode == 1, dry.stderr
    plan = dict(line.split(None, 1)[::-1] for line in dry.stdout.splitlines() if line.startswith(("identical", "con")))
    assert plan["README.md  (edited since it was generated)"] == "conflict"
    assert plan["urdf/two_dof_arm.urdf"] == "identical"  # every other file is listed too
    assert "a run would write nothing" in dry.stderr and "--force" in dry.stderr
    assert snapshot(out) == before
    real = gen_robot(SPEC, "-o", out)  # the real run refuses, as the dry run said
    assert real.returncode == 1 and "nothing was written" in real.stderr and snapshot(out) == before


def test_options_may_come_before_the_spec(tmp_path):
    result = gen_robot("--dry-run", SPEC, "-o", tmp_path / "pkg")
    assert result.returncode == 0, result.stderr
    assert "dry run: nothing written" in result.stdout and not (tmp_path / "pkg").exists()
    assert gen_robot("-o", tmp_path / "pkg", SPEC).returncode == 0
    assert (tmp_path / "pkg" / "urdf" / "two_dof_arm.urdf").is_file()


def test_a_mistyped_command_is_named_with_a_suggestion(tmp_path):
    for typo, meant in (("chek", "check"), ("generat", "generate"), ("flet", "fleet")):
        result = gen_robot(typo, tmp_path / "robot.urdf")
        assert result.returncode == 2
        assert f"{typo!r} is neither a command nor a spec file; did you mean {meant!r}?" in result.stderr
    missing = gen_robot(tmp_path / "missing.yaml")  # a spec's name: the missing file is what is reported
    assert missing.returncode == 2
    assert (
        missing.stderr.strip()
        == f"gen-robot: error: {tmp_path / 'missing.yaml'}: cannot read the spec: No such file or directory"
    )


def test_fleet_spacing_takes_units_and_count_must_be_positive(tmp_path):
    metres = gen_robot("fleet", SPEC, "--count", 2, "--spacing", "1.5", "-o", tmp_path / "m")
    centimetres = gen_robot("fleet", SPEC, "--count", 2, "--spacing", "150 cm", "-o", tmp_path / "cm")
    assert metres.returncode == centimetres.returncode == 0, centimetres.stderr
    urdfs = [(tmp_path / d / "urdf" / "two_dof_arm_fleet.urdf").read_bytes() for d in ("m", "cm")]
    assert urdfs[0] == urdfs[1]
    joints = {j.get("name"): j for j in etree.fromstring(urdfs[0]).iter("joint")}
    assert joints["r1_base_link_mount_joint"].find("origin").get("xyz").split()[0] == "1.5"
    for words, message in (
        (("--count", 0), "argument --count: must be 1 to 1,000, got 0"),
        (("--count", 10**7), "argument --count: must be 1 to 1,000, got 10,000,000 (the limit: every copy"),
        (("--count", "²"), "argument --count: expected a whole number (digits 0-9), got '²'"),
        (("--count", 2, "--grid", "²x²"), "--grid expects ROWSxCOLUMNS such as 2x5, got '²x²'"),
        (("--count", 2, "--spacing", "(" * 300 + "1" + ")" * 300), "argument --spacing: a quantity written with 601"),
        (("--count", 2, "--spacing", "15 deg"), "argument --spacing: '15 deg' is an angle, expected a length"),
        (("--count", 2, "--spacing", "-1"), "argument --spacing: must be > 0 m"),
    ):
        result = gen_robot("fleet", SPEC, *words, "-o", tmp_path / "x")
        assert result.returncode == 2 and message in result.stderr, result.stderr
    assert not (tmp_path / "x").exists()


def test_new_writes_into_a_folder_and_makes_missing_ones(tmp_path):
    (tmp_path / "specs").mkdir()
    into = gen_robot("new", "foo", "-o", tmp_path / "specs")
    assert into.returncode == 0 and (tmp_path / "specs" / "foo.yaml").is_file()
    deep = gen_robot("new", "bar", "--kind", "mobile", "-o", tmp_path / "a" / "b" / "bar.yaml")
    assert deep.returncode == 0 and (tmp_path / "a" / "b" / "bar.yaml").is_file()
    again = gen_robot("new", "foo", "-o", tmp_path / "specs")  # never overwritten
    assert again.returncode == 2 and "not overwritten" in again.stderr
    assert "(default: arm)" in gen_robot("new", "--help").stdout


def test_a_tab_in_the_indentation_is_named(tmp_path):
    spec = tmp_path / "tab.yaml"
    spec.write_text("robot: r\nlinks:\n\tbase_link: {}\n", encoding="utf-8")
    result = gen_robot(spec)
    assert result.returncode == 2
    assert f"{spec}:3:1: not valid YAML:" in result.stderr and "a tab: YAML indents with spaces only" in result.stderr


def test_new_takes_a_folder_by_its_slash_and_checks_the_name_first(tmp_path):
    result = gen_robot("new", "bot", "-o", f"{tmp_path / 'specs'}/")
    assert result.returncode == 0 and (tmp_path / "specs" / "bot.yaml").is_file()
    bad = gen_robot("new", "1bad", "-o", tmp_path / "deep" / "er" / "x.yaml")
    assert bad.returncode == 2 and "must be letters, digits and _" in bad.stderr
    assert not (tmp_path / "deep").exists()  # nothing made for a name that is refused
    (tmp_path / "afile").write_text("")
    blocked = gen_robot("new", "x", "-o", tmp_path / "afile" / "x.yaml")
    assert blocked.returncode == 2 and "cannot make the folder" in blocked.stderr


def test_options_without_a_spec_say_so():
    result = gen_robot("--dry-run")
    assert result.returncode == 2 and "no spec given for --dry-run" in result.stderr


def test_exit_codes_are_said_one_way_in_the_help_the_module_and_the_docs():
    import re

    import xacrokit.cli.app

    helped = " ".join(gen_robot("--help").stdout.split())
    assert xacrokit.cli.app.EXIT_CODES in helped
    codes = set(re.findall(r"\b(\d+) [a-z]", xacrokit.cli.app.EXIT_CODES))
    assert codes == {"0", "1", "2", "70", "130", "141"}
    docstring = " ".join((xacrokit.cli.app.__doc__ or "").split())
    documented = " ".join((REPO / "docs" / "safe-writing.md").read_text(encoding="utf-8").split())
    for code in codes:
        assert re.search(rf"\b{code} [a-z]", docstring), code
        assert re.search(rf"\b{code}\b", documented), code


def test_usage_mistakes_get_a_suggestion_and_name_only_what_is_missing():
    missing = gen_robot("check")
    assert missing.returncode == 2 and "the following arguments are required: PATH\n" in missing.stderr
    typo = gen_robot(SPEC, "--dryrun")
    assert typo.returncode == 2 and "unrecognized arguments: --dryrun; did you mean --dry-run?" in typo.stderr
    typo = gen_robot("check", SPEC, "--jsn")
    assert typo.returncode == 2 and "did you mean --json?" in typo.stderr
