"""How fast `gen-robot size` is (issue 16, item 6), measured in one run on this machine:

- the worst-case static search of a 6-axis arm (the UR5 of the examples with 5 kg on its flange; target under 1 s),
  the search alone (scipy's and pinocchio's one-time imports are timed apart);
- the motion analysis of a 7-axis arm (example-robot-data's xArm7, else the Panda of the examples) over 10,000
  trajectory samples (inverse dynamics and the inertia moved at every sample, the per-joint figures) against the bare
  pinocchio calls it needs (rnea and crba at every sample, the configurations made beforehand): the ratio, target
  at most 3.

Usage: python benchmarks/size_speed.py [RUNS]   (median of RUNS, default 3)
"""

from __future__ import annotations

import statistics
import sys
import time
from pathlib import Path

import numpy as np

REPO = Path(__file__).resolve().parent.parent
SAMPLES = 10_000


def seven_axis() -> Path:
    for entry in sys.path:
        path = Path(entry, "cmeel.prefix", "share", "example-robot-data", "robots", "xarm_description", "urdf")
        if (path / "xarm7.urdf").is_file():
            return path / "xarm7.urdf"
    return REPO / "examples" / "robots" / "industrial_arm_mod_dh.yaml"


def median_time(job, runs: int) -> float:
    times = []
    for _ in range(runs):
        start = time.perf_counter()
        job()
        times.append(time.perf_counter() - start)
    return statistics.median(times)


def main(runs: int) -> None:
    started = time.perf_counter()
    import pinocchio as pin
    from scipy.optimize import minimize  # noqa: F401  (the search's import, timed here)

    from xacrokit.reader.read_robot import read_robot
    from xacrokit.sizing import Payload
    from xacrokit.sizing.motion import Motion, inverse_dynamics, joint_motions, trajectory
    from xacrokit.sizing.sized_robot import loaded_robot
    from xacrokit.sizing.static import static_peaks

    print(f"imports (pinocchio, scipy.optimize, xacrokit.sizing): {time.perf_counter() - started:.2f} s, once")

    spec = REPO / "examples" / "robots" / "industrial_arm_std_dh.yaml"
    ur5 = loaded_robot(read_robot(spec), payloads=[Payload("tool0", 5.0)])
    search = median_time(lambda: static_peaks(ur5), runs)
    print(f"static worst-case search, 6-axis UR5 with 5 kg: {search:.3f} s (target < 1 s)")

    path = seven_axis()
    arm = loaded_robot(read_robot(path))
    n = len(arm.joints)
    rng = np.random.default_rng(0)
    lows, highs = np.array([j.span for j in arm.joints]).T
    points = tuple(tuple(lows + (highs - lows) * rng.random(n)) for _ in range(4))
    motion = Motion(waypoints=points, velocity=(1.0,) * n, acceleration=(2.0,) * n, scaling="quintic", step=1e-3)
    samples = trajectory(motion)
    every = np.linspace(0, len(samples.t) - 1, SAMPLES).astype(int)
    cut = type(samples)(samples.t[every], samples.q[every], samples.v[every], samples.a[every])

    def analysis() -> None:
        joint_motions(arm, cut, inverse_dynamics(arm, cut))

    rows = [j.v_index for j in arm.joints]
    model, data = arm.model, arm.model.createData()
    qs = [arm.configuration(q) for q in cut.q]
    vs, accelerations = np.zeros((SAMPLES, model.nv)), np.zeros((SAMPLES, model.nv))
    vs[:, rows], accelerations[:, rows] = cut.v, cut.a

    def bare() -> None:
        for k in range(SAMPLES):
            pin.rnea(model, data, qs[k], vs[k], accelerations[k])
            pin.crba(model, data, qs[k])

    ours, reference = median_time(analysis, runs), median_time(bare, runs)
    print(
        f"motion analysis, {n}-axis {path.name}, {SAMPLES} samples: {ours:.3f} s; bare rnea + crba: {reference:.3f} s; "
        f"ratio {ours / reference:.2f} (target <= 3)"
    )


if __name__ == "__main__":
    main(int(sys.argv[1]) if len(sys.argv) > 1 else 3)
