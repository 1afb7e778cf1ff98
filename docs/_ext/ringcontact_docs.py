"""Sphinx directives that generate the reference pages from the code (nothing here is hand-written).

- ``.. ringcontact-api:: PACKAGE``: one ``automodule`` section per public module of PACKAGE (a module
  whose dotted name has no part starting with ``_``), found on disk, so a new module is documented
  without editing the docs;
- ``.. ringcontact-cli::``: every job of ``reports.cli.JOBS``, every sub-command and every option with
  its help, read from the argparse parsers themselves (:mod:`cli_parsers`);
- ``.. ringcontact-ranges::``: the plausible range of every physical input (:mod:`contact.plausible`);
- ``.. ringcontact-scene-keys::``: every table and key of a rotor scene TOML file, from the same
  generator as ``docs/scene.schema.json`` (:mod:`scene_schema`);
- ``.. ringcontact-fem-scenes::``: the named boundary-condition scenes of :mod:`fem_reference.scenes`;
- ``.. ringcontact-gallery::``: every ``docs/examples/*.py``, its docstring as text, its code, and its
  printed output and figure, run at build time (``docs/_ext/gallery_run.py``).
"""
from __future__ import annotations

import ast
from pathlib import Path

from docutils import nodes
from docutils.parsers.rst import Directive
from docutils.statemachine import StringList
from sphinx.util.nodes import nested_parse_with_titles

DOCS = Path(__file__).resolve().parents[1]
ROOT = DOCS.parent


def _parse_rst(directive: Directive, lines: list[str]) -> list[nodes.Node]:
    """Parse generated reStructuredText (sections allowed) in the directive's context."""
    node = nodes.section()
    node.document = directive.state.document
    source = directive.state.document.current_source or "<generated>"
    nested_parse_with_titles(directive.state, StringList(lines, source=source), node)
    return node.children


def _heading(text: str, char: str) -> list[str]:
    return [text, char * max(len(text), 3), ""]


def _text(text: str) -> nodes.paragraph:
    return nodes.paragraph("", "", nodes.Text(text))


def _table(header: list[str], rows: list[list[str]], widths: list[int] | None = None) -> nodes.table:
    """A docutils table of plain text cells (no markup is interpreted inside cells)."""
    widths = widths or [1] * len(header)
    table = nodes.table()
    group = nodes.tgroup(cols=len(header))
    table += group
    for w in widths:
        group += nodes.colspec(colwidth=w)

    def row(cells: list[str]) -> nodes.row:
        r = nodes.row()
        for c in cells:
            entry = nodes.entry()
            entry += nodes.paragraph("", "", nodes.Text(c))
            r += entry
        return r

    head = nodes.thead()
    head += row(header)
    body = nodes.tbody()
    for cells in rows:
        body += row(cells)
    group += head
    group += body
    return table


# ------------------------------------------------------------------------------------------------
# API
# ------------------------------------------------------------------------------------------------
def public_modules(package: str) -> list[str]:
    """Dotted names of ``package`` and its public modules, packages before their modules."""
    base = ROOT / package
    out = []
    for path in sorted(base.rglob("*.py")):
        parts = path.relative_to(ROOT).with_suffix("").parts
        if parts[-1] == "__init__":
            parts = parts[:-1]
        if any(p.startswith("_") for p in parts) or "published" in parts:
            continue
        out.append(".".join(parts))
    return sorted(out, key=lambda m: (m.count(".") > 0, m))


def _is_package(module: str) -> bool:
    return (ROOT / module.replace(".", "/") / "__init__.py").is_file()


class ApiDirective(Directive):
    """``.. ringcontact-api:: PACKAGE``."""
    required_arguments = 1

    def run(self):
        lines: list[str] = []
        for mod in public_modules(self.arguments[0]):
            lines += _heading(f"``{mod}``", "-")
            lines += [f".. automodule:: {mod}"]
            # a package's docstring only: its re-exports are documented where they are defined
            lines += ["   :no-members:" if _is_package(mod) else "   :members:", ""]
        return _parse_rst(self, lines)


# ------------------------------------------------------------------------------------------------
# CLI
# ------------------------------------------------------------------------------------------------
def _parser_nodes(directive: Directive, command: str, parser, level: str) -> list[nodes.Node]:
    from cli_parsers import arguments, subparsers

    out = _parse_rst(directive, _heading(f"``{command}``", level))
    sec = out[0]
    if parser.description:
        sec += _text(parser.description)
    sec += nodes.literal_block(text=parser.format_usage().strip())
    rows = [[arg.name, arg.value, arg.default, arg.help] for arg in arguments(parser)]
    if rows:
        sec += _table(["argument", "value", "default", "help"], rows, [18, 16, 12, 54])
    for name, sub in subparsers(parser):
        sec += _parser_nodes(directive, f"{command} {name}", sub, "~" if level == "-" else "^")
    return out


class CliDirective(Directive):
    """``.. ringcontact-cli::``: the whole command line, from the parsers."""

    def run(self):
        from cli_parsers import job_parsers

        from reports.cli import JOBS
        out: list[nodes.Node] = []
        for job, (_, help_) in JOBS.items():
            parsers = job_parsers(job)
            sec = _parse_rst(self, _heading(f"``ringcontact {job}``", "-"))[0]
            sec += _text(help_)
            for command, parser in parsers:
                if command == f"ringcontact {job}":
                    sec += _parser_nodes(self, command, parser, "~")[0].children[1:]
                else:
                    sec += _parser_nodes(self, command, parser, "~")
            out.append(sec)
        return out


