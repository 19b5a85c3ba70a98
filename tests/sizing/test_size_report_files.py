"""gen-robot size --report DIR: the Markdown report and its PNG plots (matplotlib, Agg), the same bytes on every run,
names from a URDF escaped for Markdown and for matplotlib's mathtext."""

from __future__ import annotations

import re

import matplotlib.image
import numpy as np
import yaml
from test_size_static import planar_arm

from conftest import REPO, gen_robot

UR5 = REPO / "examples" / "robots" / "industrial_arm_std_dh.yaml"
SIZING = {
    "payloads": [{"frame": "tool0", "mass": "5 kg"}],
    "motion": {
        "scaling": "trapezoid",
        "dwell": 0.2,
        "velocity": "90 deg/s",
        "acceleration": 4.0,
        "waypoints": [{"shoulder_lift_joint": "-90 deg"}, {"shoulder_pan_joint": "90 deg"}],
    },
    "drives": {"shoulder_lift_joint": {"gear_ratio": 101, "peak_torque": "3.5 N*m", "max_speed": "3000 rpm"}},
}


def test_the_report_folder_holds_markdown_and_plots_that_are_drawn(tmp_path):
    sizing = tmp_path / "s.yaml"
    sizing.write_text(yaml.safe_dump(SIZING), encoding="utf-8")
    out = tmp_path / "report"
    result = gen_robot("size", UR5, "--sizing", sizing, "--report", out)
    assert result.returncode == 0, result.stderr
    text = (out / "size_report.md").read_text(encoding="utf-8")
    assert "![torque, speed and power over time](motion.png)" in text
    assert "| shoulder\\_lift\\_joint |" in text and "## Drives (motor side)" in text
    assert "![operating points of shoulder\\_lift\\_joint](drive_1.png)" in text
    for name, size in (("motion.png", (800, 800)), ("drive_1.png", (450, 600))):
        image = matplotlib.image.imread(out / name)
        assert image.shape[:2] == size
        assert np.std(image[..., :3]) > 0.05  # (lines drawn on it, not a blank page)
    first = {p.name: p.read_bytes() for p in out.iterdir()}
    again = gen_robot("size", UR5, "--sizing", sizing, "--report", out)
    assert again.returncode == 0 and {p.name: p.read_bytes() for p in out.iterdir()} == first


def test_names_from_a_urdf_are_escaped_in_the_report(tmp_path):
    urdf = planar_arm().replace('"shoulder"', '"sh|o*u$l$der"').replace('"elbow"', '"<b>elbow</b>"')
    path = tmp_path / "odd.urdf"
    path.write_text(urdf.replace("<b>", "&lt;b&gt;").replace("</b>", "&lt;/b&gt;"), encoding="utf-8")
    sizing = tmp_path / "s.yaml"
    motion = {"waypoints": [{"sh|o*u$l$der": 0.1}, {"sh|o*u$l$der": 0.5}], "acceleration": 1.0, "velocity": 1.0}
    sizing.write_text(yaml.safe_dump({"motion": motion, "drives": {"sh|o*u$l$der": {"gear_ratio": 50}}}))
    result = gen_robot("size", path, "--sizing", sizing, "--report", tmp_path / "r")
    assert result.returncode == 0, result.stderr
    text = (tmp_path / "r" / "size_report.md").read_text(encoding="utf-8")
    assert "sh\\|o\\*u$l$der" in text and "\\<b\\>elbow\\</b\\>" in text and "<b>" not in text
    assert (tmp_path / "r" / "drive_0.png").is_file()


def test_the_docs_picture_is_the_ur5_examples_report(tmp_path):
    """docs/images/ur5_motion.png is what examples/sizing/ur5_pick_and_place.yaml makes (pixel for pixel within a
    rendering tolerance: another matplotlib release may move a few pixels)."""
    out = tmp_path / "r"
    sizing = REPO / "examples" / "sizing" / "ur5_pick_and_place.yaml"
    assert gen_robot("size", UR5, "--sizing", sizing, "--report", out).returncode == 0
    made = matplotlib.image.imread(out / "motion.png")
    shown = matplotlib.image.imread(REPO / "docs" / "images" / "ur5_motion.png")
    assert made.shape == shown.shape and np.abs(made - shown).mean() < 0.01


def test_every_sizing_example_runs_the_command_its_header_gives():
    examples = sorted((REPO / "examples" / "sizing").glob("*.yaml"))
    assert len(examples) >= 5  # (none moved away)
    for example in examples:
        (line,) = [t for t in example.read_text(encoding="utf-8").splitlines() if "#   gen-robot size " in t]
        words = line.split("#   gen-robot ", 1)[1].split()[:4]  # size ROBOT --sizing FILE (not --report)
        result = gen_robot(*words, cwd=REPO)
        assert result.returncode == 0, (example.name, result.stdout, result.stderr)
        assert "OK: every margin >= 1" in result.stdout


def test_every_console_block_of_the_docs_is_real_output():
    """Each "$ gen-robot size ..." block of docs/size.md is what the command prints today."""
    docs = (REPO / "docs" / "size.md").read_text(encoding="utf-8")
    shown = re.findall(r"```text\n\$ (gen-robot size [^\n]+)\n(.*?)```", docs, flags=re.S)
    assert len(shown) >= 3  # (the two-link arm's, the lecture's two exercises)
    for command, output in shown:
        result = gen_robot(*command.split()[1:], cwd=REPO)
        assert result.returncode == 0 and result.stdout == output, command
