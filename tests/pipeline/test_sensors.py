"""Frame sensors (issue 18, item 1): the <gazebo> sensor blocks both writers make (direct emission and xacro), the
cameras' REP 103 optical frames, presets, the ros_gz_bridge file, topics namespaced by a fleet's prefixes, and bad
sensor input as located spec errors with nothing written."""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest
import yaml
from lxml import etree

from conftest import gen_robot

SPEC = (Path(__file__).parent.parent / "shared" / "sensors.yaml").read_text(encoding="utf-8")


@pytest.fixture(scope="module")
def generated(tmp_path_factory):
    folder = tmp_path_factory.mktemp("sensors")
    spec = folder / "sens.yaml"
    spec.write_text(SPEC, encoding="utf-8")
    direct = gen_robot(spec, "-o", folder / "direct")
    via = gen_robot(spec, "-o", folder / "via", "--via-xacro")
    assert direct.returncode == 0 and via.returncode == 0, (direct.stderr, via.stderr)
    assert "longer than any part" not in direct.stderr  # (a 120 m range is a sensor's, not a link's)
    return folder


def canonical(path) -> bytes:
    tree = etree.parse(str(path), etree.XMLParser(remove_blank_text=True, remove_comments=True))
    return etree.tostring(tree, method="c14n")


def sensors_of(urdf) -> dict[str, etree._Element]:
    root = etree.parse(str(urdf)).getroot()
    return {g.get("reference"): g.find("sensor") for g in root.findall("gazebo") if g.find("sensor") is not None}


def test_both_writers_make_the_same_sensor_blocks(generated):
    direct, via = generated / "direct" / "urdf" / "sens.urdf", generated / "via" / "urdf" / "sens.urdf"
    assert canonical(direct) == canonical(via)
    found = sensors_of(direct)
    assert {k: v.get("type") for k, v in found.items()} == {
        "lidar_link": "gpu_lidar",
        "camera_link": "rgbd_camera",
        "imu_link": "imu",
        "cam2_link": "camera",
        "velodyne": "gpu_lidar",
    }
    lidar = found["lidar_link"]
    assert lidar.findtext("topic") == "scan" and lidar.findtext("update_rate") == "5.0"
    assert lidar.findtext("lidar/scan/horizontal/samples") == "360"
    assert float(lidar.findtext("lidar/scan/horizontal/max_angle")) == pytest.approx(2 * math.pi * 359 / 360)
    assert (lidar.findtext("lidar/range/min"), lidar.findtext("lidar/range/max")) == ("0.16", "8.0")
    velodyne = found["velodyne"]
    assert velodyne.findtext("lidar/scan/vertical/samples") == "32"
    assert float(velodyne.findtext("lidar/scan/vertical/min_angle")) == pytest.approx(math.radians(-25))
    assert velodyne.findtext("lidar/range/max") == "120.0"
    camera = found["cam2_link"]
    assert float(camera.findtext("camera/horizontal_fov")) == pytest.approx(math.pi / 3)
    assert (camera.findtext("camera/clip/near"), camera.findtext("camera/clip/far")) == ("0.05", "20.0")
    imu = found["imu_link"]
    assert imu.findtext("imu/linear_acceleration/z/noise/stddev") == "0.02"


def test_cameras_are_stamped_in_a_rep_103_optical_frame(generated):
    """In the optical frame z points along the camera's x (forward), x along its -y (right), y along its -z (down)."""
    import yourdfpy

    urdf = generated / "direct" / "urdf" / "sens.urdf"
    found = sensors_of(urdf)
    assert found["camera_link"].findtext("gz_frame_id") == "camera_optical_frame"
    assert found["camera_link"].findtext("camera/optical_frame_id") == "camera_optical_frame"
    assert found["lidar_link"].findtext("gz_frame_id") == "lidar_link"
    robot = yourdfpy.URDF.load(str(urdf), load_meshes=False, build_scene_graph=True)
    for camera, optical in (("camera_link", "camera_optical_frame"), ("cam2_link", "cam2_optical_frame")):
        relative = np.linalg.inv(robot.get_transform(camera)) @ robot.get_transform(optical)
        assert np.allclose(relative[:3, :3], [[0, 0, 1], [-1, 0, 0], [0, -1, 0]], atol=1e-12)
        assert np.allclose(relative[:3, 3], 0)


