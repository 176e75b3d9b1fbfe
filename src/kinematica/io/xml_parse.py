"""Parsing untrusted XML (URDF, xacro, package.xml) with defusedxml, one error per problem.

Entity declarations (the "billion laughs" bomb and its relatives), external
entities and DTD-based tricks are refused with a clear error instead of being
expanded. The xacro expander asks for each element's line too, to name it in
its errors: it is kept in the private attribute :data:`LINE` of the element.
"""

from __future__ import annotations

from typing import Any, Final

from kinematica.errors import RobotFileError

__all__ = ["LINE", "local_name", "parse_xml"]

#: Attribute holding an element's source line (``"FILE_INDEX:LINE"``) when asked for;
#: a namespace of its own, so no file's attribute can be mistaken for it.
LINE: Final = "{urn:kinematica:source}line"


def local_name(tag: object) -> str:
    """An element's tag without its ``{namespace}``."""
    text = str(tag)
    return text.rsplit("}", 1)[-1] if text.startswith("{") else text


def _line_target(prefix: str) -> Any:
    """A tree builder that writes each element's line into its :data:`LINE` attribute."""
    from xml.etree.ElementTree import TreeBuilder

    class Builder(TreeBuilder):
        parser: Any = None

        def start(self, tag: Any, attrs: dict[str, str]) -> Any:
            line = self.parser.parser.CurrentLineNumber if self.parser is not None else 0
            return super().start(tag, {**attrs, LINE: f"{prefix}:{line}"})

    return Builder()


def parse_xml(data: bytes, source: str | None, *, hint: str = "", lines: str | None = None) -> Any:
    """The root element of ``data``, parsed by defusedxml (no entities, no external refs).

    Args:
        data: The file's bytes.
        source: The file, for messages.
        hint: Added to a "not valid XML" message of a file that holds ``xacro:``.
        lines: Record each element's line in its :data:`LINE` attribute, as
            ``"{lines}:{line}"``; None records nothing.

    Raises:
        RobotFileError: not XML, or hostile XML; one line naming the file.
    """
    import defusedxml
    from defusedxml import ElementTree as SafeET

    def fail(message: str) -> RobotFileError:
        return RobotFileError(message, path=source)

    try:
        if lines is None:
            return SafeET.fromstring(
                data, forbid_dtd=False, forbid_entities=True, forbid_external=True
            )
        target = _line_target(lines)
        parser = SafeET.DefusedXMLParser(
            target=target, forbid_dtd=False, forbid_entities=True, forbid_external=True
        )
        target.parser = parser
        parser.feed(data)
        return parser.close()
    except defusedxml.EntitiesForbidden as exc:
        raise fail(
            f"the XML declares an entity ({exc.name!r}): refused, since entity expansion is how "
            "XML bombs work and a URDF needs none"
        ) from exc
    except defusedxml.ExternalReferenceForbidden as exc:
        raise fail(
            f"the XML refers to an external resource ({exc.sysid or exc.pubid!r}): refused, "
            "a URDF is read on its own"
        ) from exc
    except defusedxml.DefusedXmlException as exc:
        raise fail(f"the XML uses a forbidden construct: {exc}") from exc
    except SafeET.ParseError as exc:
        line, column = getattr(exc, "position", (0, 0))
        what = str(exc).split(":")[0]
        if hint and b"xacro:" in data:
            raise fail(f"not valid XML ({what}): it looks like a xacro file; {hint}") from exc
        raise fail(f"not valid XML: {what} (line {line}, column {column + 1})") from exc
    except RecursionError as exc:  # pragma: no cover - expat does not recurse; defensive
        raise fail("the XML is nested too deeply") from exc
