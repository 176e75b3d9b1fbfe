"""kinematica's own xacro expander: robot descriptions expanded without running code.

It does what robot descriptions use, as the ``xacro`` package (2.x) does it:
properties (value and block properties, ``scope``, ``default``, ``remove``,
``lazy_eval``), macros (parameters with defaults ``p:=v``, ``^`` and ``^|``
forwarding, ``*block`` and ``**blocks``, ``<xacro:insert_block>``,
``<xacro:call>``), ``<xacro:include>`` (relative paths, ``$(find pkg)``,
``ns=``, ``optional``), ``<xacro:if>``/``<xacro:unless>``, ``<xacro:arg>``,
``<xacro:element>``, ``<xacro:attribute>``, and the substitutions ``${expr}``,
``$(arg x)``, ``$(find pkg)``, ``$(dirname)``, ``$(eval expr)``, and
``$(env X)``/``$(optenv X default)`` only when the caller allows the
environment. Expressions go through :mod:`kinematica.io.xacro_expr`, never
Python's ``eval``.

It reads only the file, the files it includes and the YAML files it loads,
and only inside the file's folder and the folders of the packages it names
(:class:`~kinematica.io.packages.PackageMap`): ``/etc/passwd`` is refused. It
stops at :data:`~kinematica.io.xacro.XACRO_MAX_NODES` elements made by macros
and includes, :data:`MAX_DEPTH` levels of nesting,
:data:`~kinematica.io.xacro_subst.MAX_FILES` files,
the size limit in characters made and the time limit. Every problem is one
:class:`~kinematica.errors.RobotFileError` naming the file and line.
"""

from __future__ import annotations

import copy
import os
import re
import time
from collections.abc import Mapping
from pathlib import Path
from typing import Any, Final

from kinematica.errors import KinematicaError, RobotFileError
from kinematica.io.packages import PackageMap, missing_package
from kinematica.io.reading import os_reason
from kinematica.io.xacro_scope import (
    Macro,
    Macros,
    Scope,
    XacroError,
    boolean,
    parse_params,
    valid_name,
)
from kinematica.io.xacro_subst import MissingPackageError, Substitutions
from kinematica.io.xml_parse import LINE, local_name

__all__ = ["MAX_DEPTH", "expand"]

#: Deepest nesting of elements and macro calls within one another.
MAX_DEPTH: Final = 120

_XACRO_TAGS: Final = frozenset(
    [
        "property",
        "macro",
        "include",
        "if",
        "unless",
        "arg",
        "insert_block",
        "call",
        "element",
        "attribute",
    ]
)


def _is_xacro(name: str) -> bool:
    return name.startswith("{") and "xacro" in name[1:].split("}", 1)[0]


