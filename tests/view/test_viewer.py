"""gen-robot view in a real browser: Debian's chromium, headless, through selenium and chromium-driver (.ci/run
installs them as root; without them these tests are skipped). Each page opens from file:// with no network request
and no console error, its forward kinematics equal pinocchio's at random joint values (1e-9), and moving a slider
changes the picture."""

from __future__ import annotations

import numpy as np
import pinocchio as pin
import pytest

from browser import browser_only, open_page, pinocchio_poses, requests_made
from conftest import REPO, ROBOT_EXAMPLES, SCENE_EXAMPLES, gen_robot
from xacrokit.reader.read_robot import read_text
from xacrokit.reader.robot_input import RobotInput
from xacrokit.reader.robot_source import read_source
from xacrokit.shared.urdf_view import read_view
from xacrokit.view.page import page, robot_json


@browser_only
@pytest.mark.parametrize("example", [*ROBOT_EXAMPLES, *SCENE_EXAMPLES], ids=lambda p: p.stem)
def test_every_example_opens_offline_and_its_kinematics_are_pinocchios(browser, example, tmp_path):
    html = tmp_path / f"{example.stem}.html"
    html.write_text(page(example), encoding="utf-8")
    urdf = read_source(RobotInput(example)).text
    open_page(browser, html)
    assert [e for e in browser.get_log("browser") if e["level"] == "SEVERE"] == []
    assert [u for u in requests_made(browser) if not u.startswith(("file://", "data:"))] == []
    joints = browser.execute_script("return window.xacrokit.joints()")
    rng = np.random.default_rng(len(joints))
    for _ in range(3):
        values = {name: float(v) for name, v in zip(joints, rng.uniform(-1.0, 1.0, len(joints)), strict=True)}
        browser.execute_script("window.xacrokit.setJoints(arguments[0])", values)
        want = pinocchio_poses(urdf, values)
        for link in browser.execute_script("return window.xacrokit.links()"):
            got = np.array(browser.execute_script("return window.xacrokit.linkPose(arguments[0])", link)).reshape(4, 4)
            if link in want:  # (pinocchio's world-fixed root is the page's identity too)
                assert np.abs(got - want[link]).max() < 1e-9, (example.stem, link)


@browser_only
def test_the_page_opens_at_home(browser, tmp_path):
    """The UR10e's home (shoulder lift and wrist 1 at -1.57, UR's start): the sliders and labels say it, the robot is
    drawn there (pinocchio's poses at home)."""
    spec = REPO / "examples" / "robots" / "ur10e.yaml"
    html = tmp_path / "ur10e.html"
    html.write_text(page(spec), encoding="utf-8")
    open_page(browser, html)
    home = {"shoulder_lift_joint": -1.57, "wrist_1_joint": -1.57}

    def shown():
        sliders = browser.find_elements("css selector", "input[data-joint]")
        return {e.get_attribute("data-joint"): float(e.get_attribute("value")) for e in sliders}

    expected = {name: home.get(name, 0.0) for name in browser.execute_script("return window.xacrokit.joints()")}
    assert shown() == expected
    label = browser.find_element("xpath", "//input[@data-joint='wrist_1_joint']/preceding-sibling::label")
    assert label.text == "wrist_1_joint = -1.570"
    want = pinocchio_poses(read_source(RobotInput(spec)).text, expected)["tool0"]
    got = np.array(browser.execute_script("return window.xacrokit.linkPose('tool0')")).reshape(4, 4)
    assert np.abs(got - want).max() < 1e-9


@browser_only
def test_moving_a_slider_changes_the_picture(browser, tmp_path):
    html = tmp_path / "ur5.html"
    html.write_text(page(REPO / "examples" / "robots" / "industrial_arm_std_dh.yaml"), encoding="utf-8")
    open_page(browser, html)
    before = browser.get_screenshot_as_png()
    browser.execute_script("window.xacrokit.setJoints({shoulder_lift_joint: -1.2, elbow_joint: 1.0})")
    after = browser.get_screenshot_as_png()
    assert before != after
    slider = browser.find_element("css selector", 'input[data-joint="shoulder_lift_joint"]')
    assert abs(float(slider.get_attribute("value")) + 1.2) < 1e-9


