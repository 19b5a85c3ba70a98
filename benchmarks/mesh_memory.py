"""How much memory `gen-robot import -o` and `gen-robot export --mjcf` need for a robot's meshes (issue 28, item 2),
measured in one run on this machine: a chain whose every link has its own binary STL (an icosphere of 81,920
triangles, 4 MB), with 1 and with MANY links; each command in a fresh process, its peak resident memory (the
process's, from `resource.getrusage`). The copies are streamed from the robot's files when the outputs are written
and only one mesh is read at a time, so the peak should barely grow with the number of meshes; the ratio of the
two peaks is printed with the meshes' total size (had every mesh been held, the peak would grow by about that).

Usage: python benchmarks/mesh_memory.py [MANY [SUBDIVISIONS]]   (default 16 6: the icosphere of 81,920 triangles; each
subdivision fewer has a quarter of the triangles: tests/test_benchmarks.py runs the steps with small meshes)
"""

from __future__ import annotations

import subprocess
import sys
import tempfile
from pathlib import Path

PEAK = """
import resource, sys
from xacrokit.cli.app import main
code = main(sys.argv[1:])
print(resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024, file=sys.stderr)
sys.exit(code)
"""


def mesh_chain(folder: Path, links: int, subdivisions: int) -> Path:
    """A URDF of ``links`` links in a chain, link k drawn and colliding with meshes/part_k.stl (a distinct file, an
    icosphere of 20 x 4^subdivisions triangles)."""
    import trimesh

    (folder / "meshes").mkdir(parents=True)
    sphere = trimesh.creation.icosphere(subdivisions=subdivisions, radius=0.05)
    parts = []
    for k in range(links):
        sphere.vertices = sphere.vertices * (1.0 + 1e-6)  # (each file different: no two the same)
        sphere.export(folder / "meshes" / f"part_{k}.stl")
        mesh = f'<geometry><mesh filename="meshes/part_{k}.stl"/></geometry>'
        parts.append(
            f'<link name="l{k}"><inertial><mass value="1"/><inertia ixx="0.001" iyy="0.001" izz="0.001"/>'
            f"</inertial><visual>{mesh}</visual><collision>{mesh}</collision></link>"
        )
        if k:
            parts.append(
                f'<joint name="j{k}" type="revolute"><parent link="l{k - 1}"/><child link="l{k}"/>'
                '<origin xyz="0 0 0.1"/><axis xyz="0 1 0"/><limit lower="-1" upper="1" effort="1" velocity="1"/>'
                "</joint>"
            )
    urdf = folder / "chain.urdf"
    urdf.write_text(f'<robot name="chain">{"".join(parts)}</robot>\n', encoding="utf-8")
    return urdf


def peak_mb(*argv: str) -> float:
    result = subprocess.run([sys.executable, "-c", PEAK, *argv], capture_output=True, text=True, timeout=600)
    if result.returncode != 0:
        raise SystemExit(f"gen-robot {' '.join(argv)} failed:\n{result.stderr}")
    return float(result.stderr.strip().splitlines()[-1])


def main(many: int, subdivisions: int) -> None:
    with tempfile.TemporaryDirectory() as scratch:
        for command in ("import", "export"):
            peaks = {}
            for links in (1, many):
                urdf = mesh_chain(Path(scratch, f"{command}{links}"), links, subdivisions)
                out = Path(scratch, f"out_{command}{links}", "robot.yaml" if command == "import" else "robot.xml")
                argv = ["import", str(urdf), "-o", str(out)] if command == "import" else ["export", str(urdf), "--mjcf"]
                peaks[links] = peak_mb(*(argv if command == "import" else [*argv, "-o", str(out)]))
            total = sum(p.stat().st_size for p in Path(scratch, f"{command}{many}", "meshes").iterdir()) / 2**20
            print(
                f"gen-robot {command}: peak {peaks[1]:.0f} MB with 1 mesh, {peaks[many]:.0f} MB with {many} "
                f"({total:.0f} MB of meshes): ratio {peaks[many] / peaks[1]:.2f}"
            )


if __name__ == "__main__":
    main(int(sys.argv[1]) if len(sys.argv) > 1 else 16, int(sys.argv[2]) if len(sys.argv) > 2 else 6)
