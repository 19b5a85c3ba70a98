"""xacrokit: an Xacro macro library and code-generation toolkit for correct ROS 2 robot descriptions.

Public API:
    generate(spec, output=None, *, dry_run=False, force=False, macros="inline", via_xacro=False, trust=False,
             progress=...) -> GenerateResult
                                                                the main job: spec -> ROS 2 description package;
                                                                .model is the Robot (or the Scene of a scene spec)
    check(robot, *, prefix=None, consumers=None, progress=None) -> CheckReport
                                                                verify a URDF, xacro document or spec (robot: a
                                                                path, or a RobotInput with xacro arguments,
                                                                package folders and trust)
    expand(path, mappings=None, *, package_paths=None, trust=None) -> str
                                                                expand a xacro document to URDF text
    macros_dir() -> Path                                        where the shipped macro library is
    XacrokitError, SpecError, SpecErrors, ExpandError, ResourceError, ConflictError   the errors raised on bad input

Heavy modules load on first use, so that ``gen-robot --help`` stays fast.
"""

from __future__ import annotations

from importlib import import_module
from typing import Any

from .errors import ExpandError, ResourceError, SpecError, SpecErrors, XacrokitError

__version__ = "0.1.0"

_LAZY = {
    "generate": ("xacrokit.pipeline", "generate"),
    "GenerateResult": ("xacrokit.pipeline", "GenerateResult"),
    "expand": ("xacrokit.expansion.xacro_expand", "expand_file"),
    "ConflictError": ("xacrokit.write.package_writer", "ConflictError"),
    "check": ("xacrokit.check", "check"),
    "CheckReport": ("xacrokit.check", "CheckReport"),
    "macros_dir": ("xacrokit.shared.package_data", "macros_dir"),
}

__all__ = [
    "CheckReport",
    "check",
    "ConflictError",
    "ExpandError",
    "GenerateResult",
    "ResourceError",
    "SpecError",
    "SpecErrors",
    "XacrokitError",
    "expand",
    "generate",
    "macros_dir",
    "__version__",
]


def __getattr__(name: str) -> Any:
    if name in _LAZY:
        module, attribute = _LAZY[name]
        value = getattr(import_module(module), attribute)
        globals()[name] = value
        return value
    raise AttributeError(f"module 'xacrokit' has no attribute {name!r}")