class _Expander(Substitutions):
    """One expansion: the substitutions and files, and the elements it makes."""

    def __init__(self, packages: PackageMap, *, max_nodes: int, **limits: Any) -> None:
        super().__init__(packages, **limits)
        self.max_nodes = max_nodes
        self.nodes = 0
        self.depth = 0
        self.current: Any = None  # the element being expanded, for messages

    # --- elements -------------------------------------------------------------------

    def where(self, elem: Any) -> str:
        """Where ``elem`` is: ``"TOP, line N"``, or ``"TOP, in INCLUDED line N"``."""
        if not self.files:
            return "?"
        top = self.files[0]
        mark = elem.get(LINE) if elem is not None else None
        index, _, line = mark.partition(":") if mark else ("", "", "")
        file = self.files[int(index)] if index else self.files[self.stack[-1] if self.stack else 0]
        if file == top:
            return f"{top}, line {line}" if line else str(top)
        return f"{top}, in {file}" + (f" line {line}" if line else "")

    def grow(self, elem: Any) -> Any:
        """A deep copy of ``elem``, counted against the node limit."""
        self.nodes += sum(1 for _ in elem.iter())
        if self.nodes > self.max_nodes:
            raise XacroError(
                f"the expansion made more than {self.max_nodes} XML elements: refused "
                "(a macro that calls itself or its callers many times over?)"
            )
        return copy.deepcopy(elem)

    def element(self, elem: Any, macros: Macros, scope: Scope) -> None:
        """Expand ``elem`` in place: its attributes, text and children."""
        self.depth += 1
        if self.depth > MAX_DEPTH:
            raise XacroError(f"elements or macro calls nested deeper than {MAX_DEPTH}: refused")
        self.current = elem
        self.check_time()
        for name in list(elem.attrib):
            if _is_xacro(name):
                del elem.attrib[name]
            elif name != LINE:
                elem.set(name, self.string(elem.get(name), scope))
        self.children(elem, macros, scope)
        self.depth -= 1

    def children(self, parent: Any, macros: Macros, scope: Scope) -> None:
        """Expand the children of ``parent``, splicing in what xacro elements become."""
        head = [self.string(parent.text, scope) if parent.text else ""]
        out: list[Any] = []

        def add_text(text: str) -> None:
            if not text:
                return
            if out:
                out[-1].tail = (out[-1].tail or "") + text
            else:
                head[0] += text

        for child in list(parent):
            tail, child.tail = child.tail, None
            if not isinstance(child.tag, str):  # a comment or processing instruction
                pass
            elif child.tag == "property" and "name" in child.attrib:
                self.current = child  # ROS 1 xacro read <property> without the namespace
                self.property(child, scope)
            elif _is_xacro(child.tag):
                self.current = child
                lead, nodes = self.xacro(child, parent, macros, scope)
                add_text(lead)
                out.extend(nodes)
            else:
                self.element(child, macros, scope)
                out.append(child)
            if tail:
                add_text(self.string(tail, scope))
        parent[:] = out
        parent.text = head[0] or None

    def content(self, elem: Any) -> tuple[str, list[Any]]:
        """What replaces an element by its content: its text and children."""
        return elem.text or "", list(elem)

    def xacro(self, elem: Any, parent: Any, macros: Macros, scope: Scope) -> tuple[str, list[Any]]:
        """What the xacro element ``elem`` becomes: (text, elements)."""
        tag = local_name(elem.tag)
        if tag == "property":
            self.property(elem, scope)
        elif tag == "macro":
            self.define(elem, macros)
        elif tag == "arg":
            name, default = _required(elem, "name"), elem.get("default")
            if default is None:
                raise XacroError("<xacro:arg> needs a default")
            if name not in self.args:
                self.args[name] = self.string(default, scope)
        elif tag in ("if", "unless"):
            condition = _required(elem, "value")
            keep = boolean(self.text(condition, scope), condition) == (tag == "if")
            if keep:
                self.children(elem, macros, scope)
                return self.content(elem)
        elif tag == "include":
            return self.include(elem, macros, scope)
        elif tag == "insert_block":
            name = _required(elem, "name")
            key = next((k for k in ("**" + name, "*" + name) if k in scope), None)
            if key is None:
                raise XacroError(f"undefined block {name!r}")
            block = self.grow(scope.lookup(key))
            if key.startswith("**"):
                self.children(block, macros, scope)
                return self.content(block)
            self.element(block, macros, scope)
            return "", [block]
        elif tag == "element":
            name = self.string(_required(elem, "name", xacro_ns=True), scope)
            if not name or not re.fullmatch(r"[A-Za-z_][\w.\-]*", name):
                raise XacroError(f"<xacro:element> needs a valid element name, got {name!r}")
            for key in [k for k in elem.attrib if _is_xacro(k)]:
                del elem.attrib[key]
            elem.tag = name
            self.element(elem, macros, scope)
            return "", [elem]
        elif tag == "attribute":
            name = self.string(_required(elem, "name"), scope)
            if not name:
                raise XacroError("<xacro:attribute> needs a name")
            parent.set(name, self.string(_required(elem, "value"), scope))
        else:
            return self.call(elem, tag, macros, scope)
        return "", []

    def property(self, elem: Any, scope: Scope) -> None:
        name = self.text(_required(elem, "name"), scope)
        if not valid_name(name):
            raise XacroError(f"the property name {name!r} is not a valid name")
        value, default = elem.get("value"), elem.get("default")
        remove = boolean(self.text(elem.get("remove", "false"), scope), "remove")
        if sum([value is not None, default is not None, remove]) > 1:
            raise XacroError(f"property {name!r}: value, default and remove exclude each other")
        if remove:
            scope.remove(name)
            return
        if default is not None:
            if name in scope:
                return
            value = default
        stored: Any = value
        key = name
        if value is None:  # a block property: its content, inserted by <xacro:insert_block>
            key, stored = "**" + name, elem
        lazy = boolean(self.text(elem.get("lazy_eval", "true"), scope), "lazy_eval")
        where = elem.get("scope")
        target = scope
        if where == "global":
            target, lazy = scope.top(), False
        elif where == "parent":
            if scope.parent is None:
                return  # xacro warns and ignores it
            target, lazy = scope.parent, False
            if not scope.namespace:
                while target.namespace and target.parent is not None:
                    target = target.parent
        if not lazy and isinstance(stored, str):
            stored = self.text(stored, scope)
        target.set(key, stored, lazy=lazy)

    def define(self, elem: Any, macros: Macros) -> None:
        name = _required(elem, "name")
        if name.startswith("xacro:"):
            name = name[6:]
        if name == "call" or "." in name or not name:
            raise XacroError(f"{name!r} cannot name a macro")
        params, defaults = parse_params(elem.get("params", ""))
        macros.table[name] = Macro(name, params, defaults, elem, self.where(elem))

    def resolve(self, name: str, macros: Macros, scope: Scope) -> tuple[Macro, Macros, Scope]:
        found = macros.find(name)
        if found is not None:
            return found, macros, scope
        *spaces, last = name.split(".")
        for space in spaces if spaces else [None]:
            inner = macros.namespace(space) if space else None
            value = scope.lookup(space) if space and space in scope else None
            if inner is None or not isinstance(value, Scope):
                break
            macros, scope = inner, value
        else:
            found = macros.find(last) if spaces else None
            if found is not None:
                return found, macros, scope
        known = f"<xacro:{name}>"
        raise XacroError(f"unknown xacro element or macro {known}")

    def call(self, elem: Any, name: str, macros: Macros, scope: Scope) -> tuple[str, list[Any]]:
        if name == "call":
            name = self.string(_required(elem, "macro"), scope)
            del elem.attrib["macro"]
        if name in _XACRO_TAGS:
            raise XacroError(f"<xacro:{name}> is malformed")
        macro, where_macros, where_scope = self.resolve(name, macros, scope)
        body = self.grow(macro.body)
        local = Scope(where_scope)
        params = list(macro.params)
        for attr, value in list(elem.attrib.items()):
            if attr == LINE or _is_xacro(attr):
                continue
            if attr not in params:
                raise XacroError(
                    f"macro {name!r} has no parameter {attr!r} (it takes {macro.params})"
                )
            params.remove(attr)
            local.set(attr, self.text(value, scope), lazy=False)
        self.children(elem, macros, scope)  # blocks are expanded where the call is
        blocks = list(elem)
        for param in [p for p in params if p.startswith("*")]:
            if not blocks:
                raise XacroError(f"macro {name!r} needs a block for {param!r}")
            local.set(param, blocks.pop(0), lazy=False)
            params.remove(param)
        if blocks:
            raise XacroError(
                f"macro {name!r} got a block it has no parameter for (<{blocks[0].tag}>)"
            )
        for param in list(params):
            forward, default = macro.defaults.get(param, (False, None))
            if forward and param in scope:
                local.set(param, scope.lookup(param), lazy=False)
            elif default is not None:
                local.set(param, self.text(default, scope), lazy=False)
            elif forward:
                raise XacroError(f"macro {name!r}: no property {param!r} to forward (^)")
            else:
                continue
            params.remove(param)
        if params:
            raise XacroError(f"macro {name!r} called without its parameters {', '.join(params)}")
        self.depth += 1
        if self.depth > MAX_DEPTH:
            raise XacroError(f"macro calls nested deeper than {MAX_DEPTH}: refused")
        self.children(body, Macros(where_macros), local)
        self.depth -= 1
        return self.content(body)

    def include(self, elem: Any, macros: Macros, scope: Scope) -> tuple[str, list[Any]]:
        spec = self.string(_required(elem, "filename"), scope)
        optional = boolean(self.text(elem.get("optional", "false"), scope), "optional")
        space = elem.get("ns")
        if space:
            space = self.string(space, scope)
            if not valid_name(space):
                raise XacroError(f"the include's namespace {space!r} is not a valid name")
            inner = Scope(scope, namespace=True)
            scope.set(space, inner, lazy=False)
            macros.namespaces[space] = inner_macros = Macros()
            scope, macros = inner, inner_macros
        path = self.current_dir() / spec
        if any(c in spec for c in "*?["):
            raise XacroError(f"includes by pattern ({spec!r}) are not supported")
        real = self.readable(path, "the included file")
        if real in (self.files[i].resolve() for i in self.stack):
            chain = " -> ".join(str(self.files[i]) for i in self.stack)
            raise XacroError(f"include cycle: {chain} -> {path}")
        if optional and not real.exists():
            return "", []
        root = self.parse_file(path)
        self.stack.append(len(self.files) - 1)
        self.element(root, macros, scope)
        self.stack.pop()
        return self.content(root)


