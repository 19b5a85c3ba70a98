"""The rows file reader (issue 43, item 3; ``pose --configurations``, ``ik --targets``): each row's line and its
values as text, named or positional; limits and encodings refused with the file and line."""

from __future__ import annotations

import pytest

from xacrokit.cli import rows_file
from xacrokit.cli.rows_file import Row, read_rows
from xacrokit.errors import SpecError, SpecErrors


def written(tmp_path, name: str, data: str | bytes):
    path = tmp_path / name
    path.write_bytes(data.encode("utf-8") if isinstance(data, str) else data)
    return path


def test_csv_rows_keep_their_text_and_their_first_line(tmp_path):
    path = written(tmp_path, "t.csv", '\ufeffx, y ,label\n1,-2.5e3,"a\nb"\n\n 30deg ,0.1 m,c\n')
    assert read_rows(path) == [
        Row(2, ("1", "-2.5e3", "a\nb"), ("x", "y", "label"), header_line=1),  # (a field over two lines: the first)
        Row(5, ("30deg", "0.1 m", "c"), ("x", "y", "label"), header_line=1),
    ]
    assert read_rows(path)[1].named() == {"x": "30deg", "y": "0.1 m", "label": "c"}


def test_yaml_rows_keep_each_values_line(tmp_path):
    path = written(tmp_path, "t.yaml", "- a: 1.5\n  b: -30deg\n- [1e-3, 2]\n")
    assert read_rows(path) == [Row(1, ("1.5", "-30deg"), ("a", "b"), (1, 2)), Row(3, ("0.001", "2"), None, (3, 3))]
    assert read_rows(path)[0].line_of(1) == 2 and read_rows(path)[1].named() is None


def test_a_file_of_more_rows_than_the_limit_is_refused_at_the_first_beyond(tmp_path, monkeypatch):
    monkeypatch.setattr(rows_file, "MAX_ROWS", 3)
    assert len(read_rows(written(tmp_path, "ok.csv", "1\n2\n3\n"))) == 3
    with pytest.raises(SpecError) as csv_error:
        read_rows(written(tmp_path, "t.csv", "a\n1\n2\n3\n4\n"))
    assert str(csv_error.value) == f"{tmp_path / 't.csv'}:5: more than 3 rows; split the file"
    with pytest.raises(SpecError) as yaml_error:
        read_rows(written(tmp_path, "t.yaml", "- [1]\n- [2]\n- [3]\n- [4]\n"))
    assert str(yaml_error.value) == f"{tmp_path / 't.yaml'}:4: more than 3 rows; split the file"


def test_unreadable_files_say_why(tmp_path):
    (tmp_path / "d.csv").mkdir()
    with pytest.raises(SpecError) as folder:
        read_rows(tmp_path / "d.csv")
    assert str(folder.value) == f"{tmp_path / 'd.csv'}: cannot read it: it is a folder, not a file"
    with pytest.raises(SpecError) as latin:
        read_rows(written(tmp_path, "t.yaml", b"- [1]\n- [caf\xe9]\n"))
    assert str(latin.value) == f"{tmp_path / 't.yaml'}:2:7: not UTF-8 text (byte 0xe9); save it as UTF-8"
    with pytest.raises(SpecErrors) as bad_yaml:
        read_rows(written(tmp_path, "u.yaml", "- [1\n"))
    assert bad_yaml.value.errors[0].line is not None
    with pytest.raises(SpecError) as comments:
        read_rows(written(tmp_path, "c.yaml", "# nothing yet\n"))
    assert str(comments.value).endswith(
        "c.yaml: no rows: give a list of rows (mappings name: value, or lists of values)"
    )
