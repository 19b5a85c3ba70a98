"""An untrusted document expands within bounds (xacrokit.expansion.bounded_child): what no check of an expression's text
can bound, its time, memory and output, is bounded by a forked child; a trusted document is not bounded."""

from __future__ import annotations

import os
import signal
import time

import pytest

import xacrokit.expansion.xacro_expand as expansion
from conftest import XACRO_HEADER, gen_robot
from xacrokit.errors import ExpandError
from xacrokit.expansion.bounded_child import Bounds

# a macro that calls the level below it twice: 2**depth links
DOUBLING = XACRO_HEADER + (
    '<xacro:macro name="grow" params="n id">'
    '<xacro:if value="${n == 0}"><link name="l_${id}"/></xacro:if>'
    '<xacro:if value="${n > 0}"><xacro:grow n="${n - 1}" id="${id}a"/><xacro:grow n="${n - 1}" id="${id}b"/>'
    "</xacro:if></xacro:macro>"
    '<xacro:grow n="{depth}" id="x"/></robot>'
)


def document(folder, text, name="doc.urdf.xacro"):
    path = folder / name
    path.write_text(text, encoding="utf-8")
    return path


@pytest.fixture
def small_bounds(monkeypatch):
    bounds = Bounds(seconds=2.0, memory=512 * 2**20, output=20_000)
    monkeypatch.setattr(expansion, "EXPAND_BOUNDS", bounds)
    return bounds


def test_an_expression_that_asks_for_too_much_memory_is_stopped(tmp_path):
    path = document(tmp_path, XACRO_HEADER + "<link name=\"${'x' * 10**10}\"/></robot>")  # 10 GB
    with pytest.raises(ExpandError) as caught:
        expansion.expand_file(path)
    assert "expanding it needs more than 4 GiB of memory (the bounds on documents from elsewhere)" in str(caught.value)
    assert "--trust" in str(caught.value)


def test_an_expression_that_computes_for_hours_is_stopped_in_time(tmp_path, small_bounds):
    path = document(tmp_path, XACRO_HEADER + '<link name="${9**9**9}"/></robot>')  # one C call, hours long
    started = time.monotonic()
    with pytest.raises(ExpandError) as caught:
        expansion.expand_file(path)
    assert time.monotonic() - started < small_bounds.seconds + 5
    assert "it did not finish expanding within 2 s" in str(caught.value)


def test_a_document_that_grows_too_large_is_stopped_and_a_trusted_one_is_not(tmp_path, monkeypatch):
    small_bounds = Bounds(seconds=120.0, memory=512 * 2**20, output=20_000)  # (time enough on a loaded machine)
    monkeypatch.setattr(expansion, "EXPAND_BOUNDS", small_bounds)
    path = document(tmp_path, DOUBLING.replace("{depth}", "10"))  # 1,024 links: about 32 kB of URDF, in about 1 s
    with pytest.raises(ExpandError) as caught:
        expansion.expand_file(path)
    assert "it expands to more than 0.0190735 MiB of URDF" in str(caught.value)
    urdf = expansion.expand_file(path, trust=True)
    assert urdf.count("<link ") == 2**10 and len(urdf) > small_bounds.output


def test_within_bounds_the_child_gives_the_same_urdf_and_the_same_errors(tmp_path):
    path = document(tmp_path, DOUBLING.replace("{depth}", "3"))
    assert expansion.expand_file(path) == expansion.expand_file(path, trust=True)
    broken = document(tmp_path, XACRO_HEADER + '<xacro:macro name="m" params="a"/><xacro:m/></robot>', "b.xacro")
    errors = []
    for trust in (False, True):
        with pytest.raises(ExpandError) as caught:
            expansion.expand_file(broken, trust=trust)
        errors.append((caught.value.message, caught.value.file, caught.value.macro_stack, caught.value.file_stack))
    assert errors[0] == errors[1] and "a" in errors[0][0]


def test_xacro_warnings_in_the_child_reach_the_parent(tmp_path, capsys):
    path = document(tmp_path, XACRO_HEADER + '<xacro:property name="pi" value="3"/><link name="l${pi}"/></robot>')
    assert '<link name="l3"/>' in expansion.expand_file(path)
    assert "redefining global symbol: pi" in capsys.readouterr().err


def test_a_child_that_dies_is_an_error_not_a_hang(tmp_path, monkeypatch):
    def crash(*args, **kwargs):
        os.kill(os.getpid(), signal.SIGTERM)

    monkeypatch.setattr(expansion, "_expand", crash)
    with pytest.raises(ExpandError) as caught:
        expansion.expand_file(document(tmp_path, XACRO_HEADER + "</robot>"))
    assert "expanding the document stopped (killed by SIGTERM)" in str(caught.value)


def test_the_command_line_says_so_with_exit_2(tmp_path):
    path = document(tmp_path, XACRO_HEADER + "<link name=\"${'x' * 10**10}\"/></robot>")
    for words in (("expand", path), ("check", path, "--consumers", "none")):
        result = gen_robot(*words)
        assert result.returncode == 2 and "needs more than 4 GiB of memory" in result.stderr, result.stderr
        assert "Traceback" not in result.stderr