class RangesDirective(Directive):
    """``.. ringcontact-ranges::``: the table ``ringcontact --ranges`` prints."""

    def run(self):
        from contact.plausible import RANGES, range_text
        rows = [[name, range_text(name).removeprefix("in "), why] for name, (*_, why) in RANGES.items()]
        return [_table(["input", "plausible range", "why these bounds"], rows, [20, 20, 60])]


# ------------------------------------------------------------------------------------------------
# scene TOML reference, FEM scenes
# ------------------------------------------------------------------------------------------------
class SceneKeysDirective(Directive):
    """``.. ringcontact-scene-keys::``: one table of keys per TOML table of a rotor scene."""

    def run(self):
        from scene_schema import key_rows, scene_schema, table_rows
        schema = scene_schema()
        out: list[nodes.Node] = []
        sec = _parse_rst(self, _heading("Top level", "-"))[0]
        sec += _table(["key", "type", "required", "meaning"], key_rows(schema, top=True), [16, 12, 10, 62])
        out.append(sec)
        for title, description, rows in table_rows(schema):
            sec = _parse_rst(self, _heading(title, "-"))[0]
            if description:
                sec += _text(description)
            sec += _table(["key", "type / unit", "required / default", "allowed", "notes"], rows, [22, 12, 14, 22, 30])
            out.append(sec)
        return out


class SceneCrossChecksDirective(Directive):
    """``.. ringcontact-scene-cross-checks::``: what the parser checks beyond the schema."""

    def run(self):
        from scene_schema import CROSS_CHECKS
        items = nodes.bullet_list()
        for text in CROSS_CHECKS:
            items += nodes.list_item("", _text(text))
        return [items]


class FemScenesDirective(Directive):
    """``.. ringcontact-fem-scenes::``: the named FEM boundary-condition scenes and their rings."""

    def run(self):
        from fem_reference import scenes as fs
        named = [fs.clamped(), fs.clamped(plane="stress"), fs.persson(20.0)] + fs.paper_candidates()
        rows = []
        for s in named:
            r = s.rings
            rows.append([s.name, f"plane {s.plane}", fs.BEARING_DRIVES[s.bearing_drive], fs.SUPPORT_HOLDS[s.support_hold],
                         f"R_b {r.outer_radius_m * 1e3:g} mm (bore {r.inner_radius_m * 1e3:g} mm), "
                         f"support outer {r.support_outer_radius_m * 1e3:g} mm, δ0 {r.clearance_m * 1e3:g} mm, "
                         f"l0 {r.width_m * 1e3:g} mm"])
        out = [_table(["scene", "plane", "bearing driven", "support held", "rings"], rows, [22, 10, 26, 22, 28])]
        out.append(_text(f"Any ratio > 2 names a Persson plate (persson-<ratio>); {len(named)} scenes listed "
                         f"(fem_reference.scenes.by_name resolves each name)."))
        from fem_reference.solid.solve import SCENES
        out.append(_text("The 3D tilted-ring half model (fem_reference.solid.solve.SCENES) has its own scenes:"))
        out.append(_table(["3D scene", "boundary conditions"], [[k, v] for k, v in SCENES.items()], [26, 74]))
        return out


# ------------------------------------------------------------------------------------------------
# gallery
# ------------------------------------------------------------------------------------------------
def example_files() -> list[Path]:
    return sorted((DOCS / "examples").glob("*.py"))


class GalleryDirective(Directive):
    """``.. ringcontact-gallery::``: every worked example, its docstring then its code."""

    def run(self):
        from gallery_run import run_examples

        out: list[nodes.Node] = []
        results = run_examples(example_files())          # side by side: the build waits for the longest
        for path in example_files():
            text = path.read_text(encoding="utf-8")
            tree = ast.parse(text)
            doc = ast.get_docstring(tree) or path.stem
            if ast.get_docstring(tree):          # the docstring is shown as text above the code, not twice
                text = "\n".join(text.splitlines()[tree.body[0].end_lineno:]).lstrip("\n") + "\n"
            title, _, body = doc.partition("\n")
            self.state.document.settings.record_dependencies.add(str(path))
            lines = _heading(title.strip(), "-") + body.strip().splitlines() + [""]
            lines += [f"Run it from the repository root: ``python docs/examples/{path.name}`` (checked by "
                      "``tests/docs/test_gallery.py``).", ""]
            sec = _parse_rst(self, lines)[0]
            block = nodes.literal_block(text=text)
            block["language"] = "python"
            sec += block
            sec += self._result(path, results[path])
            out.append(sec)
        return out

    def _result(self, path: Path, run) -> list[nodes.Node]:
        """The example's printed output and its figure, run at build time (``gallery_run.run_examples``: the
        pair, or the exception its run raised)."""
        if isinstance(run, Exception):               # the build fails with the example's error
            return [self.state.document.reporter.error(f"gallery example {path.name}: {run}")]
        printed, png = run
        result: list[nodes.Node] = [nodes.paragraph(text="Output:")]
        shown = nodes.literal_block(text=printed.rstrip() + "\n")
        shown["language"] = "text"
        result.append(shown)
        if png is not None:
            rel = "/" + png.relative_to(DOCS).as_posix()
            result.append(nodes.image(uri=rel, alt=f"figure of {path.name}", classes=["gallery-figure"]))
        return result


def setup(app):
    app.add_directive("ringcontact-api", ApiDirective)
    app.add_directive("ringcontact-cli", CliDirective)
    app.add_directive("ringcontact-ranges", RangesDirective)
    app.add_directive("ringcontact-scene-keys", SceneKeysDirective)
    app.add_directive("ringcontact-scene-cross-checks", SceneCrossChecksDirective)
    app.add_directive("ringcontact-fem-scenes", FemScenesDirective)
    app.add_directive("ringcontact-gallery", GalleryDirective)
    return {"version": "1", "parallel_read_safe": True, "parallel_write_safe": True}