@browser_only
def test_the_labels_follow_set_joints(browser, tmp_path):
    """setJoints moves the sliders and their labels say the new values (they read '= 0.000' before); a value beyond a
    slider's end is said as the robot is posed, though the slider stops at its end."""
    html = tmp_path / "ur5.html"
    html.write_text(page(REPO / "examples" / "robots" / "industrial_arm_std_dh.yaml"), encoding="utf-8")
    open_page(browser, html)
    browser.execute_script("window.xacrokit.setJoints({shoulder_lift_joint: -1.2, elbow_joint: 4.0})")

    def label(joint):
        return browser.find_element("xpath", f"//input[@data-joint='{joint}']/preceding-sibling::label").text

    assert label("shoulder_lift_joint") == "shoulder_lift_joint = -1.200"
    assert label("elbow_joint") == "elbow_joint = 4.000"  # (elbow: -pi to pi)
    assert label("wrist_2_joint") == "wrist_2_joint = 0.000"
    elbow = browser.find_element("css selector", 'input[data-joint="elbow_joint"]')
    assert abs(float(elbow.get_attribute("value")) - np.pi) < 1e-6


def test_names_cannot_break_out_of_the_page(tmp_path):
    evil = "</script><script>alert(1)</script>"
    urdf = tmp_path / "evil.urdf"
    urdf.write_text(
        f'<robot name="{evil.replace("<", "&lt;")}"><link name="a&lt;/script&gt;"/></robot>', encoding="utf-8"
    )
    text = page(urdf)
    assert "</script><script>alert" not in text and text.count("</script>") == 3  # (import map, robot, module)
    assert robot_json(read_view(urdf.read_text(encoding="utf-8")), str)["links"][0]["name"] == "a</script>"


@browser_only
def test_a_missing_mesh_is_said_and_the_rest_is_drawn(browser, tmp_path):
    missing = tmp_path / "m.urdf"
    missing.write_text(
        '<robot name="m"><link name="a"><visual><geometry><mesh filename="gone.stl"/></geometry></visual>'
        '<visual><geometry><box size="0.1 0.1 0.1"/></geometry></visual></link>'
        '<link name="b"><visual><geometry><mesh filename="package://nowhere/b.stl"/></geometry></visual></link>'
        '<joint name="j" type="fixed"><parent link="a"/><child link="b"/></joint></robot>',
        encoding="utf-8",
    )
    result = gen_robot("view", missing, "-o", tmp_path / "m.html")
    assert result.returncode == 0, result.stderr
    warnings = result.stderr.splitlines()
    assert len(warnings) == 2 and "link a: mesh 'gone.stl' is not there" in warnings[0]
    assert "link b: mesh 'package://nowhere/b.stl'" in warnings[1] and "nowhere" in warnings[1]
    open_page(browser, tmp_path / "m.html")
    shown = browser.find_element("id", "missing")
    assert shown.is_displayed() and "gone.stl" in shown.text and "package://nowhere/b.stl" in shown.text
    assert browser.execute_script("return window.xacrokit.links()") == ["a", "b"]


def test_a_well_formed_robot_loads_and_other_faults_are_located(tmp_path):
    bad = tmp_path / "bad.urdf"
    bad.write_text("<robot name='x'><link name='a'></robot>", encoding="utf-8")
    result = gen_robot("view", bad, "-o", tmp_path / "bad.html")
    assert result.returncode == 2 and "bad.urdf" in result.stderr and "Traceback" not in result.stderr
    assert not (tmp_path / "bad.html").exists()
    other = tmp_path / "robot.sdf"
    other.write_text("<sdf/>", encoding="utf-8")
    result = gen_robot("view", other, "-o", tmp_path / "o.html")
    assert result.returncode == 2 and "Traceback" not in result.stderr


