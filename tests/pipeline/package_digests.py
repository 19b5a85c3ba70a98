"""The SHA-256 of every file that every example and scene generates, as a restructure must keep them (issue 27:
"every example and scene generates the same package as before").

``python tests/pipeline/package_digests.py`` records them into ``package_digests.json`` beside this file; run it only
when a change to the generated packages is meant, and say so in the commit (the digests were first recorded at
4419d6d, before the restructure). tests/pipeline/test_package_digests.py compares a fresh generation with them.
"""

from __future__ import annotations

import hashlib
import json
import sys
import tempfile
from pathlib import Path

HERE = Path(__file__).resolve().parent
REPO = HERE.parent.parent
RECORD = HERE / "package_digests.json"
# every robot example in two macro modes (inline: plain XML; copy: calls to the copied library), every scene inline
CASES = [
    *[(f"robots/{p.name}", m) for p in sorted((REPO / "examples/robots").glob("*.yaml")) for m in ("inline", "copy")],
    *[(f"scenes/{p.name}", "inline") for p in sorted((REPO / "examples/scenes").glob("*.yaml"))],
]


# meshes gen-robot makes with trimesh (a tube's OBJ): their bytes are trimesh's writer's, which a new trimesh release
# may format otherwise; they are recorded by name only (the URDF that names them is compared byte for byte)
MADE_BY_TRIMESH = "meshes/xacrokit/"


def digests(relative: str, mode: str) -> dict[str, str]:
    """File (relative to the package root) -> SHA-256 of what ``generate`` writes for the example."""
    import xacrokit

    with tempfile.TemporaryDirectory() as scratch:
        out = Path(scratch, "pkg")
        xacrokit.generate(REPO / "examples" / relative, out, macros=mode)  # type: ignore[arg-type]
        return {
            str(p.relative_to(out)): "made by trimesh"
            if str(p.relative_to(out)).startswith(MADE_BY_TRIMESH)
            else hashlib.sha256(p.read_bytes()).hexdigest()
            for p in sorted(out.rglob("*"))
            if p.is_file()
        }


def main() -> int:
    record = {f"{relative} {mode}": digests(relative, mode) for relative, mode in CASES}
    RECORD.write_text(json.dumps(record, indent=1, sort_keys=True) + "\n", encoding="utf-8")
    print(f"{RECORD}: {len(record)} packages, {sum(map(len, record.values()))} files")
    return 0


if __name__ == "__main__":
    sys.exit(main())
