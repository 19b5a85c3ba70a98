"""gen-robot view in a real browser: Debian's chromium, headless, through selenium and chromium-driver (.ci/run
installs them as root; without them these tests are skipped). Each page opens from file:// with no network request
and no console error, its forward kinematics equal pinocchio's at random joint values (1e-9), and moving a slider
changes the picture."""

from __future__ import annotations

import json
import shutil

import numpy as np
import pinocchio as pin
import pytest

from conftest import REPO, ROBOT_EXAMPLES, SCENE_EXAMPLES, gen_robot
from xacrokit.errors import XacrokitError
from xacrokit.viewer import page, robot_json

CHROMIUM = shutil.which("chromium") or shutil.which("chromium-browser")
DRIVER = shutil.which("chromedriver")
browser_only = pytest.mark.skipif(not (CHROMIUM and DRIVER), reason="chromium and chromedriver are not installed")


@pytest.fixture(scope="module")
def browser():
    webdriver = pytest.importorskip("selenium.webdriver")
    options = webdriver.ChromeOptions()
    options.binary_location = CHROMIUM
    for flag in ("--headless=new", "--no-sandbox", "--disable-gpu", "--use-gl=swiftshader", "--window-size=900,700"):
        options.add_argument(flag)
    options.add_argument("--enable-unsafe-swiftshader")
    options.set_capability("goog:loggingPrefs", {"browser": "ALL", "performance": "ALL"})
    driver = webdriver.Chrome(service=webdriver.ChromeService(executable_path=DRIVER), options=options)
    yield driver
    driver.quit()


def open_page(browser, path):
    browser.get(path.as_uri())
    for _ in range(200):
        if browser.execute_script("return window.xacrokit && window.xacrokit.ready === true"):
            return
        browser.implicitly_wait(0.05)
    raise AssertionError(f"the page never got ready: {browser.get_log('browser')}")


def requests_made(browser) -> list[str]:
    """Every URL the page asked for, from Chrome's performance log (the page itself is the file:// one)."""
    urls = []
    for entry in browser.get_log("performance"):
        message = json.loads(entry["message"])["message"]
        if message["method"] == "Network.requestWillBeSent":
            urls.append(message["params"]["request"]["url"])
    return urls


def pinocchio_poses(urdf: str, values: dict[str, float]) -> dict[str, np.ndarray]:
    """pinocchio's link poses at ``values``, a mimic joint (a joint of its own in pinocchio's model here) set to
    multiplier x leader + offset as the URDF says."""
    from lxml import etree

    values = dict(values)
    for joint in etree.fromstring(urdf.encode("utf-8")).findall("joint"):
        mimic = joint.find("mimic")
        if mimic is not None:
            leader = values.get(mimic.get("joint"), 0.0)
            values[joint.get("name")] = float(mimic.get("multiplier", 1)) * leader + float(mimic.get("offset", 0))
    model = pin.buildModelFromXML(urdf)
    data = model.createData()
    q = pin.neutral(model)
    for name, value in values.items():
        joint = model.joints[model.getJointId(name)]
        if joint.nq == 2:
            q[joint.idx_q], q[joint.idx_q + 1] = np.cos(value), np.sin(value)
        else:
            q[joint.idx_q] = value
    pin.framesForwardKinematics(model, data, q)
    return {f.name: data.oMf[i].homogeneous for i, f in enumerate(model.frames) if f.type == pin.FrameType.BODY}


@browser_only
@pytest.mark.parametrize("example", [*ROBOT_EXAMPLES, *SCENE_EXAMPLES], ids=lambda p: p.stem)
def test_every_example_opens_offline_and_its_kinematics_are_pinocchios(browser, example, tmp_path):
    from xacrokit.check.run import input_kind, load_urdf

    html = tmp_path / f"{example.stem}.html"
    html.write_text(page(example), encoding="utf-8")
    urdf = load_urdf(example, input_kind(example), None, None, {})[0]
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


def test_names_cannot_break_out_of_the_page_and_a_missing_mesh_is_an_error(tmp_path):
    evil = "</script><script>alert(1)</script>"
    urdf = tmp_path / "evil.urdf"
    urdf.write_text(
        f'<robot name="{evil.replace("<", "&lt;")}"><link name="a&lt;/script&gt;"/></robot>', encoding="utf-8"
    )
    text = page(urdf)
    assert "</script><script>alert" not in text and text.count("</script>") == 3  # (import map, robot, module)
    assert robot_json(urdf.read_text(encoding="utf-8"), str)["links"][0]["name"] == "a</script>"
    missing = tmp_path / "m.urdf"
    missing.write_text(
        '<robot name="m"><link name="a"><visual><geometry><mesh filename="gone.stl"/></geometry></visual></link>'
        "</robot>",
        encoding="utf-8",
    )
    with pytest.raises(XacrokitError, match="'gone.stl' is not there"):
        page(missing)
    result = gen_robot("view", missing, "-o", tmp_path / "m.html")
    assert result.returncode == 2 and not (tmp_path / "m.html").exists()


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
