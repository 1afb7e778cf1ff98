"""The argparse parsers of every ``ringcontact`` job, captured without running any job.

Each job builds its parser inside its entry function (``reports.cli.JOBS``). :func:`job_parsers`
calls the entry with an empty argument list while ``ArgumentParser.parse_args`` is replaced by a
function that raises :class:`_Captured` with the parser, so nothing after the parsing runs. A job
that dispatches its sub-commands by hand (``fem3d``: a ``SUBCOMMANDS`` table) is walked the same way,
one entry per sub-command. Sub-parsers made with ``add_subparsers`` are found by :func:`subparsers`.
"""
from __future__ import annotations

import argparse
import importlib
from dataclasses import dataclass
from unittest import mock


class _Captured(Exception):
    def __init__(self, parser: argparse.ArgumentParser):
        super().__init__(parser.prog)
        self.parser = parser


def _capture(entry) -> argparse.ArgumentParser:
    def grab(self, *args, **kwargs):
        raise _Captured(self)

    with mock.patch.object(argparse.ArgumentParser, "parse_args", grab), \
            mock.patch.object(argparse.ArgumentParser, "parse_known_args", grab):
        try:
            entry([])
        except _Captured as got:
            return got.parser
    raise RuntimeError(f"{entry.__module__}.{entry.__name__} returned without parsing its arguments")


def job_parsers(job: str) -> list[tuple[str, argparse.ArgumentParser]]:
    """``[(command, parser)]`` of a job: one entry, or one per hand-dispatched sub-command."""
    from reports.cli import JOBS

    module_name, _, func_name = JOBS[job][0].partition(":")
    module = importlib.import_module(module_name)
    table = getattr(module, "SUBCOMMANDS", None) if not func_name else None
    if table:
        return [(f"ringcontact {job} {name}", _capture(entry)) for name, entry in table.items()]
    return [(f"ringcontact {job}", _capture(getattr(module, func_name or "main")))]


def subparsers(parser: argparse.ArgumentParser) -> list[tuple[str, argparse.ArgumentParser]]:
    """The ``add_subparsers`` sub-commands of ``parser`` (aliases once)."""
    out, seen = [], set()
    for action in parser._actions:
        if isinstance(action, argparse._SubParsersAction):
            for name, sub in action.choices.items():
                if id(sub) not in seen:
                    seen.add(id(sub))
                    out.append((name, sub))
    return out


@dataclass(frozen=True)
class Argument:
    """One row of the CLI reference: the option strings (or the positional name), what it takes, its
    default and its help with ``%(default)s`` and friends expanded."""
    name: str
    value: str
    default: str
    help: str


def arguments(parser: argparse.ArgumentParser) -> list[Argument]:
    """Every argument of ``parser`` except ``--help`` and the sub-command selector."""
    fmt = parser._get_formatter()
    out = []
    for action in parser._actions:
        if isinstance(action, (argparse._HelpAction, argparse._SubParsersAction)) or action.help == argparse.SUPPRESS:
            continue
        name = ", ".join(action.option_strings) or action.metavar or action.dest
        if action.nargs == 0:
            value = "(flag)"
        elif action.choices is not None:
            value = "{" + ",".join(str(c) for c in action.choices) + "}"
        else:
            value = fmt._format_args(action, fmt._get_default_metavar_for_optional(action)
                                     if action.option_strings else fmt._get_default_metavar_for_positional(action))
        if action.required or not action.option_strings:
            default = "required" if action.nargs not in ("?", "*") else ""
        elif action.default in (None, False, argparse.SUPPRESS) or action.nargs == 0:
            default = ""
        elif isinstance(action.default, (list, tuple)):
            default = " ".join(str(v) for v in action.default)
        else:
            default = str(action.default)
        help_ = fmt._expand_help(action) if action.help else ""
        out.append(Argument(name, value, default, " ".join(help_.split())))
    return out
