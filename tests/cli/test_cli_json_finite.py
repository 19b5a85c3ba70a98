"""Every --json of gen-robot goes through one printer (cli/json_output.py) that prints RFC 8259 JSON or nothing
(issue 41): a result holding inf or NaN, which Python's json would print as Infinity or NaN, is exit 2 with the place
in the result said. The commands refuse such results before (their own tests); here the printer's wiring, with the
result made to hold one."""

from __future__ import annotations

import math
from types import SimpleNamespace

import pytest

import xacrokit.check.file_workers
import xacrokit.check.sarif_report
import xacrokit.sizing
from xacrokit.cli import main

URDF = '<robot name="r"><link name="base"/></robot>'


@pytest.mark.parametrize(
    ("module", "name", "words"),
    [
        (xacrokit.check.file_workers, "run_dict", ["check", "{folder}", "--json", "--consumers", "none"]),
        (xacrokit.check.sarif_report, "sarif_log", ["check", "{folder}", "--format", "sarif", "--consumers", "none"]),
        (xacrokit.sizing, "size", ["size", "{folder}/r.urdf", "--json"]),
    ],
)
def test_no_command_prints_a_number_json_cannot_hold(tmp_path, capsys, monkeypatch, module, name, words):
    (tmp_path / "r.urdf").write_text(URDF, encoding="utf-8")
    held = {"found": [{"value": math.nan}], "peak": -math.inf}
    report = SimpleNamespace(to_dict=lambda: held, exit_code=0)
    monkeypatch.setattr(module, name, lambda *args, **kwargs: report if name == "size" else held)
    code = main([word.format(folder=tmp_path) for word in words])
    out, err = capsys.readouterr()
    assert code == 2 and out == ""
    assert err == (
        "gen-robot: error: the result overflows: $.found[0].value is nan, beyond what a float holds (JSON has no "
        "number for it); nothing printed\n"
    )
