"""``gen-robot view ROBOT --sizing FILE``: the sizing file's motion, played in the page with its torques beside it.

The motion is the one ``gen-robot size`` analyses (:func:`xacrokit.sizing.size`: waypoints time-scaled within the
limits, torques by inverse dynamics with the payloads and loads). The page gets its samples thinned to at most one
per 1/60 s (the first and last kept; the page interpolates linearly between them) and a torque plot drawn by
matplotlib (Agg) with the axes' place in the picture, so that the page can put a cursor on the time shown.
"""

from __future__ import annotations

import base64
import io
import os
from typing import TYPE_CHECKING, Any

import numpy as np

from ..errors import XacrokitError

if TYPE_CHECKING:
    from ..reader.read_robot import ReadRobot

FRAME = 1.0 / 60.0  # the page's frame: no two samples sent closer in time
MOST = 20_000  # samples at most (a 5-minute cycle at 60 per second is 18,000)


def motion_json(robot: ReadRobot, sizing: str | os.PathLike[str]) -> dict[str, Any]:
    """The motion of the sizing file, as the page reads it: joint names, times (s), positions and torques per
    sample, and the torque plot (a PNG data: URL, the plot area's edges as fractions of the picture, and the times
    at its left and right edges).

    Raises:
        XacrokitError: a sizing file without a motion (or any error ``gen-robot size`` gives for these inputs).
        SpecErrors: an invalid sizing file (located).
    """
    from ..sizing import size  # (heavy: jsonschema)

    report = size(robot, sizing=sizing)
    if report.samples is None:
        raise XacrokitError(f"{sizing}: the sizing file has no motion to play (add motion: with waypoints)")
    trajectory, torque = report.samples
    keep = thin(trajectory.t)
    names = [peak.joint for peak in report.peaks]
    picture, box, start, end = _plot(trajectory.t, torque, names)
    return {
        "joints": names,
        "t": trajectory.t[keep].tolist(),
        "q": trajectory.q[keep].tolist(),
        "torque": torque[keep].tolist(),
        "plot": {"png": picture, **box, "start": start, "end": end},
    }


def thin(times: np.ndarray) -> np.ndarray:
    """The indices of the samples to send: the first, then each one at least a frame after the last kept, and the
    last; at most ``MOST`` (the frame widened for a longer cycle)."""
    duration = float(times[-1] - times[0]) if len(times) else 0.0
    frame = max(FRAME, duration / (MOST - 2))
    kept = [0]
    for index in range(1, len(times)):
        if times[index] - times[kept[-1]] >= frame:
            kept.append(index)
    if kept[-1] != len(times) - 1:
        kept.append(len(times) - 1)
    return np.array(kept, dtype=int)


def _plot(times: np.ndarray, torque: np.ndarray, names: list[str]) -> tuple[str, dict[str, float], float, float]:
    """The torque plot as a PNG data: URL, the axes' box in fractions of the figure (left, right, bottom, top, y
    upwards) and the times at its left and right edges."""
    import matplotlib  # (heavy: matplotlib)

    matplotlib.use("Agg")
    from matplotlib.figure import Figure  # (heavy: matplotlib)

    from ..sizing.report_document import plot_label  # (heavy: jsonschema)

    figure = Figure(figsize=(2.9, 2.6), dpi=100)
    axes = figure.subplots()
    for index, name in enumerate(names):
        axes.plot(times, torque[:, index], linewidth=1.0, label=plot_label(name))
    axes.set_xlim(float(times[0]), float(times[-1]) if times[-1] > times[0] else float(times[0]) + 1.0)
    axes.set_xlabel("time (s)", fontsize=8)
    axes.set_ylabel("torque (N·m or N)", fontsize=8)
    axes.tick_params(labelsize=7)
    axes.grid(True, alpha=0.3)
    if len(names) <= 8:
        axes.legend(fontsize=6, ncol=2)
    figure.tight_layout(pad=0.3)
    buffer = io.BytesIO()
    figure.savefig(buffer, format="png", metadata={"Software": None})
    box = axes.get_position()
    start, end = axes.get_xlim()
    picture = "data:image/png;base64," + base64.b64encode(buffer.getvalue()).decode("ascii")
    edges = {"left": float(box.x0), "right": float(box.x1), "bottom": float(box.y0), "top": float(box.y1)}
    return picture, edges, float(start), float(end)
