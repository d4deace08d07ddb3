"""``.. aliasing-cli::``: the command-line reference, walked from :func:`aliasing.cli.build_parser`.

Every subcommand gets a section with its usage line, description, epilog and a table of every
positional argument and option (flags, metavar, choices, default, help), so the page cannot
drift from the parser.
"""

from __future__ import annotations

import argparse
import re

from docutils import nodes
from docutils.statemachine import StringList
from sphinx.application import Sphinx
from sphinx.util.docutils import SphinxDirective


def _esc(text: str) -> str:
    return text.replace("\\", "\\\\").replace("*", "\\*").replace("`", "\\`").replace("|", "\\|").replace("_", "\\_")


_FLAG = re.compile(r"(?<![\w`-])(--?[a-zA-Z][\w-]*)")


def _text(text: str) -> str:
    """Help text as reST: escaped, with option names as code (else smart quotes turn -- into –)."""
    return _FLAG.sub(r"\\ ``\1``\\ ", _esc(" ".join(text.split())))  # "\ ": literals may touch text


def _rows(parser: argparse.ArgumentParser) -> list[tuple[str, str]]:
    rows = []
    for act in parser._actions:  # argparse has no public walk over its actions
        if isinstance(act, (argparse._HelpAction, argparse._SubParsersAction)):
            continue
        if act.option_strings:
            flag = ", ".join(act.option_strings)
            if act.nargs != 0:
                flag += " " + (act.metavar or act.dest.upper())
        else:
            flag = act.metavar or act.dest
        text = act.help or ""
        if act.choices:
            text += f" Choices: {', '.join(map(str, act.choices))}."
        if act.default not in (None, False, [], argparse.SUPPRESS) and "default" not in text:
            text += f" Default: {act.default}."
        rows.append((flag, text))
    return rows


def cli_rst(parser: argparse.ArgumentParser) -> list[str]:
    sub = next(a for a in parser._actions if isinstance(a, argparse._SubParsersAction))
    helps = {c.dest: c.help for c in sub._choices_actions}
    lines: list[str] = []
    for name, p in sub.choices.items():
        title = f"aliasing {name}"
        lines += [f".. _cli-{name}:", "", title, "-" * len(title), ""]
        if helps.get(name):
            lines += [_text(helps[name]), ""]
        lines += ["::", ""] + ["   " + u for u in p.format_usage().strip().splitlines()] + [""]
        for block in (p.description, p.epilog):
            if block:
                lines += [_text(block), ""]
        lines += [".. list-table::", "   :header-rows: 1", "   :widths: 30 70", "",
                  "   * - argument", "     - meaning"]
        for flag, text in _rows(p):
            lines += [f"   * - ``{flag}``", f"     - {_text(text) or '—'}"]
        lines.append("")
    return lines


class AliasingCli(SphinxDirective):
    """Insert the generated reference of every ``aliasing`` subcommand."""

    has_content = False

    def run(self) -> list[nodes.Node]:
        from aliasing.cli import build_parser

        node = nodes.section()
        node.document = self.state.document
        self.state.nested_parse(StringList(cli_rst(build_parser()), source="aliasing.cli"), 0, node,
                                match_titles=True)
        return node.children


def setup(app: Sphinx) -> dict:
    app.add_directive("aliasing-cli", AliasingCli)
    # the parser lives in several modules: re-read the pages using the directive on every build
    app.connect("env-get-outdated", lambda app, env, added, changed, removed:
                [d for d in env.found_docs if d == "cli"])
    return {"parallel_read_safe": True, "version": "1"}
