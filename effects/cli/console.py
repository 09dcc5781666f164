"""The rich console every command prints through.

A reader that leaves (`effects validate ... | head -1`) must end the command as a closed pipe:
`effects.cli.main` answers BrokenPipeError with exit 141, as a process killed by SIGPIPE. rich's
own answer is `SystemExit(1)` (`Console.on_broken_pipe`), which made the commands that print
through rich exit 1 on a closed pipe while `--json`, printed plainly, exited 141.
"""
from __future__ import annotations

import errno

from rich.console import Console


class PipeConsole(Console):
    """rich's Console, with a closed pipe raised as BrokenPipeError for main to answer."""

    def on_broken_pipe(self) -> None:
        self.quiet = True      # rich's own first step: nothing more is written through it
        raise BrokenPipeError(errno.EPIPE, "the reader closed the pipe")


def make_console(**options) -> Console:
    """A `PipeConsole` (highlight off, as the commands print names, not Python values)."""
    options.setdefault("highlight", False)
    return PipeConsole(**options)