def _required(elem: Any, name: str, *, xacro_ns: bool = False) -> str:
    if xacro_ns:  # xacro:name, in xacro's namespace
        found = (v for k, v in elem.attrib.items() if _is_xacro(k) and k.endswith("}" + name))
        value = next(found, None)
    else:
        value = elem.get(name)
    if value is None:
        raise XacroError(f"<xacro:{local_name(elem.tag)}> needs the attribute {name!r}")
    return str(value)


def expand(
    path: str | os.PathLike[str],
    *,
    max_bytes: int,
    max_nodes: int,
    time_limit: float,
    env: bool = False,
    packages: PackageMap | None = None,
    args: Mapping[str, str] | None = None,
) -> Any:
    """The URDF element tree that the xacro file ``path`` expands to.

    Args:
        path: The xacro file.
        max_bytes: Largest file read and most characters of text made, each.
        max_nodes: Most XML elements made by macro calls, blocks and includes.
        time_limit: Seconds the expansion may take.
        env: Allow ``$(env ...)`` and ``$(optenv ...)``.
        packages: Where ``$(find pkg)`` looks (default: the rules of
            :class:`PackageMap` without user folders).
        args: Values of the file's ``<xacro:arg>`` (text), over their defaults.

    Returns:
        The root element (an ``xml.etree.ElementTree.Element``).

    Raises:
        RobotFileError: one line naming the file, the line and the problem.
    """
    p = Path(path)
    source = str(p)
    folder = p.resolve().parent
    pmap = packages if packages is not None else PackageMap(start=p)
    roots = [folder] + [f for f in [pmap.own_folder()] if f is not None]
    run = _Expander(
        pmap,
        env=env,
        max_nodes=max_nodes,
        max_chars=max_bytes,
        deadline=time.monotonic() + time_limit,
        roots=roots,
    )
    run.args.update(args or {})
    try:
        root = run.parse_file(p)
        run.stack.append(0)
        run.element(root, Macros(), Scope(None, run.text))
    except MissingPackageError as exc:
        raise missing_package(exc.name, f"{run.where(run.current)}") from exc
    except XacroError as exc:
        raise RobotFileError(str(exc), path=run.where(run.current)) from exc
    except RobotFileError:
        raise
    except KinematicaError as exc:
        raise RobotFileError(str(exc), path=run.where(run.current)) from exc
    except RecursionError as exc:
        raise RobotFileError("the xacro file nests too deeply: refused", path=source) from exc
    except OSError as exc:
        raise RobotFileError(f"cannot read a file: {os_reason(exc)}", path=source) from exc
    for elem in root.iter():
        elem.attrib.pop(LINE, None)
    return root
