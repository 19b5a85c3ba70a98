"""Simulated sensors on a spec's frames (``frames: NAME: sensor:``): their values resolved from the spec, the preset and
the type's defaults into a :class:`Sensor` (a record of the model, defined here beside its tables: the model imports
it); the ``<gazebo reference>`` block with Gazebo Harmonic's ``<sensor>`` (both writers: the direct emitter and the
package's gazebo.xacro get the same element, the xacro one with ``${prefix}`` in it); the camera's optical frame (REP
103: its name and pose; resolve adds its link and joint); and the ros_gz_bridge entries of ``config/NAME_bridge.yaml``.
docs/sensors.md documents every default and preset with its source.
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass
from typing import Any

from lxml import etree

from .value_text import num

GZ_TYPES = {
    "lidar": "gpu_lidar",
    "lidar_3d": "gpu_lidar",
    "camera": "camera",
    "depth_camera": "depth_camera",
    "rgbd_camera": "rgbd_camera",
    "imu": "imu",
}
CAMERAS = ("camera", "depth_camera", "rgbd_camera")
FULL_TURN = 2.0 * math.pi

# Each type's defaults (SI): a plain simulated sensor when the spec and its preset say nothing.
DEFAULTS: dict[str, dict[str, Any]] = {
    "lidar": {
        "topic": "scan",
        "update_rate": 10.0,
        "samples": 360,
        "min_angle": -math.pi,
        "max_angle": math.pi - FULL_TURN / 360,  # (a full turn without its last ray on its first)
        "range_min": 0.1,
        "range_max": 10.0,
        "range_resolution": 0.01,
    },
    "lidar_3d": {
        "topic": "lidar",  # (gpu_lidar publishes LaserScan here and the point cloud on lidar/points)
        "update_rate": 10.0,
        "samples": 1024,
        "min_angle": -math.pi,
        "max_angle": math.pi - FULL_TURN / 1024,
        "vertical_samples": 16,
        "vertical_min": -math.radians(15.0),
        "vertical_max": math.radians(15.0),
        "range_min": 0.3,
        "range_max": 100.0,
        "range_resolution": 0.01,
    },
    "camera": {"topic": "image", "update_rate": 30.0, "width": 640, "height": 480, "fov": math.radians(60.0)},
    "depth_camera": {"topic": "depth", "update_rate": 30.0, "width": 640, "height": 480, "fov": math.radians(85.0)},
    "rgbd_camera": {"topic": "rgbd", "update_rate": 30.0, "width": 640, "height": 480, "fov": math.radians(85.0)},
    "imu": {"topic": "imu", "update_rate": 100.0},
}
CLIP = {"camera": (0.05, 50.0), "depth_camera": (0.1, 10.0), "rgbd_camera": (0.1, 10.0)}

# Presets: (type, values, the frame's body when it has none: shape and mass). Sources in docs/sensors.md.
PRESETS: dict[str, tuple[str, dict[str, Any], dict[str, Any]]] = {
    "lds_02": (  # ROBOTIS LDS-02 (TurtleBot3): 360 deg at 1 deg, 0.16 to 8 m, 5 Hz, 70 x 90 x 42 mm, 131 g
        "lidar",
        {
            "update_rate": 5.0,
            "samples": 360,
            "min_angle": 0.0,
            "max_angle": FULL_TURN * 359 / 360,
            "range_min": 0.16,
            "range_max": 8.0,
            "range_resolution": 0.01,
            "noise_stddev": 0.01,  # (its +-10 mm accuracy below 300 mm, as a standard deviation)
        },
        {"shape": {"box": {"size": [0.090, 0.070, 0.042]}}, "mass": 0.131},
    ),
    "d435": (  # Intel RealSense D435-class: its D430 depth module, 85.2 x 58 deg, 1280 x 720, 0.11 to 10 m
        "rgbd_camera",
        {"update_rate": 30.0, "width": 1280, "height": 720, "fov": math.radians(85.2), "near": 0.11, "far": 10.0},
        {"shape": {"box": {"size": [0.025, 0.090, 0.025]}}, "mass": 0.072},
    ),
    "imu": (  # a generic IMU board: not one datasheet's (docs/sensors.md)
        "imu",
        {"update_rate": 200.0},
        {"shape": {"box": {"size": [0.025, 0.025, 0.005]}}, "mass": 0.01},
    ),
}

OPTICAL_RPY = (-math.pi / 2.0, 0.0, -math.pi / 2.0)  # REP 103: the optical frame's z forward, x right, y down


@dataclass(frozen=True)
class Sensor:
    """A simulated sensor at a frame, part of the model (:mod:`xacrokit.model`): every value resolved (preset, then
    defaults). ``frame`` is the link its readings are stamped with (a camera's optical frame)."""

    link: str
    kind: str  # lidar, lidar_3d, camera, depth_camera, rgbd_camera or imu
    frame: str
    topic: str
    update_rate: float
    samples: int = 0
    min_angle: float = 0.0
    max_angle: float = 0.0
    vertical_samples: int = 0
    vertical_min: float = 0.0
    vertical_max: float = 0.0
    range_min: float = 0.0
    range_max: float = 0.0
    range_resolution: float = 0.0
    width: int = 0
    height: int = 0
    fov: float = 0.0
    image_format: str = "R8G8B8"
    near: float = 0.0
    far: float = 0.0
    noise_mean: float = 0.0
    noise_stddev: float = 0.0
    accel_stddev: float = 0.0


def preset_body(data: Mapping[str, Any]) -> dict[str | int, Any]:
    """The shape and mass a frame's sensor preset gives a frame that has neither (an empty dict otherwise)."""
    sensor = data.get("sensor")
    if not isinstance(sensor, Mapping) or sensor.get("preset") not in PRESETS:
        return {}
    if any(key in data for key in ("shape", "mass", "density", "inertia")):
        return {}
    return {key: value for key, value in PRESETS[sensor["preset"]][2].items()}


def sensor_kind(data: Mapping[str, Any]) -> str:
    """A sensor's type: its own, else its preset's."""
    preset = PRESETS.get(data.get("preset", ""))
    return str(data.get("type") or (preset[0] if preset else "lidar"))


def optical_name(frame: str, data: Mapping[str, Any]) -> str:
    """A camera's optical frame: ``optical_frame``, else the frame's name without ``_link``, + ``_optical_frame``."""
    given = data.get("optical_frame")
    if given:
        return str(given)
    return f"{frame.removesuffix('_link')}_optical_frame"


def resolve_sensor(frame: str, data: Mapping[str, Any]) -> Sensor:
    """The sensor of a frame (its spec mapping, quantities already SI); a camera's readings are stamped with its
    optical frame (``Sensor.frame``), a link at OPTICAL_RPY from the frame that resolve adds."""
    preset = PRESETS.get(data.get("preset", ""))
    kind = sensor_kind(data)
    values: dict[str, Any] = dict(DEFAULTS[kind])
    if kind in CLIP:
        values["near"], values["far"] = CLIP[kind]
    if preset is not None and preset[0] == kind:
        values.update(preset[1])
    given = {
        "topic": data.get("topic"),
        "update_rate": data.get("update_rate"),
        "range_min": data.get("range", {}).get("min"),
        "range_max": data.get("range", {}).get("max"),
        "range_resolution": data.get("range", {}).get("resolution"),
        "samples": data.get("horizontal", {}).get("samples"),
        "min_angle": data.get("horizontal", {}).get("min_angle"),
        "max_angle": data.get("horizontal", {}).get("max_angle"),
        "vertical_samples": data.get("vertical", {}).get("samples"),
        "vertical_min": data.get("vertical", {}).get("min_angle"),
        "vertical_max": data.get("vertical", {}).get("max_angle"),
        "width": data.get("image", {}).get("width"),
        "height": data.get("image", {}).get("height"),
        "fov": data.get("image", {}).get("fov"),
        "image_format": data.get("image", {}).get("format"),
        "near": data.get("clip", {}).get("near"),
        "far": data.get("clip", {}).get("far"),
        "noise_mean": data.get("noise", {}).get("mean"),
        "noise_stddev": data.get("noise", {}).get("stddev"),
        "accel_stddev": data.get("noise", {}).get("accel_stddev"),
    }
    values.update({key: value for key, value in given.items() if value is not None})
    if kind == "depth_camera" and "image_format" not in values:
        values["image_format"] = "R_FLOAT32"
    stamp = optical_name(frame, data) if kind in CAMERAS else frame
    return Sensor(link=frame, kind=kind, frame=stamp, **values)


def sensor_problems(frame: str, sensor: Sensor) -> list[tuple[tuple[str, ...], str]]:
    """What makes a resolved sensor impossible: (the key path under the frame's ``sensor``, the message)."""
    found: list[tuple[tuple[str, ...], str]] = []
    if sensor.kind in ("lidar", "lidar_3d", "depth_camera", "rgbd_camera") and sensor.range_min < 0:
        found.append((("range", "min"), f"the range must start at 0 m or more, got {sensor.range_min:g} m"))
    if sensor.kind in ("lidar", "lidar_3d") and not sensor.range_max > sensor.range_min:
        found.append(
            (("range", "max"), f"range max {sensor.range_max:g} m must be beyond range min {sensor.range_min:g} m")
        )
    if sensor.kind in ("lidar", "lidar_3d") and not sensor.range_resolution > 0:
        found.append((("range", "resolution"), "the range resolution must be > 0 m"))
    if sensor.kind in ("lidar", "lidar_3d"):
        span = sensor.max_angle - sensor.min_angle
        if span < 0 or (span == 0 and sensor.samples > 1):
            found.append(
                (
                    ("horizontal", "max_angle"),
                    f"max_angle {sensor.max_angle:g} rad is below min_angle {sensor.min_angle:g}",
                )
            )
        elif span > FULL_TURN + 1e-9:
            found.append((("horizontal", "max_angle"), f"the scan spans {span:g} rad, more than a full turn (2 pi)"))
        elif span > 0 and sensor.samples == 1:
            found.append(
                (("horizontal", "samples"), "one sample cannot span an angle: give 2 or more, or equal angles")
            )
    if sensor.kind == "lidar_3d" and sensor.vertical_max < sensor.vertical_min:
        found.append((("vertical", "max_angle"), "the vertical max_angle is below its min_angle"))
    if sensor.kind in CAMERAS:
        if not 0 < sensor.fov < math.pi:
            found.append((("image", "fov"), f"the field of view must be between 0 and pi rad, got {sensor.fov:g}"))
        if not 0 < sensor.near < sensor.far:
            found.append(
                (("clip", "far"), f"the clip needs 0 < near < far, got {sensor.near:g} m and {sensor.far:g} m")
            )
    return found


def topic_namespace(prefix: str) -> str:
    """The namespace a prefix gives a sensor's topics: r1_ -> 'r1/'; none for no prefix."""
    name = prefix.rstrip("_")
    return f"{name}/" if name else ""


XACRO_NAMESPACE = "${prefix.rstrip('_') + '/' if prefix.rstrip('_') else ''}"  # topic_namespace, in xacro


def _text(parent: Any, tag: str, value: Any) -> Any:
    element = etree.SubElement(parent, tag)
    element.text = value if isinstance(value, str) else num(value)
    return element


def _noise(parent: Any, mean: float, stddev: float, *, typed: bool = False) -> None:
    noise = etree.SubElement(parent, "noise", type="gaussian") if typed else etree.SubElement(parent, "noise")
    if not typed:
        _text(noise, "type", "gaussian")
    _text(noise, "mean", mean)
    _text(noise, "stddev", stddev)


def sensor_element(sensor: Sensor, prefix: str, namespace: str) -> Any:
    """``<gazebo reference="PREFIX+link"><sensor ...>``: names glued to ``prefix``, the topic under ``namespace``."""
    gazebo = etree.Element("gazebo", reference=prefix + sensor.link)
    element = etree.SubElement(gazebo, "sensor", name=prefix + sensor.link, type=GZ_TYPES[sensor.kind])
    _text(element, "gz_frame_id", prefix + sensor.frame)
    _text(element, "topic", namespace + sensor.topic)
    _text(element, "update_rate", sensor.update_rate)
    _text(element, "always_on", "true")
    _text(element, "visualize", "false")
    if sensor.kind in ("lidar", "lidar_3d"):
        lidar = etree.SubElement(element, "lidar")
        scan = etree.SubElement(lidar, "scan")
        rows = [("horizontal", sensor.samples, sensor.min_angle, sensor.max_angle)]
        if sensor.kind == "lidar_3d":
            rows.append(("vertical", sensor.vertical_samples, sensor.vertical_min, sensor.vertical_max))
        for tag, samples, low, high in rows:
            axis = etree.SubElement(scan, tag)
            _text(axis, "samples", str(samples))
            _text(axis, "resolution", "1")
            _text(axis, "min_angle", low)
            _text(axis, "max_angle", high)
        reach = etree.SubElement(lidar, "range")
        _text(reach, "min", sensor.range_min)
        _text(reach, "max", sensor.range_max)
        _text(reach, "resolution", sensor.range_resolution)
        if sensor.noise_stddev > 0:
            _noise(lidar, sensor.noise_mean, sensor.noise_stddev)
    elif sensor.kind in CAMERAS:
        camera = etree.SubElement(element, "camera")
        _text(camera, "horizontal_fov", sensor.fov)
        image = etree.SubElement(camera, "image")
        _text(image, "width", str(sensor.width))
        _text(image, "height", str(sensor.height))
        _text(image, "format", sensor.image_format)
        clip = etree.SubElement(camera, "clip")
        _text(clip, "near", sensor.near)
        _text(clip, "far", sensor.far)
        if sensor.noise_stddev > 0:
            _noise(camera, sensor.noise_mean, sensor.noise_stddev)
        _text(camera, "optical_frame_id", prefix + sensor.frame)
    else:
        imu = etree.SubElement(element, "imu")
        for group, stddev in (("angular_velocity", sensor.noise_stddev), ("linear_acceleration", sensor.accel_stddev)):
            if stddev > 0:
                holder = etree.SubElement(imu, group)
                for axis in "xyz":
                    _noise(etree.SubElement(holder, axis), 0.0, stddev, typed=True)
    return gazebo


def bridge_entries(sensor: Sensor, namespace: str = "") -> list[dict[str, str]]:
    """The ros_gz_bridge entries of a sensor's topics (Gazebo to ROS), names under ``namespace``."""
    topic = namespace + sensor.topic
    parent = topic.rpartition("/")[0]
    info = f"{parent}/camera_info" if parent else "camera_info"
    pairs: list[tuple[str, str, str]] = []
    if sensor.kind == "lidar":
        pairs.append((topic, "sensor_msgs/msg/LaserScan", "gz.msgs.LaserScan"))
    elif sensor.kind == "lidar_3d":
        pairs.append((f"{topic}/points", "sensor_msgs/msg/PointCloud2", "gz.msgs.PointCloudPacked"))
    elif sensor.kind == "camera":
        pairs += [
            (topic, "sensor_msgs/msg/Image", "gz.msgs.Image"),
            (info, "sensor_msgs/msg/CameraInfo", "gz.msgs.CameraInfo"),
        ]
    elif sensor.kind == "depth_camera":
        pairs += [
            (topic, "sensor_msgs/msg/Image", "gz.msgs.Image"),
            (f"{topic}/points", "sensor_msgs/msg/PointCloud2", "gz.msgs.PointCloudPacked"),
            (info, "sensor_msgs/msg/CameraInfo", "gz.msgs.CameraInfo"),
        ]
    elif sensor.kind == "rgbd_camera":
        pairs += [
            (f"{topic}/image", "sensor_msgs/msg/Image", "gz.msgs.Image"),
            (f"{topic}/depth_image", "sensor_msgs/msg/Image", "gz.msgs.Image"),
            (f"{topic}/points", "sensor_msgs/msg/PointCloud2", "gz.msgs.PointCloudPacked"),
            (f"{topic}/camera_info", "sensor_msgs/msg/CameraInfo", "gz.msgs.CameraInfo"),
        ]
    else:
        pairs.append((topic, "sensor_msgs/msg/Imu", "gz.msgs.IMU"))
    return [
        {"ros_topic_name": ros, "gz_topic_name": ros, "ros_type_name": r, "gz_type_name": g, "direction": "GZ_TO_ROS"}
        for ros, r, g in pairs
    ]
