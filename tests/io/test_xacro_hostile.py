"""Opening a hostile xacro file runs nothing (issue 34, item 1).

Each variant below would create a marker file if anything in it ran (the shell's
``touch``, Python's ``open``, ...). kinematica's expander must refuse each with one
line naming the file (and, for an expression, the line and the expression), and the
marker must not exist afterwards. The first variant is the escape the audit found; the
xacro package, trusted, does run it (the test shows it, so the payload is real).
"""

from __future__ import annotations

import subprocess
import sys
from pathlib import Path

import pytest

import kinematica as km
import kinematica.io.xacro as xacro_module
from kinematica.io import read_urdf

HEAD = '<?xml version="1.0"?>\n<robot name="evil" xmlns:xacro="http://www.ros.org/wiki/xacro">\n'
TAIL = '  <link name="base"/>\n</robot>\n'

# f.__globals__ without a name that starts with "__": the descriptor's own __get__, by string
GLOBALS = (
    "python.vars(python.type(python.vars(python.type(xacro.tokenize))['__globals__']))"
    "['__get__'](python.vars(python.type(xacro.tokenize))['__globals__'], xacro.tokenize)"
)
ESCAPE = GLOBALS + "['os'].system('touch {marker}')"


def variants(marker: Path) -> dict[str, tuple[str, str]]:
    """name -> (file body, a fragment the error must quote)."""
    m = str(marker)
    touch = f"touch {m}"
    return {
        "escape in an attribute": (
            f'<link name="${{{ESCAPE.format(marker=m)}}}"/>',
            "'python' namespace is refused",
        ),
        "escape in text": (f"<note>${{{ESCAPE.format(marker=m)}}}</note>", "python"),
        "escape in a property": (
            f'<xacro:property name="p" value="${{{ESCAPE.format(marker=m)}}}"/>'
            '<link name="${p}"/>',
            "python",
        ),
        "escape in a macro default": (
            f'<xacro:macro name="m" params="x:=${{{ESCAPE.format(marker=m)}}}">'
            '<link name="${x}"/></xacro:macro><xacro:m/>',
            "python",
        ),
        "escape in a condition": (
            f'<xacro:if value="${{{ESCAPE.format(marker=m)}}}"><link name="x"/></xacro:if>',
            "python",
        ),
        "escape in $(eval)": (
            f"<link name=\"$(eval {GLOBALS}['os'].system('{touch}'))\"/>",
            "python",
        ),
        "__import__": (
            f"<link name=\"${{__import__('os').system('{touch}')}}\"/>",
            "double underscore",
        ),
        "eval": (
            f"<link name=\"${{eval(&quot;open('{m}', 'w')&quot;)}}\"/>",
            "unknown name 'eval'",
        ),
        "exec": (
            f"<link name=\"${{exec('import os; os.system(1)')}}\"/><x>{touch}</x>",
            "unknown name 'exec'",
        ),
        "open": (f"<link name=\"${{open('{m}', 'w')}}\"/>", "unknown name 'open'"),
        "getattr": (
            f"<link name=\"${{getattr(xacro.tokenize, '__glo' + 'bals__')['os'].system('{touch}')}}"
            '"/>',
            "unknown name 'getattr'",
        ),
        "attribute chain": (
            '<link name="${().__class__.__bases__[0].__subclasses__()}"/>',
            "double underscore",
        ),
        "attribute of a function": (
            f"<link name=\"${{xacro.tokenize.func_globals['os'].system('{touch}')}}\"/>",
            "xacro.tokenize",
        ),
        "method of a string": (
            "<link name=\"${'0.__init__.__globals__'.format(xacro.tokenize)}\"/>",
            "(...).format is not a function that may be called",
        ),
        "format with %": (f"<link name=\"${{'%s' % '{touch}'}}\"/>", "string formatting"),
        "f-string": (f"<link name=\"${{f'open(&quot;{m}&quot;, &quot;w&quot;)'}}\"/>", "f''"),
        "a brace ends the expression": (
            f"<link name=\"${{f'{{open(&quot;{m}&quot;, &quot;w&quot;)}}'}}\"/>",
            "string that is not closed",
        ),
        "lambda": (
            f"<link name=\"${{(lambda: open('{m}', 'w'))()}}\"/>",
            "lambda functions are not allowed",
        ),
        "comprehension": (
            f"<link name=\"${{[open('{m}', 'w') for c in 'x']}}\"/>",
            "comprehensions are not allowed",
        ),
        "names built from properties": (
            '<xacro:property name="u" value="_"/>'
            f"<xacro:arg name=\"rest\" default=\"_import__('os').system('{touch}')\"/>"
            '<link name="${_$(arg rest)}"/>',
            "double underscore",
        ),
        "code in an argument": (
            f"<xacro:arg name=\"code\" default=\"open('{m}', 'w')\"/>"
            '<link name="${$(arg code)}"/>',
            "unknown name 'open'",
        ),
        "a property named like a builtin slot": (
            '<xacro:property name="__builtins__" value="1"/>',
            "not a valid name",
        ),
        "python.type": ('<link name="${python.type(1)}"/>', "'python' namespace is refused"),
        "math module internals": ('<link name="${math.__dict__}"/>', "double underscore"),
        "xacro functions that are not offered": (
            "<link name=\"${xacro.abs_filename('x')}\"/>",
            "not a function that may be called",
        ),
        "load_yaml outside the packages": (
            f"<link name=\"${{load_yaml('{marker.parent.parent / 'outside' / 'secret.yaml'}')}}"
            '"/>',
            "outside the folders",
        ),
        "load_yaml of a python tag": (
            "<link name=\"${load_yaml('tagged.yaml')}\"/>",
            "not valid YAML",
        ),
        "$(env) without consent": ('<link name="$(env HOME)"/>', "'HOME'"),
        "$(optenv) without consent": ('<link name="$(optenv HOME nothing)"/>', "'HOME'"),
        "include /etc/passwd": ('<xacro:include filename="/etc/passwd"/>', "outside the folders"),
        "include through a symlink": (
            '<xacro:include filename="link_to_passwd"/>',
            "outside the folders",
        ),
        "include of itself": ('<xacro:include filename="evil.xacro"/>', "include cycle"),
        "a package name that is a path": (
            '<xacro:include filename="$(find ../../..)/etc/passwd"/>',
            "needs the ROS package '../../..'",
        ),
        "unknown substitution": ('<link name="$(cwd)"/>', "unknown or malformed substitution"),
        "unknown xacro element": ('<xacro:python code="x"/>', "unknown xacro element"),
    }