def test_undeclared_namespace_prefixes_are_read_past_as_consumers_do(tmp_path):
    """airo-models' UR arms carry <limit drake:acceleration=...> without declaring drake (check's U003): view,
    graph and render read the robot as every URDF consumer does."""
    urdf = tmp_path / "drake.urdf"
    urdf.write_text(
        '<robot name="d"><link name="a"><visual><geometry><box size="0.1 0.1 0.1"/></geometry></visual>'
        '<drake:thing value="1"/></link><link name="b"/><joint name="j" type="revolute"><parent link="a"/>'
        '<child link="b"/><limit lower="-1" upper="1" effort="1" velocity="1" drake:acceleration="3"/></joint></robot>',
        encoding="utf-8",
    )
    robot = robot_json(read_text(urdf.read_text(encoding="utf-8")).view, str)
    assert [j["name"] for j in robot["joints"]] == ["j"] and robot["joints"][0]["upper"] == 1.0
    for command, output in (("view", "d.html"), ("graph", "d.dot"), ("render", "d.png")):
        result = gen_robot(command, urdf, "-o", tmp_path / output)
        assert result.returncode == 0, (command, result.stderr)
    assert '"joint:j"' in (tmp_path / "d.dot").read_text(encoding="utf-8")


@browser_only
def test_toggles_change_the_picture_and_the_sweep_moves_each_joint(browser, tmp_path):
    import time

    html = tmp_path / "ur5.html"
    html.write_text(page(REPO / "examples" / "robots" / "industrial_arm_std_dh.yaml"), encoding="utf-8")
    open_page(browser, html)
    shots = [browser.get_screenshot_as_png()]
    for toggle in ("show-inertia", "show-com", "show-frames", "show-collision", "show-visual"):
        browser.find_element("id", toggle).click()
        shots.append(browser.get_screenshot_as_png())
    assert len(set(shots)) == len(shots)  # (every toggle changed what is drawn)
    still = browser.execute_script("return window.xacrokit.linkPose('tool0')")
    browser.find_element("id", "sweep").click()
    time.sleep(0.5)  # (a quarter into the first joint's sweep)
    assert browser.execute_script("return window.xacrokit.linkPose('tool0')") != still


FLOATING_PLANAR = """<robot name="fp">
  <link name="world"/>
  <joint name="free" type="floating"><parent link="world"/><child link="body"/>
    <origin xyz="0.1 -0.2 0.3" rpy="0.3 -0.2 0.5"/></joint>
  <link name="body"><inertial><mass value="1"/>
    <inertia ixx="0.1" iyy="0.1" izz="0.1" ixy="0" ixz="0" iyz="0"/></inertial>
    <visual><geometry><box size="0.2 0.1 0.05"/></geometry></visual></link>
  <joint name="slide" type="planar"><parent link="body"/><child link="puck"/>
    <origin xyz="0 0 0.1" rpy="0.1 0.2 0.3"/><axis xyz="0 0 1"/></joint>
  <link name="puck"><inertial><mass value="1"/>
    <inertia ixx="0.1" iyy="0.1" izz="0.1" ixy="0" ixz="0" iyz="0"/></inertial>
    <visual><geometry><cylinder radius="0.05" length="0.02"/></geometry></visual></link>
  <joint name="arm" type="revolute"><parent link="puck"/><child link="tip"/><origin xyz="0.2 0 0"/>
    <axis xyz="0 1 0"/><limit lower="-1" upper="1" effort="1" velocity="1"/></joint>
  <link name="tip"/>
</robot>"""


@browser_only
def test_floating_and_planar_joints_are_posed_as_pinocchio_poses_them(browser, tmp_path):
    urdf = tmp_path / "fp.urdf"
    urdf.write_text(FLOATING_PLANAR, encoding="utf-8")
    html = tmp_path / "fp.html"
    html.write_text(page(urdf), encoding="utf-8")
    open_page(browser, html)
    assert browser.execute_script("return window.xacrokit.multiJoints()") == {"free": 6, "slide": 3}
    model = pin.buildModelFromXML(FLOATING_PLANAR)
    data = model.createData()
    rng = np.random.default_rng(7)
    for _ in range(4):
        free, slide, arm = rng.uniform(-1, 1, 6), rng.uniform(-1, 1, 3), float(rng.uniform(-1, 1))
        browser.execute_script(
            "window.xacrokit.setJoints(arguments[0])", {"free": free.tolist(), "slide": slide.tolist(), "arm": arm}
        )
        quaternion = pin.Quaternion(pin.rpy.rpyToMatrix(*free[3:])).coeffs()  # (x, y, z, w)
        q = np.concatenate([free[:3], quaternion, slide[:2], [np.cos(slide[2]), np.sin(slide[2])], [arm]])
        pin.framesForwardKinematics(model, data, q)
        for link in ("body", "puck", "tip"):
            want = data.oMf[model.getFrameId(link)].homogeneous
            got = np.array(browser.execute_script("return window.xacrokit.linkPose(arguments[0])", link)).reshape(4, 4)
            assert np.abs(got - want).max() < 1e-9, link
    with pytest.raises(Exception, match="slide takes 3 numbers"):
        browser.execute_script("window.xacrokit.setJoints({slide: [1, 2]})")


