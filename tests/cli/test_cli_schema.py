"""gen-robot schema: each JSON Schema, valid 2020-12, with descriptions."""

from __future__ import annotations

import json

import jsonschema
import pytest

from conftest import gen_robot


def test_schema_command_prints_a_valid_2020_12_schema_with_descriptions():
    result = gen_robot("schema")
    schema = json.loads(result.stdout)
    jsonschema.Draft202012Validator.check_schema(schema)

    def walk(node, where):
        if isinstance(node, dict):
            if "properties" in node:
                for key, value in node["properties"].items():
                    assert "description" in value or "$ref" in value, f"{where}.{key} has no description"
            for key, value in node.items():
                walk(value, f"{where}.{key}")
        elif isinstance(node, list):
            for item in node:
                walk(item, where)

    walk(schema, "$")
    for name, definition in schema["$defs"].items():
        assert "description" in definition, name


@pytest.mark.parametrize("kind", ["robot", "scene", "check-report", "check-run"])
def test_schema_command_prints_each_schema(kind):
    result = gen_robot("schema", "--kind", kind)
    schema = json.loads(result.stdout)
    jsonschema.Draft202012Validator.check_schema(schema)
    assert schema["$id"] == f"urn:xacrokit:schema:{kind}:v1"