@pytest.fixture
def room(tmp_path: Path) -> tuple[Path, Path]:
    """A folder for the hostile file, with a YAML file holding a Python tag and a symlink
    to /etc/passwd beside it, and a YAML file outside; the marker's path."""
    here = tmp_path / "here"
    here.mkdir()
    (tmp_path / "outside").mkdir()
    (tmp_path / "outside" / "secret.yaml").write_text("secret: 42\n")
    marker = here / "marker"
    (here / "tagged.yaml").write_text(f"x: !!python/object/apply:os.system ['touch {marker}']\n")
    (here / "link_to_passwd").symlink_to("/etc/passwd")
    return here, marker


def test_at_least_twenty_variants() -> None:
    assert len(variants(Path("/m"))) >= 30


@pytest.mark.parametrize("name", sorted(variants(Path("/m"))))
def test_a_hostile_file_runs_nothing(room: tuple[Path, Path], name: str) -> None:
    here, marker = room
    body, quoted = variants(marker)[name]
    path = here / "evil.xacro"
    path.write_text(HEAD + "  " + body + "\n" + TAIL)
    with pytest.raises(km.RobotFileError) as info:
        km.load(path)
    message = str(info.value)
    assert "\n" not in message
    assert str(path) in message
    assert quoted in message, message
    if "${" in body and "load_yaml" not in body and "builtins" not in body:
        assert "line 3" in message and "expression" in message, message
    assert not marker.exists()


def test_the_command_line_runs_nothing(room: tuple[Path, Path]) -> None:
    here, marker = room
    path = here / "evil.xacro"
    path.write_text(HEAD + f'  <link name="${{{ESCAPE.format(marker=marker)}}}"/>\n' + TAIL)
    done = subprocess.run(
        [sys.executable, "-m", "kinematica.cli.main", "show", str(path)],
        capture_output=True,
        text=True,
        check=False,
    )
    assert done.returncode == 2
    assert len(done.stderr.strip().splitlines()) == 1
    assert "'python' namespace is refused" in done.stderr
    assert not marker.exists()


@pytest.mark.skipif(xacro_module._xacro_dir() is None, reason="the xacro package is not installed")
def test_the_escape_is_real_the_xacro_package_runs_it_when_trusted(
    room: tuple[Path, Path],
) -> None:
    here, marker = room
    path = here / "evil.xacro"
    head = HEAD.replace('name="evil"', f'name="${{{ESCAPE.format(marker=marker)}}}"')
    path.write_text(head + TAIL)
    # the child has an empty environment: give the shell a PATH to find touch
    touch = "/usr/bin/touch" if Path("/usr/bin/touch").exists() else "/bin/touch"
    path.write_text(path.read_text().replace("'touch ", f"'{touch} "))
    model = read_urdf(path, trust_xacro=True)
    assert model.name == "0"  # os.system's exit status
    assert marker.exists()
