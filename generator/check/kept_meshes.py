"""What the geometry rules take from a mesh file, kept across runs: its convex hull's vertices and its triangle count,
and the uniform solid it encloses at a scale (for a finding's message).

Reading a mesh and taking its hull is most of what ``gen-robot check`` spends on a robot of meshes (TIAGo dual's 124
mesh files, the G1's 87: a second and more; the consumers read no mesh, or fewer), and the same files are checked again
and again (CI, an edit of the URDF around unchanged meshes). So the facts of each file are kept in the user's cache
folder (:mod:`xacrokit.shared.user_cache`: private to the user, ``XACROKIT_CACHE=off`` turns it off), in
``meshes-VERSION``, one small JSON file a mesh named by the SHA-256 of FORMAT, the file's suffix (which says the reader)
and the SHA-256 of its bytes (which the reader of a robot's meshes has taken already): a file whose bytes change is a
new name, and its facts are worked out afresh. The vertices are kept as their float32 bytes, so a kept hull is the same
array, bit for bit, as the one worked out. A kept file that does not read back whole is worked out again and written
anew.
"""

from __future__ import annotations

import base64
import hashlib
import json
from collections.abc import Callable
from typing import TYPE_CHECKING

from .. import __version__
from ..shared.user_cache import cache_folder, kept, read_cached, source_stamp

if TYPE_CHECKING:
    import numpy as np

FORMAT = 2  # (raise it when what is kept, or how it is worked out, changes: the old files are then never read)
Facts = tuple["np.ndarray", int]  # a mesh's hull vertices (float32, N x 3) and its triangle count


def kept_facts(data: bytes, suffix: str, work_out: Callable[[], Facts], digest: bytes | None = None) -> Facts:
    """The facts of the mesh file whose bytes are ``data`` (of kind ``suffix``; ``digest``: their SHA-256, when
    known): kept ones, else ``work_out()``'s, then kept. What ``work_out`` raises (a file that is no mesh) is raised,
    and nothing is kept."""
    return kept("meshes", __version__, _facts_name(data, suffix, digest), work_out, _written, _read)


def facts_kept(data: bytes, suffix: str, digest: bytes | None = None) -> bool:
    """Whether :func:`kept_facts` would find the facts of this mesh file kept (read back whole)."""
    folder = cache_folder("meshes", __version__)
    text = None if folder is None else read_cached(folder, _facts_name(data, suffix, digest))
    if text is None:
        return False
    try:
        _read(text)
    except ValueError:
        return False
    return True


def _facts_name(data: bytes, suffix: str, digest: bytes | None = None) -> str:
    return _name(f"{FORMAT}:{_code()}:{suffix}:", data, digest)


def _name(what: str, data: bytes, digest: bytes | None) -> str:
    """A kept file's name: the SHA-256 of ``what`` and of the file's bytes' SHA-256 (``digest``, when known)."""
    return hashlib.sha256(what.encode() + (digest or hashlib.sha256(data).digest())).hexdigest() + ".json"


def _code() -> str:
    """The code that works the facts out: trimesh's install and our modules that call it (an edit of them, in an
    editable install, works the facts out afresh)."""
    return source_stamp("trimesh", "xacrokit.check.inertia_geometry", "xacrokit.shared.mesh_solids")


def kept_values(
    data: bytes, what: str, work_out: Callable[[], list[float] | None], digest: bytes | None = None
) -> list[float] | None:
    """Numbers worked out from the mesh file whose bytes are ``data`` (``what``: which numbers, and from what: the
    reader, a scale; ``digest``: the bytes' SHA-256, when known), kept as :func:`kept_facts` keeps a mesh's facts
    (None, too: nothing to work out)."""
    name = _name(f"{FORMAT}:{_code()}:{what}:", data, digest)
    return kept("meshes", __version__, name, work_out, json.dumps, _values)  # (a float's repr reads back the same)


def _values(text: str) -> list[float] | None:
    """Kept numbers (or None). Raises ValueError when the text is not what :func:`kept_values` writes."""
    said = json.loads(text)
    if said is None or (isinstance(said, list) and all(isinstance(v, float) for v in said)):
        return said
    raise ValueError("not kept numbers")


def _written(facts: Facts) -> str:
    import numpy as np  # (heavy: numpy)

    points, triangles = facts
    rows = np.ascontiguousarray(points, dtype="<f4")
    said = {"triangles": int(triangles), "vertices": len(rows), "points": base64.b64encode(rows.tobytes()).decode()}
    return json.dumps(said)


def _read(text: str) -> Facts:
    """Kept facts. Raises ValueError when the text is not what :func:`_written` writes (a damaged file)."""
    import numpy as np  # (heavy: numpy)

    try:
        said = json.loads(text)
        data = base64.b64decode(said["points"], validate=True)
        vertices, triangles = said["vertices"], said["triangles"]
    except (KeyError, TypeError) as exc:
        raise ValueError(f"not kept facts: {exc}") from exc
    if not isinstance(vertices, int) or not isinstance(triangles, int) or triangles < 1 or len(data) != 12 * vertices:
        raise ValueError("not kept facts: counts")
    return np.frombuffer(data, dtype="<f4").reshape(vertices, 3).astype(np.float32), triangles
