"""xacrokit: an Xacro macro library and code-generation toolkit for correct ROS 2 robot descriptions.

Public API:
    expand(path, mappings=None, *, package_paths=None) -> str   expand a xacro document to URDF text
    macros_dir() -> Path                                        where the shipped macro library is
    XacrokitError, ExpandError                                   the errors raised on bad input
"""

from __future__ import annotations

from .errors import ExpandError, ResourceError, XacrokitError
from .expand import expand_file as expand
from .resources import macros_dir

__version__ = "0.1.0"

__all__ = ["ExpandError", "ResourceError", "XacrokitError", "expand", "macros_dir", "__version__"]
