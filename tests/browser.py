"""Headless chromium for the tests of gen-robot view's pages: Debian's chromium and chromium-driver driven by selenium
(.ci/run installs them as root; without them the tests that need a browser are skipped). The ``browser`` fixture
(tests/conftest.py) is one browser for the session."""

from __future__ import annotations

import json
import shutil

import numpy as np
import pinocchio as pin
import pytest

CHROMIUM = shutil.which("chromium") or shutil.which("chromium-browser")
DRIVER = shutil.which("chromedriver")
browser_only = pytest.mark.skipif(not (CHROMIUM and DRIVER), reason="chromium and chromedriver are not installed")


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


def start_browser():
    """A headless chromium (software WebGL) that keeps its console and network logs."""
    from selenium import webdriver

    options = webdriver.ChromeOptions()
    options.binary_location = CHROMIUM
    for flag in ("--headless=new", "--no-sandbox", "--disable-gpu", "--use-gl=swiftshader", "--window-size=900,700"):
        options.add_argument(flag)
    options.add_argument("--enable-unsafe-swiftshader")
    options.set_capability("goog:loggingPrefs", {"browser": "ALL", "performance": "ALL"})
    return webdriver.Chrome(service=webdriver.ChromeService(executable_path=DRIVER), options=options)
