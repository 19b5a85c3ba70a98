"""A wrong value where the schema allows more than one type (density: number or text; a visual's material: text or
none) is a located error, exit 2: it was an internal error (exit 70), the type message taking a list of types as a
key (issue 41's hostile review)."""

from __future__ import annotations

import pytest
import yaml

from conftest import gen_robot

BOX = {"box": {"size": [0.1, 0.1, 0.1]}}


@pytest.mark.parametrize(
    "link",
    [
        {"shape": BOX, "density": [1]},
        {"shape": BOX, "density": {"a": 1}},
        {"shape": BOX, "mass": 1.0, "visuals": [{"shape": BOX, "material": [1]}]},
    ],
    ids=["density-list", "density-mapping", "visual-material-list"],
)
def test_a_value_of_none_of_the_allowed_types_is_a_located_error(link, tmp_path):
    spec = tmp_path / "bad.yaml"
    spec.write_text(yaml.safe_dump({"robot": "r", "links": {"base_link": link}}), encoding="utf-8")
    done = gen_robot(str(spec), "-o", str(tmp_path / "out"), cwd=tmp_path)
    assert done.returncode == 2, done.stderr
    assert "internal error" not in done.stderr and "bad.yaml:" in done.stderr
    assert not (tmp_path / "out").exists()
