"""The ``cusp-scene-schema`` directive: the scene schema reference, generated at build time.

Everything in the tables is read from the code that checks a scene: the sections and their
keys from :mod:`cusp.app.scene`, the bodies and their parameters (unit, allowed range,
required or all-or-none) from the body registry :mod:`cusp.models.registry`, the limits from
:mod:`cusp.app.limits`. A key added to the schema appears here without editing a page;
``tests/test_docs.py`` checks that every key the parser accepts is in the generated text.
"""

from __future__ import annotations

from collections.abc import Iterable

from cusp.app import limits, scene
from cusp.models import registry


def _table(title: str, header: Iterable[str], rows: Iterable[Iterable[str]]) -> list[str]:
    """A reST list-table (each cell one line of text)."""
    out = [f".. list-table:: {title}", "   :header-rows: 1", ""]
    for row in (list(header), *map(list, rows)):
        out.append(f"   * - {row[0] or '..'}")
        out += [f"     - {cell}" if cell else "     -" for cell in row[1:]]
    return [*out, ""]


def _lit(value: object) -> str:
    return f"``{value}``"


def _number_row(p: registry.Parameter, how: str) -> list[str]:
    return [_lit(p.name), p.unit or "1", p.range_text() or "any finite", how, p.description]


def _sections() -> list[str]:
    rows = []
    order = ("scene", "surface", "loading", "options", "solver", "manifold", "output")
    for name in (*order, *sorted(set(scene._SECTIONS) - set(order))):
        if name == "surface":
            listed = f"{_lit('model')} and the parameters of its body (below)"
        elif name == "sweep":
            listed = (
                'the varied fields by their dotted names (``"surface.mu" = [...]`` or '
                "``{ start, stop, num, spacing }``), or ``cases`` (a CSV file): see Sweeps"
            )
        else:
            listed = ", ".join(_lit(k) for k in sorted(scene._section_keys(name)))
        required = "required" if name in scene._REQUIRED_SECTIONS else "optional"
        rows.append([f"``[{name}]``", required, listed])
    return _table("Sections", ["section", "", "keys"], rows)


def _bodies() -> list[str]:
    rows = []
    for name in registry.body_names():
        entry = registry.body_entry(name)
        rows.append(
            [
                _lit(name),
                entry.description,
                "yes" if entry.has_path else f"no: {entry.refusal}",
            ]
        )
    out = _table("[surface] model: the registered bodies", ["model", "body", "a path"], rows)
    for name in registry.body_names(with_path=True):
        entry = registry.body_entry(name)
        rows = [_number_row(p, "required") for p in entry.required]
        rows += [_number_row(p, f"all or none ({entry.optional_name})") for p in entry.optional]
        out += _table(
            f'[surface] of model = "{name}"',
            ["key", "unit", "allowed", "", "meaning"],
            rows,
        )
    return out


def _numbers() -> list[str]:
    rows = []
    for section in ("loading", "solver"):
        for key in sorted(scene._section_keys(section)):
            p = scene._NUMBERS[key]
            how = "required" if section == "loading" else "optional"
            rows.append([f"``[{section}] {key}``", *_number_row(p, how)[1:]])
    return _table("[loading] and [solver]", ["key", "unit", "allowed", "", "meaning"], rows)


def _choices() -> list[str]:
    rows = [
        [
            "``[options] area_reading``",
            ", ".join(_lit(repr(r)) for r in scene.AREA_READINGS),
            _lit(repr(scene.AREA_READINGS[0])),
        ],
        [
            "``[manifold] parameter``",
            ", ".join(
                f"{_lit(repr(k))} ({f'[{u}]' if u else 'no unit'})"
                for k, u in scene.MANIFOLD_PARAMETERS.items()
            ),
            "(required with [manifold])",
        ],
        [
            "``[manifold] range``",
            "two numbers [low, high], 0 < low < high, holding the scene's value",
            "(required with [manifold])",
        ],
        [
            "``[output] figures``",
            ", ".join(_lit(f) for f in scene.FIGURES)
            + "; "
            + ", ".join(_lit(f) for f in scene.MANIFOLD_FIGURES)
            + " with [manifold] only",
            ", ".join(_lit(f) for f in scene.DEFAULT_FIGURES)
            + "; with [manifold]: "
            + ", ".join(_lit(f) for f in scene.DEFAULT_MANIFOLD_FIGURES),
        ],
    ]
    return _table("Choices", ["key", "allowed", "default"], rows)


def _limits() -> list[str]:
    rows = [
        ["scene file size", f"{limits.MAX_SCENE_BYTES} bytes"],
        ["line length", f"{limits.MAX_LINE_CHARS} characters"],
        ["nesting of arrays and tables", str(limits.MAX_NESTING)],
        ["values in a list", str(limits.MAX_LIST)],
        ["cases (listed mu times listed reduced_normal_load)", str(limits.MAX_CASES)],
        ["``[scene] name``", f"{limits.MAX_NAME_CHARS} characters"],
        ["``[scene] title``", f"{limits.MAX_TITLE_CHARS} characters"],
    ]
    return _table("Limits", ["what", "at most"], rows)


def schema_rst() -> list[str]:
    """The whole reference as lines of reStructuredText."""
    return [*_sections(), *_bodies(), *_numbers(), *_choices(), *_limits()]


def setup(app):
    """Register the directive (sphinx and docutils are imported here only: the tests read
    :func:`schema_rst` without them)."""
    from docutils import nodes
    from docutils.statemachine import StringList
    from sphinx.util.docutils import SphinxDirective

    class SceneSchema(SphinxDirective):
        """``.. cusp-scene-schema::``: the tables of :func:`schema_rst`, parsed in place."""

        has_content = False

        def run(self) -> list[nodes.Node]:
            container = nodes.container()
            lines = StringList(schema_rst(), source="cusp-scene-schema")
            self.state.nested_parse(lines, self.content_offset, container)
            return container.children

    app.add_directive("cusp-scene-schema", SceneSchema)
    return {"version": "1", "parallel_read_safe": True, "parallel_write_safe": True}