@browser_only
def test_a_sizing_motion_plays_with_its_torque_plot(browser, tmp_path):
    """The two-link arm's quintic move (examples/sizing/planar_2dof_payload.yaml): from (0, 90 deg) to (90 deg, 0)
    at 1.5 rad/s and 4 rad/s^2, so T = max(15/8 (pi/2) / 1.5, sqrt(10/sqrt(3) (pi/2) / 4)) = 1.9635 s, and
    q(t) = q_a + (10u^3 - 15u^4 + 6u^5)(q_b - q_a), u = t/T: the page's positions against that closed form (linear
    interpolation between samples 1/60 s apart is within |q''| h^2 / 8 < 1e-4 of it), its link poses against
    pinocchio's at those positions, and its cursor at the time shown."""
    robot = REPO / "examples" / "robots" / "planar_2dof.yaml"
    html = tmp_path / "motion.html"
    result = gen_robot("view", robot, "--sizing", REPO / "examples" / "sizing" / "planar_2dof_payload.yaml", "-o", html)
    assert result.returncode == 0, result.stderr
    urdf = read_source(RobotInput(robot)).text
    open_page(browser, html)
    assert [e for e in browser.get_log("browser") if e["level"] == "SEVERE"] == []
    assert browser.execute_script("return document.getElementById('plot-image').naturalWidth") == 290
    duration = 15 / 8 * (np.pi / 2) / 1.5
    start, end = np.array([0.0, np.pi / 2]), np.array([np.pi / 2, 0.0])
    cursors = []
    for t in (0.0, 0.3, 0.77, 1.5, duration):
        u = t / duration
        want = start + (10 * u**3 - 15 * u**4 + 6 * u**5) * (end - start)
        got = np.array(browser.execute_script("return window.xacrokit.playAt(arguments[0])", t))
        assert np.abs(got - want).max() < 1e-4, t
        poses = pinocchio_poses(urdf, {"joint_1": got[0], "joint_2": got[1]})
        tool = np.array(browser.execute_script("return window.xacrokit.linkPose('tool_link')")).reshape(4, 4)
        assert np.abs(tool - poses["tool_link"]).max() < 1e-9
        cursors.append(browser.execute_script("return parseFloat(document.getElementById('cursor').style.left)"))
    plot = browser.execute_script("return JSON.parse(document.getElementById('robot').textContent).motion.plot")
    width = browser.execute_script("return document.getElementById('plot-image').clientWidth")
    assert abs(cursors[0] - plot["left"] * width) < 0.5 and abs(cursors[-1] - plot["right"] * width) < 0.5
    assert cursors == sorted(cursors) and plot["start"] == 0.0 and abs(plot["end"] - duration) < 1e-3
    slider = browser.find_element("css selector", 'input[data-joint="joint_1"]')
    assert abs(float(slider.get_attribute("value")) - np.pi / 2) < 1e-4  # (the sliders follow the motion)
    browser.execute_script("window.xacrokit.playAt(0)")
    before = browser.get_screenshot_as_png()
    browser.find_element("id", "play").click()
    import time

    time.sleep(0.8)
    assert browser.get_screenshot_as_png() != before


def test_a_sizing_file_without_a_motion_is_refused(tmp_path):
    still = tmp_path / "still.yaml"
    still.write_text("payloads:\n  - {frame: tool_link, mass: 1 kg}\n", encoding="utf-8")
    robot = REPO / "examples" / "robots" / "planar_2dof.yaml"
    result = gen_robot("view", robot, "--sizing", still, "-o", tmp_path / "p.html")
    assert result.returncode == 2 and "has no motion to play" in result.stderr
    assert not (tmp_path / "p.html").exists()
