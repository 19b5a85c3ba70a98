"""Sensor rules: the ``<sensor>`` of a ``<gazebo reference>`` block is one Gazebo knows (G002), with values it can
simulate (G003), and a full-turn scan does not cast its first ray twice (G004). The block's reference is R001's."""

from __future__ import annotations

import math
from collections.abc import Iterator

from .findings import Finding, rule_table
from .urdf_document import Doc

RULES = rule_table(
    {
        "G002": (
            "sensor-type",
            "warning",
            "a <sensor> has a type Gazebo (sdformat) knows: gpu_lidar, camera, depth_camera, rgbd_camera, imu, ... "
            "(Gazebo skips a sensor of a type it does not know)",
        ),
        "G003": (
            "sensor-values",
            "error",
            "a sensor's values can be simulated: update_rate >= 0; a lidar's samples >= 1, min_angle <= max_angle, "
            "a span of at most a full turn, 0 <= range min < max, resolution > 0; a camera's horizontal_fov "
            "between 0 and pi, image width and height >= 1, 0 < clip near < far",
        ),
        "G004": (
            "scan-overlap",
            "warning",
            "a lidar scan of exactly a full turn with N samples ends on the ray it starts with (two readings of one "
            "direction): end it one step short, at min_angle + 2 pi (N - 1) / N",
        ),
    }
)

# sdformat's sensor types (sdf/1.11/sensor.sdf, and the older names it still reads)
KNOWN = frozenset(
    "air_pressure air_speed altimeter boundingbox_camera camera contact custom depth depth_camera dvl "
    "force_torque gps gpu_lidar gpu_ray imu lidar logical_camera magnetometer multicamera navsat ray rfid rfidtag "
    "rgbd rgbd_camera segmentation_camera sonar thermal thermal_camera wide_angle_camera wireless_receiver "
    "wireless_transmitter".split()
)
LIDARS = ("gpu_lidar", "gpu_ray", "lidar", "ray")
CAMERAS = ("camera", "depth_camera", "depth", "rgbd_camera", "rgbd", "thermal_camera", "thermal", "wide_angle_camera")


def _value(element, path: str) -> float | None:
    text = element.findtext(path)
    if text is None:
        return None
    try:
        value = float(text)
    except ValueError:
        return math.nan
    return value


def sensor_rules(doc: Doc) -> Iterator[Finding]:
    for gazebo in doc.view.gazebo:
        for sensor in gazebo.element.findall("sensor"):  # (a sensor block is Gazebo's, not URDF's: read as written)
            name = sensor.get("name") or gazebo.reference or ""
            kind = sensor.get("type", "")
            if kind not in KNOWN:
                yield doc.finding(
                    "G002", "gazebo", name, f"<sensor type={kind!r}> is not a sensor type Gazebo knows", sensor
                )
                continue
            for problem in _problems(sensor, kind):
                yield doc.finding("G003", "gazebo", name, f"<sensor {name!r}>: {problem}", sensor)
            if kind in LIDARS:
                samples = _value(sensor, "*/scan/horizontal/samples")
                low, high = _value(sensor, "*/scan/horizontal/min_angle"), _value(sensor, "*/scan/horizontal/max_angle")
                if samples and samples > 1 and low is not None and high is not None:
                    if abs((high - low) - 2 * math.pi) < 1e-6:
                        yield doc.finding(
                            "G004",
                            "gazebo",
                            name,
                            f"<sensor {name!r}>: {samples:g} samples over exactly a full turn cast the first ray "
                            f"twice; end the scan at {low + 2 * math.pi * (samples - 1) / samples:.6g}",
                            sensor,
                        )


def _problems(sensor, kind: str) -> Iterator[str]:
    rate = _value(sensor, "update_rate")
    if rate is not None and not rate >= 0:
        yield f"update_rate {rate:g} must be >= 0"
    if kind in LIDARS:
        yield from _lidar_problems(sensor)
    if kind in CAMERAS:
        yield from _camera_problems(sensor, kind)


def _lidar_problems(sensor) -> Iterator[str]:
    """A scan's samples and angles, and its range."""
    for axis in ("horizontal", "vertical"):
        samples = _value(sensor, f"*/scan/{axis}/samples")
        low, high = _value(sensor, f"*/scan/{axis}/min_angle"), _value(sensor, f"*/scan/{axis}/max_angle")
        if samples is not None and not samples >= 1:
            yield f"{axis} samples {samples:g} must be >= 1"
        if low is not None and high is not None:
            if not low <= high:
                yield f"{axis} min_angle {low:g} is beyond max_angle {high:g}"
            elif high - low > 2 * math.pi + 1e-6:
                yield f"the {axis} scan spans {high - low:g} rad, more than a full turn"
    low, high = _value(sensor, "*/range/min"), _value(sensor, "*/range/max")
    resolution = _value(sensor, "*/range/resolution")
    if low is not None and not low >= 0:
        yield f"range min {low:g} m must be >= 0"
    if low is not None and high is not None and not high > low:
        yield f"range max {high:g} m must be beyond range min {low:g} m"
    if resolution is not None and not resolution > 0:
        yield f"range resolution {resolution:g} m must be > 0"


def _camera_problems(sensor, kind: str) -> Iterator[str]:
    """A camera's field of view, image and clip."""
    fov = _value(sensor, "camera/horizontal_fov")
    widest = 2 * math.pi if kind == "wide_angle_camera" else math.pi  # (a pinhole camera sees less than pi)
    if fov is not None and not 0 < fov < widest:
        yield f"horizontal_fov {fov:g} rad must be between 0 and {'2 pi' if widest > math.pi else 'pi'}"
    for side in ("width", "height"):
        pixels = _value(sensor, f"camera/image/{side}")
        if pixels is not None and not pixels >= 1:
            yield f"image {side} {pixels:g} must be >= 1 pixel"
    near, far = _value(sensor, "camera/clip/near"), _value(sensor, "camera/clip/far")
    if near is not None and far is not None and not 0 < near < far:
        yield f"the clip needs 0 < near < far, got {near:g} m and {far:g} m"
