"""Where the data shipped inside the package lives: the macro library, the templates and the schemas.

They are sub-packages (``xacrokit.macros`` ...) so that the import system finds them the same way in an editable
install (where they are the repository's top-level folders) and in a wheel (where they sit inside ``xacrokit/``): their
module spec's search location is the folder (``importlib.util.find_spec``, which start-up has loaded already;
``importlib.resources`` would add its own modules to every command's start for the same answer on disk).
"""

from __future__ import annotations

import importlib.util
from pathlib import Path

from ..errors import ResourceError

PUBLIC_MACRO_FILES = ("inertia.xacro", "links.xacro", "materials.xacro", "wheel.xacro", "dh.xacro")
# the public macros those files define (a test checks this against the files' banners)
PUBLIC_MACROS = (
    "box_inertial",
    "cylinder_inertial",
    "sphere_inertial",
    "hollow_cylinder_inertial",
    "capsule_inertial",
    "inertial",
    "box_link",
    "cylinder_link",
    "sphere_link",
    "wheel",
    "dh_arm",
)


# the elements of the xacro language (xacro:NAME): no macro may be named so, or xacro takes it for the element
XACRO_KEYWORDS = frozenset(
    {"include", "macro", "property", "arg", "if", "unless", "call", "insert_block", "element", "attribute"}
)


def _data_dir(package: str) -> Path:
    try:
        found = importlib.util.find_spec(package)
    except ModuleNotFoundError as exc:  # the install is missing a data folder
        raise ResourceError(f"xacrokit is installed without {package}: reinstall it ({exc})") from exc
    if found is None or not found.submodule_search_locations:
        raise ResourceError(f"xacrokit is installed without {package}: reinstall it")
    path = Path(next(iter(found.submodule_search_locations)))
    if not path.is_dir():
        # A zipped install has no real folder; xacro needs files it can open by name.
        raise ResourceError(f"{package} is not a folder on disk ({path}); install xacrokit unzipped")
    return path


def macros_dir() -> Path:
    """The folder holding the public macro files (``inertia.xacro`` ...)."""
    return _data_dir("xacrokit.macros")


def package_share_dir() -> Path:
    """What ``$(find xacrokit)`` stands for: the folder that holds ``macros/``."""
    return macros_dir().parent


def templates_dir() -> Path:
    """The folder holding the jinja2 templates of generated packages."""
    return _data_dir("xacrokit.templates")


def schemas_dir() -> Path:
    """The folder holding the JSON Schemas of spec files."""
    return _data_dir("xacrokit.schemas")
