"""Joint values as vectors (issue 43, items 2 and 3): ``--at`` of several pairs, ``--q`` in the joints' order (the
order ``pose --json`` lists as ``joints``), and ``pose --configurations FILE``, a pose per row of a CSV or YAML file
on the robot read once; each answer the single ``--at`` pose's, each bad value located."""

from __future__ import annotations

import json
import math

import pinocchio
import pytest

from conftest import REPO
from xacrokit.cli.app import main
from xacrokit.reader import read_robot as read_robot_module

PLANAR = str(REPO / "examples" / "robots" / "planar_2dof.yaml")
L1, L2, HEIGHT = 0.6, 0.4, 0.06  # (the two-link arm's links and its joints' height)


def run(capsys, *words: str) -> tuple[int, str, str]:
    code = main(list(words))
    out, err = capsys.readouterr()
    return code, out, err


def tip(q1: float, q2: float) -> list[float]:
    return [L1 * math.cos(q1) + L2 * math.cos(q1 + q2), L1 * math.sin(q1) + L2 * math.sin(q1 + q2), HEIGHT]


def one_error(err: str) -> str:
    lines = err.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith("gen-robot: error: "), err
    return lines[0].removeprefix("gen-robot: error: ")


# ------------------------------------------------------------------------------------------ item 2: --at and --q
@pytest.mark.parametrize("command", ["pose", "jacobian"])
def test_one_at_takes_several_pairs_as_several_ats_do(capsys, command):
    code, out, err = run(capsys, command, PLANAR, "tool_link", "--at", "joint_1=30deg,joint_2=-0.5", "--json")
    assert code == 0, err
    code, expected, err = run(capsys, command, PLANAR, "tool_link", "--at", "joint_1=30deg", "--at", "joint_2=-0.5",
                              "--json")  # fmt: skip
    assert code == 0 and json.loads(out) == json.loads(expected)
    code, out, err = run(capsys, command, PLANAR, "tool_link", "--at", "joint_1=1,joint_2=2", "--at", "joint_1=3")
    assert (code, out) == (2, "")
    assert one_error(err) == "--at joint_1: the joint is given twice (1 and 3): give each joint once"


def test_pose_json_lists_the_joints_in_q_order_with_their_values(capsys):
    code, out, err = run(capsys, "pose", PLANAR, "tool_link", "--at", "joint_2=60deg", "--json")
    assert code == 0, err
    said = json.loads(out)
    assert said["joints"] == ["joint_1", "joint_2"]
    assert said["values"] == pytest.approx({"joint_1": 0.0, "joint_2": math.pi / 3}, abs=1e-15)


@pytest.mark.parametrize("command", ["pose", "jacobian"])
def test_q_is_every_joint_in_the_joints_order_with_units(capsys, command):
    code, out, err = run(capsys, command, PLANAR, "tool_link", "--q", "-30deg,1.2", "--json")
    assert code == 0, err
    code, expected, _ = run(capsys, command, PLANAR, "tool_link", "--at", "joint_1=-30deg,joint_2=1.2", "--json")
    assert json.loads(out) == json.loads(expected)
    if command == "pose":
        assert json.loads(out)["xyz"] == pytest.approx(tip(-math.pi / 6, 1.2), abs=1e-12)


def test_at_overrides_q_for_the_joints_it_names(capsys):
    code, out, err = run(capsys, "pose", PLANAR, "tool_link", "--q", "10deg,20deg", "--at", "joint_2=60deg", "--json")
    assert code == 0, err
    said = json.loads(out)
    assert said["values"] == pytest.approx({"joint_1": math.radians(10), "joint_2": math.radians(60)}, abs=1e-15)
    assert said["xyz"] == pytest.approx(tip(math.radians(10), math.radians(60)), abs=1e-12)


@pytest.mark.parametrize("command", ["pose", "jacobian"])
@pytest.mark.parametrize("q", ["30deg", "1,2,3", "1,,2"])
def test_q_of_another_count_says_how_many_and_which_joints(capsys, command, q):
    code, out, err = run(capsys, command, PLANAR, "tool_link", "--q", q, "--json")
    assert (code, out) == (2, "")
    if q == "1,,2":
        assert one_error(err) == "--q '1,,2': 3 values for the robot's 2 joints (joint_1, joint_2, in this order)"
    else:
        count = len(q.split(","))
        values = "1 value" if count == 1 else f"{count} values"
        assert one_error(err) == f"--q {q!r}: {values} for the robot's 2 joints (joint_1, joint_2, in this order)"


