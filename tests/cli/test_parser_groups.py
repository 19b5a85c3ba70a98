"""A run of one command builds only its group's parsers (build_parser(command)): each command's parser built so must
take exactly what the whole parser (the one help shows) gives it, and nothing of the other groups may be built."""

from __future__ import annotations

import argparse

import pytest

from xacrokit.cli.app import COMMANDS, build_parser


def _commands(parser: argparse.ArgumentParser) -> dict[str, argparse.ArgumentParser]:
    assert parser._subparsers is not None
    (action,) = parser._subparsers._group_actions
    return dict(action.choices)  # type: ignore[arg-type]


def _shape(parser: argparse.ArgumentParser) -> list[tuple[tuple[str, ...], str, object, object]]:
    return [(tuple(a.option_strings), a.dest, a.default, a.nargs) for a in parser._actions]


def test_the_whole_parser_has_every_command() -> None:
    assert sorted(_commands(build_parser())) == sorted(COMMANDS)


@pytest.mark.parametrize("command", COMMANDS)
def test_a_command_alone_parses_as_in_the_whole_parser(command: str) -> None:
    alone, whole = _commands(build_parser(command)), _commands(build_parser())
    assert command in alone
    assert _shape(alone[command]) == _shape(whole[command])
    assert alone[command].format_help() == whole[command].format_help()
    assert len(alone) <= 4  # (its group alone: schema, expand, macros and materials are the largest)
