"""Every example robot spec carries the schema modeline (a path that exists) and follows the schema."""

from __future__ import annotations

import os
from pathlib import Path

import jsonschema
import yaml

from conftest import REPO, ROBOT_EXAMPLES


def test_examples_carry_the_schema_modeline_and_validate_against_the_schema():
    from xacrokit.validate import robot_schema

    robots = [*ROBOT_EXAMPLES, *sorted((REPO / "examples" / "scenes" / "robots").glob("*.yaml"))]
    assert len(robots) >= 16  # (the robot examples and the scenes' own robots: none moved away)
    for path in robots:
        text = path.read_text(encoding="utf-8")
        schema = Path(os.path.relpath(REPO / "schemas" / "robot.schema.json", path.parent)).as_posix()
        assert text.startswith(f"# yaml-language-server: $schema={schema}\n"), path.name
        jsonschema.validate(yaml.safe_load(text), robot_schema())
        assert (path.parent / schema).is_file()