def test_a_bad_q_value_or_one_outside_the_limits_names_its_place(capsys):
    code, out, err = run(capsys, "pose", PLANAR, "tool_link", "--q", "0,1 parsec", "--json")
    assert (code, out) == (2, "") and one_error(err).startswith("--q value 2 (joint_2=1 parsec): ")
    code, out, err = run(capsys, "pose", PLANAR, "tool_link", "--q", "0,170deg", "--json")
    assert code == 0 and json.loads(out)["values"]["joint_2"] == pytest.approx(math.radians(170))
    assert err.startswith("gen-robot: warning: --q value 2 (joint_2=170deg): 2.96706 rad is outside its limits")


def test_help_says_the_order_of_q(capsys):
    with pytest.raises(SystemExit):
        main(["pose", "--help"])
    said = " ".join(capsys.readouterr().out.split())
    assert "the joints one sets (revolute, continuous and prismatic joints that mimic none) in the file's order" in said
    assert "--configurations FILE" in said


# ------------------------------------------------------------------------------- item 3: pose --configurations
ROWS = [(math.radians(30), math.radians(60)), (0.0, -0.5), (-1.0, 1.5)]
FILES = {
    "named.csv": "joint_2,joint_1\n60deg,30deg\n\n-0.5,0\n1.5,-1\n",
    "positional.csv": "30deg,60deg\n0,-0.5\n\n-1,1.5\n",
    "mappings.yaml": "- {joint_1: 30deg, joint_2: 60deg}\n- joint_1: 0\n  joint_2: -0.5\n"
    "- {joint_2: 1.5, joint_1: -1}\n",
    "lists.yml": "# a trajectory\n- [30deg, 60deg]\n- [0, -0.5]\n- ['-1 rad', 1.5]\n",
}
LINES = {"named.csv": [2, 4, 5], "positional.csv": [1, 2, 4], "mappings.yaml": [1, 2, 4], "lists.yml": [2, 3, 4]}


@pytest.mark.parametrize("name", sorted(FILES))
def test_a_pose_per_row_each_the_single_poses(capsys, tmp_path, name):
    path = tmp_path / name
    path.write_text(FILES[name], encoding="utf-8")
    code, out, err = run(capsys, "pose", PLANAR, "tool_link", "--configurations", str(path), "--json")
    assert code == 0, err
    rows = json.loads(out)
    assert [row["line"] for row in rows] == LINES[name]
    for row, (q1, q2) in zip(rows, ROWS, strict=True):
        assert row["values"] == pytest.approx({"joint_1": q1, "joint_2": q2}, abs=1e-15)
        assert row["xyz"] == pytest.approx(tip(q1, q2), abs=1e-12)
        code, single, _ = run(capsys, "pose", PLANAR, "tool_link", "--q", f"{q1!r},{q2!r}", "--json")
        assert {k: v for k, v in row.items() if k != "line"} == json.loads(single)


def test_rows_as_text_a_block_each_headed_by_its_line(capsys, tmp_path):
    path = tmp_path / "t.csv"
    path.write_text(FILES["positional.csv"], encoding="utf-8")
    code, out, err = run(capsys, "pose", PLANAR, "tool_link", "--configurations", str(path), "--point", "-1,0,0")
    assert code == 0, err
    heads = [line for line in out.splitlines() if not line.startswith(" ")]
    assert heads == [
        f"{path}:1: pose of tool_link in base_link at joint_1 = 0.523599, joint_2 = 1.0472:",
        f"{path}:2: pose of tool_link in base_link at joint_1 = 0, joint_2 = -0.5:",
        f"{path}:4: pose of tool_link in base_link at joint_1 = -1, joint_2 = 1.5:",
    ]
    xyz = [[float(v) for v in line.split()[1:4]] for line in out.splitlines() if line.startswith("  xyz")]
    assert xyz == [pytest.approx(tip(q1, q2), abs=1e-9) for q1, q2 in ROWS]
    assert sum(line.startswith("  point") for line in out.splitlines()) == 3


