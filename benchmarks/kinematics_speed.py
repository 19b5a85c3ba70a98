"""How long `gen-robot pose`, `jacobian` and `ik` take as processes, against a bare Python script that does the same
with pinocchio (issue 45: at most 1.5 times).

For the UR10e (examples/robots/ur10e.yaml; its URDF generated once into a scratch folder by `gen-robot generate`),
each command is run as a whole process on the spec and on the URDF, and beside it a bare script (a process of its own,
the same interpreter) that reads the URDF with pinocchio and does the same work: ``pose`` forward kinematics and the
frame's pose printed; ``jacobian`` the frame's Jacobian (LOCAL_WORLD_ALIGNED) printed; ``ik`` pinocchio's own
example of closed-loop inverse kinematics (damped least squares on log6, from the neutral configuration) to the pose
that ``pose`` prints, the joint values printed. The bare script reads the URDF only: a spec's ratio includes what
generating it in memory costs.

The two of a pair run back to back, their order alternating from run to run, RUNS pairs; it prints the median wall
time of each, the median of the pairs' wall ratios, and the same for CPU time (user + system of the process and its
children, which a loaded machine disturbs less). Run ``python -m compileall -q generator`` first when the package is
installed editable with PYTHONDONTWRITEBYTECODE set (a real install compiles its modules).

Usage: python benchmarks/kinematics_speed.py [RUNS] [--no-warm-up]   (RUNS: default 9; --no-warm-up: no untimed
first pair, for a smoke run that only shows the script works)
"""

from __future__ import annotations

import os
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

REPO = Path(__file__).resolve().parent.parent
SPEC = REPO / "examples" / "robots" / "ur10e.yaml"
GEN_ROBOT = str(Path(sys.executable).with_name("gen-robot"))
FRAME = "tool0"
Q = (0.1, -1.2, 1.3, -0.4, 1.5, 0.6)
Q_TEXT = ",".join(f"{v:g}" for v in Q)

BARE_START = f"""
import sys
import numpy as np
import pinocchio as pin
model = pin.buildModelFromUrdf(sys.argv[1])
data = model.createData()
frame = model.getFrameId({FRAME!r})
"""
BARE = {
    "pose": BARE_START
    + f"""q = np.array({list(Q)})
pin.framesForwardKinematics(model, data, q)
placement = data.oMf[frame]
print(placement.translation, pin.rpy.matrixToRpy(placement.rotation))
print(placement.homogeneous)
""",
    "jacobian": BARE_START
    + f"""q = np.array({list(Q)})
print(pin.computeFrameJacobian(model, data, q, frame, pin.LOCAL_WORLD_ALIGNED))
""",
    # pinocchio's documented CLIK example, to a frame's pose (its target: the frame at Q)
    "ik": BARE_START
    + f"""pin.framesForwardKinematics(model, data, np.array({list(Q)}))
target = pin.SE3(data.oMf[frame])
q = pin.neutral(model)
for _ in range(1000):
    pin.framesForwardKinematics(model, data, q)
    error = pin.log6(data.oMf[frame].actInv(target)).vector
    if np.linalg.norm(error) < 1e-9:
        break
    J = -pin.Jlog6(target.actInv(data.oMf[frame])) @ pin.computeFrameJacobian(model, data, q, frame)
    v = -J.T @ np.linalg.solve(J @ J.T + 1e-12 * np.eye(6), error)
    q = pin.integrate(model, q, 0.1 * v)
print(q, np.linalg.norm(error))
""",
}


def target_text(urdf: Path) -> str:
    """X,Y,Z,roll,pitch,yaw of the frame at Q (what `gen-robot pose` prints), for `gen-robot ik --to`."""
    import numpy as np
    import pinocchio as pin

    model = pin.buildModelFromUrdf(str(urdf))
    data = model.createData()
    pin.framesForwardKinematics(model, data, np.array(Q))
    placement = data.oMf[model.getFrameId(FRAME)]
    values = [*placement.translation, *pin.rpy.matrixToRpy(placement.rotation)]
    return ",".join(f"{v:.12f}" for v in values)


def timed(command: list[str]) -> tuple[float, float]:
    """Wall and CPU seconds (user + system, children included) of one process."""
    before = os.times()
    start = time.perf_counter()
    done = subprocess.run(command, capture_output=True, text=True, check=False, timeout=600)
    wall = time.perf_counter() - start
    after = os.times()
    if done.returncode != 0:
        raise SystemExit(f"{' '.join(command)} failed ({done.returncode}): {done.stderr.strip()}")
    return wall, (after.children_user - before.children_user) + (after.children_system - before.children_system)


def paired(ours: list[str], bare: list[str], runs: int, warm_up: bool = True) -> dict[str, list[float]]:
    times: dict[str, list[float]] = {"ours": [], "bare": [], "ours_cpu": [], "bare_cpu": []}
    if warm_up:  # (untimed: the files in the page cache)
        timed(ours), timed(bare)
    for run in range(runs):
        order = [("ours", ours), ("bare", bare)]
        for key, command in order if run % 2 == 0 else order[::-1]:
            wall, cpu = timed(command)
            times[key].append(wall)
            times[f"{key}_cpu"].append(cpu)
    return times


def main(runs: int, warm_up: bool = True) -> None:
    with tempfile.TemporaryDirectory(prefix="xacrokit-bench-") as scratch:
        out = Path(scratch, "ur10e")
        subprocess.run([GEN_ROBOT, "generate", str(SPEC), "-o", str(out)], check=True, capture_output=True)
        urdf = next(out.glob("urdf/*.urdf"))
        scripts = {}
        for name, text in BARE.items():
            scripts[name] = Path(scratch, f"bare_{name}.py")
            scripts[name].write_text(text, encoding="utf-8")
        asked = {"pose": ["--q", Q_TEXT], "jacobian": ["--q", Q_TEXT], "ik": ["--to", target_text(urdf)]}
        print(f"gen-robot's kinematics commands against a bare pinocchio script, {runs} pairs as processes")
        print(f"{'command':<24} {'ours s':>7} {'bare s':>7} {'wall ratio':>10} {'ours cpu':>8} {'bare cpu':>8} ratio")
        for name, more in asked.items():
            bare = [sys.executable, str(scripts[name]), str(urdf)]
            for label, robot in (("spec", SPEC), ("URDF", urdf)):
                times = paired([GEN_ROBOT, name, str(robot), FRAME, *more], bare, runs, warm_up)
                wall = statistics.median(a / b for a, b in zip(times["ours"], times["bare"], strict=True))
                cpu = statistics.median(a / b for a, b in zip(times["ours_cpu"], times["bare_cpu"], strict=True))
                print(
                    f"{name + ' (' + label + ')':<24} {statistics.median(times['ours']):>7.3f} "
                    f"{statistics.median(times['bare']):>7.3f} {wall:>10.2f} "
                    f"{statistics.median(times['ours_cpu']):>8.3f} {statistics.median(times['bare_cpu']):>8.3f} "
                    f"{cpu:.2f}"
                )


if __name__ == "__main__":
    words = [w for w in sys.argv[1:] if w != "--no-warm-up"]
    main(int(words[0]) if words else 9, warm_up="--no-warm-up" not in sys.argv)