def test_a_preset_gives_a_bare_frame_its_datasheet_body(generated):
    root = etree.parse(str(generated / "direct" / "urdf" / "sens.urdf")).getroot()
    lidar = root.find("link[@name='lidar_link']")
    assert lidar.find("visual/geometry/box").get("size") == "0.09 0.07 0.042"  # (LDS-02: 70 W x 90 D x 42 H mm)
    assert lidar.find("inertial/mass").get("value") == "0.131"
    velodyne = root.find("link[@name='velodyne']")
    assert velodyne.find("inertial/mass").get("value") == "0.8"  # (its own body: no preset)


def test_the_bridge_file_carries_the_clock_and_every_sensor_topic(generated):
    entries = yaml.safe_load((generated / "direct" / "config" / "sens_bridge.yaml").read_text(encoding="utf-8"))
    topics = {e["ros_topic_name"]: (e["ros_type_name"], e["gz_type_name"]) for e in entries}
    assert topics["clock"] == ("rosgraph_msgs/msg/Clock", "gz.msgs.Clock")
    assert topics["scan"] == ("sensor_msgs/msg/LaserScan", "gz.msgs.LaserScan")
    assert topics["imu"] == ("sensor_msgs/msg/Imu", "gz.msgs.IMU")
    assert topics["front/rgbd/points"] == ("sensor_msgs/msg/PointCloud2", "gz.msgs.PointCloudPacked")
    assert topics["lidar/points"] == ("sensor_msgs/msg/PointCloud2", "gz.msgs.PointCloudPacked")
    assert {"image", "camera_info", "front/rgbd/image", "front/rgbd/depth_image"} <= set(topics)
    assert all(e["direction"] == "GZ_TO_ROS" and e["gz_topic_name"] == e["ros_topic_name"] for e in entries)


def test_a_fleet_puts_each_robots_topics_under_its_prefix(generated, tmp_path):
    result = gen_robot("fleet", generated / "sens.yaml", "--count", "2", "-o", tmp_path / "fleet")
    assert result.returncode == 0, result.stderr
    (urdf,) = (tmp_path / "fleet" / "urdf").glob("*.urdf")
    found = sensors_of(urdf)
    assert found["r1_lidar_link"].findtext("topic") == "r1/scan"
    assert found["r0_camera_link"].findtext("gz_frame_id") == "r0_camera_optical_frame"
    assert found["r0_camera_link"].findtext("topic") == "r0/front/rgbd"


@pytest.mark.parametrize(
    ("sensor", "where", "message"),
    [
        ("{type: sonar}", "sensor.type", "sonar"),
        ("{type: lidar, horizontal: {samples: 0}}", "sensor.horizontal.samples", "0"),
        ("{type: lidar, range: {min: -0.1}}", "sensor.range.min", "0 m or more"),
        ("{type: lidar, range: {min: 2, max: 1}}", "sensor.range.max", "beyond range min"),
        ("{type: lidar, range: {resolution: 0}}", "sensor.range.resolution", "> 0 m"),
        ("{type: lidar, horizontal: {min_angle: -200 deg, max_angle: 200 deg}}", "horizontal.max_angle", "full turn"),
        ("{type: camera, image: {fov: 190 deg}}", "sensor.image.fov", "between 0 and pi"),
        ("{type: camera, clip: {near: 2, far: 1}}", "sensor.clip.far", "near < far"),
        ("{type: lidar, update_rate: 0}", "sensor.update_rate", "0"),
        ("{type: imu, noise: {stddev: -1}}", "sensor.noise.stddev", "-1"),
        ("{type: lidar, preset: d435}", "sensor.preset", "is a rgbd_camera, not a lidar"),
    ],
)
def test_bad_sensor_input_is_a_located_spec_error_and_nothing_is_written(tmp_path, sensor, where, message):
    spec = tmp_path / "bad.yaml"
    spec.write_text(
        f"robot: bad\nlinks:\n  base_link: {{}}\nframes:\n  s_link:\n    parent: base_link\n    sensor: {sensor}\n",
        encoding="utf-8",
    )
    result = gen_robot(spec, "-o", tmp_path / "out")
    assert result.returncode == 2 and "Traceback" not in result.stderr
    assert "bad.yaml:7:" in result.stderr and where in result.stderr and message in result.stderr, result.stderr
    assert not (tmp_path / "out").exists()
