"""``gen-robot size ... --report DIR``: the sizing report as Markdown with PNG plots (matplotlib's Agg backend: no
display, the same picture on every machine): torque, speed and power over the motion's time, and each drive's
operating points against its motor's torque and speed limits.

Files: ``DIR/size_report.md``, ``DIR/motion.png`` (with a motion), ``DIR/drive_K.png`` (K: the joint's index, not
its name, which comes from a URDF and may not make a file name); written atomically. Names in the Markdown are
escaped for it (``text.markdown_text``).
"""

from __future__ import annotations

import io
from pathlib import Path
from typing import Any

import numpy as np

from ..shared.value_text import markdown_text
from ..write.outputs import OutputFile, write_outputs
from .size_results import SizeReport, ratio


def write_report(report: SizeReport, folder: str | Path, *, force: bool = False) -> list[Path]:
    """Write the report's Markdown and plots into ``folder`` (made if missing) through the write stage
    (:func:`~xacrokit.write.outputs.write_outputs`: a file there that gen-robot did not write is kept, and nothing is
    written, unless ``force``); the paths written."""
    root = Path(folder)
    files: list[OutputFile] = []
    pictures: dict[str, str] = {}
    if report.samples is not None:
        pictures["motion"] = "motion.png"
        files.append(OutputFile("motion.png", _png(_motion_figure(report))))
        for index, joint in enumerate(report.peaks):
            if joint.joint in report.drives:
                name = f"drive_{index}.png"
                pictures[joint.joint] = name
                files.append(OutputFile(name, _png(_drive_figure(report, index))))
    files.insert(0, OutputFile("size_report.md", markdown(report, pictures)))
    write_outputs(root, files, force=force)
    return [root / item.relative for item in files]


def markdown(report: SizeReport, pictures: dict[str, str]) -> str:
    """The Markdown of the report, with the plots ``pictures`` names ('motion' and drive joints -> file)."""
    lines = [
        f"# Sizing report: {markdown_text(report.robot)}",
        "",
        f"Input `{markdown_text(report.path)}`. A peak torque is what the motor must produce, by magnitude (N·m; N "
        "for prismatic joints; the JSON keeps its sign); "
        f"gravity {report.gravity:g} m/s² along −z; the motion's torques "
        + ("include" if report.joint_friction else "leave out")
        + " the joints' damping and friction; margin = limit / need (below 1 fails).",
        "",
    ]
    for held in report.payloads:
        lines.append(f"- payload {held.mass:g} kg on {markdown_text(held.frame)}, centre of mass {list(held.com)} m")
    for load in report.loads:
        lines.append(
            f"- load on {markdown_text(load.frame)}: force {list(load.force)} N, moment {list(load.moment)} N·m"
        )
    lines += ["", "## Static worst case", "", "| joint | peak torque | of it loads | effort limit | margin |"]
    lines.append("|---|---|---|---|---|")
    for peak in report.peaks:
        lines.append(
            f"| {markdown_text(peak.joint)} | {peak.need:.4g} | {peak.loads_need:.4g} | "
            f"{_num(report.efforts.get(peak.joint))} | {_num(report.margin(peak))} |"
        )
    if report.motions is not None:
        lines += ["", "## Along the motion", ""]
        if "motion" in pictures:
            lines += [f"![torque, speed and power over time]({pictures['motion']})", ""]
        lines.append("| joint | peak torque | RMS torque | peak speed | peak power | regenerative | energy (J) |")
        lines.append("|---|---|---|---|---|---|---|")
        for m in report.motions:
            lines.append(
                f"| {markdown_text(m.joint)} | {abs(m.peak_torque):.4g} | {m.rms_torque:.4g} | {m.peak_speed:.4g} | "
                f"{m.peak_power:.4g} | {m.peak_regenerative_power:.4g} | {m.energy:.4g} |"
            )
    if report.drives:
        lines += ["", "## Drives (motor side)", ""]
        for joint in report.drives:
            side = report.drive_side(joint)
            if side is None:
                continue
            lines.append(
                f"- {markdown_text(joint)}: ratio {side['gear_ratio']:g}, efficiency {side['efficiency']:g}; motor "
                f"peak torque {side['motor_peak_torque']:.4g} N·m, RMS {side['motor_rms_torque']:.4g} N·m, peak speed "
                f"{side['motor_peak_speed']:.4g} rad/s, inertia ratio {_num(side['inertia_ratio'])}"
            )
            if joint in pictures:
                lines += ["", f"![operating points of {markdown_text(joint)}]({pictures[joint]})", ""]
    lines += ["", "## Verdict", ""]
    if report.failures:
        lines += [f"- FAIL {markdown_text(joint)}: {what}" for joint, what in report.failures]
    else:
        lines.append("Every margin is at least 1.")
    return "\n".join(lines) + "\n"


def _num(value: float | None) -> str:
    return "-" if value is None else f"{value:.4g}"


def _figure() -> Any:
    import matplotlib  # (heavy: matplotlib)

    matplotlib.use("Agg")
    from matplotlib.figure import Figure  # (heavy: matplotlib)

    return Figure


def _motion_figure(report: SizeReport) -> Any:
    path, torque = report.samples  # type: ignore[misc]
    figure = _figure()(figsize=(8, 8), dpi=100)
    axes = figure.subplots(3, 1, sharex=True)
    for index, joint in enumerate(report.peaks):
        axes[0].plot(path.t, torque[:, index], label=plot_label(joint.joint))
        axes[1].plot(path.t, path.v[:, index])
        axes[2].plot(path.t, torque[:, index] * path.v[:, index])
    axes[0].set_ylabel("torque (N·m)")
    axes[1].set_ylabel("speed (rad/s)")
    axes[2].set_ylabel("power (W)")
    axes[2].set_xlabel("time (s)")
    axes[0].legend(fontsize="small", ncol=2)
    for ax in axes:
        ax.grid(True, alpha=0.3)
    figure.tight_layout()
    return figure


def _drive_figure(report: SizeReport, index: int) -> Any:
    path, torque = report.samples  # type: ignore[misc]
    joint = report.peaks[index].joint
    drive = report.drives[joint]
    scale = drive.gear_ratio * drive.efficiency
    speed = np.abs(path.v[:, index]) * drive.gear_ratio
    motor = np.abs(torque[:, index]) / scale
    figure = _figure()(figsize=(6, 4.5), dpi=100)
    ax = figure.subplots()
    ax.plot(speed, motor, ".", markersize=2, label="operating points")
    if drive.peak_torque is not None:
        ax.axhline(drive.peak_torque, color="tab:red", label="motor peak torque")
    if drive.rated_torque is not None:
        ax.axhline(drive.rated_torque, color="tab:orange", linestyle="--", label="motor rated torque")
    if drive.max_speed is not None:
        ax.axvline(drive.max_speed, color="tab:purple", label="motor maximum speed")
    ax.set_xlabel("motor speed (rad/s)")
    ax.set_ylabel("motor torque (N·m)")
    ax.set_title(f"{plot_label(joint)}: margin {_num(ratio(drive.peak_torque, float(motor.max()) or 0.0))}")
    ax.grid(True, alpha=0.3)
    ax.legend(fontsize="small")
    figure.tight_layout()
    return figure


def plot_label(name: str) -> str:
    """A name shown as it is in a plot: matplotlib reads text between two ``$`` as mathematics."""
    return name.replace("$", r"\$")


def _png(figure: Any) -> bytes:
    """The figure as PNG, without the metadata that would change between runs (matplotlib's version)."""
    buffer = io.BytesIO()
    figure.savefig(buffer, format="png", metadata={"Software": None})
    return buffer.getvalue()