def test_at_overrides_every_row_and_q_with_a_file_is_refused(capsys, tmp_path):
    path = tmp_path / "t.csv"
    path.write_text(FILES["named.csv"], encoding="utf-8")
    code, out, err = run(capsys, "pose", PLANAR, "tool_link", "--configurations", str(path), "--at", "joint_1=0.25",
                         "--json")  # fmt: skip
    assert code == 0, err
    assert [row["values"]["joint_1"] for row in json.loads(out)] == [0.25] * 3
    code, out, err = run(capsys, "pose", PLANAR, "tool_link", "--configurations", str(path), "--q", "0,0")
    assert (code, out) == (2, "")
    assert one_error(err) == "--q and --configurations: the file gives every row's values; give one of them"


@pytest.mark.parametrize(
    ("name", "text", "said"),
    [
        ("a.csv", "joint_1,joint_2\n1,2\n1\n", "{f}:3: 1 value for the header's 2 columns (joint_1, joint_2)"),
        ("b.csv", "1,2\n1,2,3\n", "{f}:2: 3 values for the robot's 2 joints (joint_1, joint_2, in this order)"),
        ("c.csv", "joint_1,joint_9\n1,2\n", "{f}:1: column joint_9: no moving joint of that name (did you mean"),
        ("d.csv", "1,2\n0.5,abc\n", "{f}:2: value 2 (joint_2=abc): "),
        ("e.csv", "joint_1,joint_2\n1,\n", "{f}:2: column 2 (joint_2) is empty; give a value"),
        ("f.csv", "joint_1,joint_1\n1,2\n", "{f}:1: the header names 'joint_1' twice (columns 1 and 2)"),
        ("g.yaml", "- joint_1: 0.5\n  joint_2: 1 parsec\n", "{f}:2: joint_2=1 parsec: "),
        ("h.yaml", "- joint_1: 0.5\n  joint_2:\n", "{f}:2:11: $[0].joint_2: empty; give a number"),
        ("i.yaml", "joint_1: 1\n", "{f}:1:1: give a list of rows"),
        ("j.yml", "- [1, 2]\n- 3\n", "{f}:2:3: $[1]: a row is a mapping (name: value) or a list of values"),
        ("k.csv", "", "{f}: no rows"),
        ("l.txt", "1,2\n", "{f}: give a .csv, .yaml or .yml file"),
        ("m.yaml", "- [1, true]\n", "{f}:1:7: $[0][1]: true, not a number"),
    ],
)
def test_a_bad_row_is_located_in_its_file(capsys, tmp_path, name, text, said):
    path = tmp_path / name
    path.write_text(text, encoding="utf-8")
    code, out, err = run(capsys, "pose", PLANAR, "tool_link", "--configurations", str(path), "--json")
    assert (code, out) == (2, "")
    assert one_error(err).startswith(said.format(f=path)), err


def test_a_file_that_is_not_utf8_is_refused_at_its_byte(capsys, tmp_path):
    path = tmp_path / "t.csv"
    path.write_bytes(b"joint_1,joint_2\n1,2\n0.5,\xe9\n")
    code, out, err = run(capsys, "pose", PLANAR, "tool_link", "--configurations", str(path))
    assert (code, out) == (2, "")
    assert one_error(err) == f"{path}:3:5: not UTF-8 text (byte 0xe9); save it as UTF-8"


def test_every_row_is_posed_on_the_robot_read_once(capsys, tmp_path, monkeypatch):
    counts = {"reads": 0, "builds": 0}
    read_source, build = read_robot_module.read_source, pinocchio.buildModelFromXML

    def counted_read(*args, **kwargs):
        counts["reads"] += 1
        return read_source(*args, **kwargs)

    def counted_build(*args, **kwargs):
        counts["builds"] += 1
        return build(*args, **kwargs)

    monkeypatch.setattr(read_robot_module, "read_source", counted_read)
    monkeypatch.setattr(pinocchio, "buildModelFromXML", counted_build)
    path = tmp_path / "t.csv"
    path.write_text("".join(f"{k / 100},{-k / 100}\n" for k in range(50)), encoding="utf-8")
    code, out, err = run(capsys, "pose", PLANAR, "tool_link", "--configurations", str(path), "--json")
    assert code == 0, err
    assert len(json.loads(out)) == 50 and counts == {"reads": 1, "builds": 1}
