"""Expanding an untrusted xacro document runs no code: expressions that could reach Python's internals are refused
(check, expand and scene probing alike), real descriptions' expressions still work, and --trust restores xacro's own
behaviour for one's own documents."""

from __future__ import annotations

import pytest

import xacrokit
from conftest import XACRO_HEADER, expand_text, gen_robot
from xacrokit.expansion.expression_guard import expression_problem

# xacro's own check (no name starting with __) lets these through; each reaches Python's object graph or builtins
ESCAPES = [
    "python.vars(python.type)['__subclasses__']",  # the published escape: to every class, then os.system
    "[].__class__",
    "x.__class__.__mro__",
    "'{0.__class__}'.format(x)",
    "('{0._' + '_class_' + '_}').format(x)",
    "python.type(x)",
    "python.vars(x)",
    "m._private",
    "__import__('os')",
    "b'__class__'",
    "f'{x.__class__}'",
    # a walk from a generator's frame to a module's globals, with no underscore (found in review)
    "python.list((g := (g.gi_frame.f_back.f_back.f_globals for x in [0])) and g)[0]['os'].getpid()",
    "(x for x in [0]).gi_frame.f_back.f_globals",
    "python.type.mro(python.type)",
]
# $(eval ...) sees Python's builtins: there these names are refused too
BUILTIN_ESCAPES = ["getattr(x, 'y')", "exec('1')", "open('/etc/passwd')", "vars()", "type(x)", "eval('1')"]

# what real descriptions write (UR, Franka, KUKA, our own library): all allowed
REAL = [
    "pi / 2",
    "-pi",
    "radians(90)",
    "math.pi * 2",
    "xacro.load_yaml(file)['shoulder']['x']",
    "sec_limits['shoulder_pan_joint']['min_position']",
    "'true' if use_fake else 'false'",
    "str(a) + ' ' + str(b)",
    "[v * 2 for v in values]",
    "python.isinstance(value, (python.int, python.float)) and not python.isinstance(value, python.bool)",
    "'{:.3f}'.format(length)",
    "d.get('key', 0.0)",
    "name.split('_')[0].upper()",
    "xacro.fatal('inertial: bad', python.repr(v))",
    "_xacrokit_pivot2 > 0",  # our own private properties: a name with one leading _ is a property, not internals
    "type",  # a macro's own parameter named type (a joint macro's: params="name type parent child")
    "cfg.type + '_joint'",  # a field of a xacro.dotify'd YAML file
    "'revolute' if type == 'r' else input",  # (in ${...} these are the document's names, not Python's builtins)
]


@pytest.mark.parametrize("expression", ESCAPES)
def test_escapes_are_refused(expression):
    assert expression_problem(expression) is not None


@pytest.mark.parametrize("expression", BUILTIN_ESCAPES)
def test_escapes_through_builtins_are_refused_in_eval(expression):
    assert expression_problem(expression, builtins=True) is not None


@pytest.mark.parametrize("expression", REAL)
def test_real_expressions_pass(expression):
    assert expression_problem(expression) is None


NAMESPACE_ESCAPES = [
    "<link name=\"${python['type'] is not None}\"/>",  # the python namespace is a dict: a subscript reaches type
    # a dunder name held in a property (never evaluated, so never parsed) used as a key
    '<xacro:property name="k" value="__subclasses__"/>'
    "<link name=\"${python['vars'](python['type'])[k] is not None}\"/>",
]


@pytest.mark.parametrize("body", NAMESPACE_ESCAPES, ids=["subscript", "property-held-dunder"])
def test_type_and_vars_are_out_of_reach_when_untrusted(tmp_path, body):
    doc = XACRO_HEADER + body + "\n</robot>\n"
    with pytest.raises(xacrokit.ExpandError, match="type"):
        expand_text(doc, tmp_path)
    assert expand_text(doc, tmp_path, trust=True).find("link").get("name") == "True"


def test_a_macro_parameter_named_type_expands_untrusted(tmp_path):
    doc = XACRO_HEADER + (
        '<xacro:macro name="j" params="name type"><joint name="${name}" type="${type}"/></xacro:macro>'
        '<xacro:j name="a" type="revolute"/></robot>'
    )
    assert expand_text(doc, tmp_path).find("joint").get("type") == "revolute"


# a harmless use of the escape's first step: the object graph is in reach when trusted, refused when not
PROBE = "<link name=\"${python.vars(python.type)['__subclasses__'] is not None}\"/>"
BUILTINS = '<link name="$(eval open is not None)"/>'  # $(eval) has all of Python's builtins, open and exec among them


@pytest.mark.parametrize("body", [PROBE, BUILTINS], ids=["subclasses", "eval-builtins"])
def test_an_untrusted_document_is_refused_and_a_trusted_one_is_evaluated(tmp_path, body):
    doc = XACRO_HEADER + body + "\n</robot>\n"
    with pytest.raises(xacrokit.ExpandError, match="refused to evaluate .*--trust"):
        expand_text(doc, tmp_path)
    assert expand_text(doc, tmp_path, trust=True).find("link").get("name") == "True"


def test_the_command_line_refuses_and_trusts_on_request(tmp_path):
    path = tmp_path / "probe.urdf.xacro"
    path.write_text(XACRO_HEADER + PROBE + "\n</robot>\n", encoding="utf-8")
    for command in (["expand", path], ["check", path, "--consumers", "none"]):
        refused = gen_robot(*command)
        assert refused.returncode == 2 and "refused to evaluate" in refused.stderr, refused.stderr
        assert "Traceback" not in refused.stderr
    trusted = gen_robot("expand", path, "--trust")
    assert trusted.returncode == 0 and 'name="True"' in trusted.stdout, trusted.stderr


def test_a_document_reading_yaml_and_indexing_it_expands_untrusted(tmp_path):
    (tmp_path / "limits.yaml").write_text("shoulder: {lower: -1.5, upper: 1.5}\n", encoding="utf-8")
    doc = (
        XACRO_HEADER
        + '<xacro:property name="limits" value="${xacro.load_yaml(\'limits.yaml\')}"/>\n'
        + "<link name=\"l_${limits['shoulder']['lower'] * 2}_${'%.1f' % pi}\"/>\n</robot>\n"
    )
    # (xacro's ${...} ends at the first }: a format string with braces cannot be written there)
    assert expand_text(doc, tmp_path).find("link").get("name") == "l_-3.0_3.1"


def test_the_guard_is_lifted_after_each_expansion(tmp_path):
    import xacro

    before = xacro.safe_eval
    with pytest.raises(xacrokit.ExpandError):
        expand_text(XACRO_HEADER + PROBE + "\n</robot>\n", tmp_path)
    assert xacro.safe_eval is before
