"""The MoveIt part of a generated package: ``config/NAME.srdf``, its collision matrix sampled on the URDF the package
carries (its meshes read where the package will hold them), and the configuration MoveIt reads beside it."""

from __future__ import annotations

import functools
import tempfile
from collections.abc import Sequence
from pathlib import Path

from ..model import Robot, Scene
from ..render.environment import RenderedFile
from ..shared.urdf_view import read_view
from ..write.atomic import write_text_atomic
from .collision_matrix import Judged, Meshes, Sampling, adjacent_pairs, cached_matrix, links_and_joints, matrix_key
from .moveit_config_files import moveit_config_files
from .semantics import Semantics, robot_semantics, scene_semantics
from .srdf_document import srdf_text

Home = tuple[tuple[str, float], ...]  # joint values, in the joints' order
SAMPLING = Sampling()  # the setup assistant's default: 10,000 configurations; seed 0
MAX_LINKS = 600  # links with collision geometry beyond which only adjacent pairs are said (180,000 pairs)


def semantics_of(model: Robot | Scene) -> Semantics:
    """A robot's or a scene's SRDF parts (its matrix aside)."""
    return robot_semantics(model) if isinstance(model, Robot) else scene_semantics(model)


def moveit_files(robot: Robot, files: Sequence[RenderedFile], *, spec_name: str) -> list[RenderedFile]:
    """A robot package's MoveIt files: its SRDF, and the configuration and launch files beside it
    (:mod:`.moveit_config_files`: for a robot with a JointTrajectoryController)."""
    srdf = srdf_file(robot, files, spec_name=spec_name)
    return [srdf, *moveit_config_files(robot, semantics_of(robot), spec_name=spec_name)]


def srdf_file(
    model: Robot | Scene, files: Sequence[RenderedFile], *, spec_name: str, sampling: Sampling = SAMPLING
) -> RenderedFile:
    """``config/NAME.srdf`` of a rendered package whose ``files`` hold its URDF (``urdf/NAME.urdf``)."""
    urdf = next(file.text for file in files if file.path == f"urdf/{model.name}.urdf")
    semantics = semantics_of(model)
    links, joints = links_and_joints(urdf, f"urdf/{model.name}.urdf")
    solid = set(links)
    adjacent = Judged({p: "Adjacent" for p in sorted(adjacent_pairs(joints, solid))}, 0, 0)
    if len(solid) > MAX_LINKS:
        judged, why_not = adjacent, f"{len(solid):,} links with collision geometry, more than the {MAX_LINKS} sampled"
    else:
        try:
            judged, why_not = collision_matrix(urdf, model.package, files, semantics, sampling), ""
        except (RuntimeError, ValueError, LookupError) as exc:  # (pinocchio or coal refused a shape: no sampling)
            judged, why_not = adjacent, f"pinocchio could not read the collision geometry ({exc})"
    text = srdf_text(semantics, judged, sampling, source=spec_name, why_not=why_not)
    return RenderedFile(f"config/{model.name}.srdf", text)


def collision_matrix(
    urdf: str, package: str, files: Sequence[RenderedFile], semantics: Semantics, sampling: Sampling
) -> Judged:
    """The disabled pairs of a package's URDF (its text), its meshes (``files`` under ``meshes/``) written to a
    scratch copy of the package ``package`` for pinocchio to read, judged at the semantics' home."""
    meshes = tuple((file.path, file.content) for file in files if file.path.startswith("meshes/"))
    return _judged(urdf, package, meshes, semantics.home, sampling)


@functools.lru_cache(maxsize=32)
def _judged(urdf: str, package: str, meshes: Meshes, home: Home, sampling: Sampling) -> Judged:
    """:func:`collision_matrix` on its values, remembered in this process and kept in the user's cache folder
    (``collision_matrix``): a package generated again (a second run, a dry run, the tests' many runs of one example)
    is not sampled again. (Judged is frozen; its dict is only read.)"""
    key = matrix_key(urdf, package, meshes, home, sampling)
    return cached_matrix(key, lambda: _sampled(urdf, package, meshes, home, sampling))


def _sampled(urdf: str, package: str, meshes: Meshes, home: Home, sampling: Sampling) -> Judged:
    """The matrix sampled: the meshes written to a scratch copy of the package for pinocchio to read."""
    from .collision_pairs import collision_bodies, configuration, disabled_pairs  # (heavy: pinocchio, numpy)

    with tempfile.TemporaryDirectory(prefix="xacrokit-srdf-") as scratch:
        root = Path(scratch) / package
        for path, content in meshes:
            write_text_atomic(root / path, content)
        bodies = collision_bodies(read_view(urdf), root / "urdf", {package: root})
        return disabled_pairs(bodies, configuration(bodies, dict(home)), sampling)
