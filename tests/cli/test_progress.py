"""Progress on stderr: redrawn on a terminal, plain lines in a log (issue 32)."""

from __future__ import annotations

import io

from psdbound.common.progress import counter


class _Tty(io.StringIO):
    def isatty(self) -> bool:
        return True


def test_a_log_gets_plain_lines_at_each_tenth_and_the_end():
    out = io.StringIO()
    p = counter("station-days computed", stream=out)
    for k in range(1, 101):
        p(k, 100)
    text = out.getvalue()
    assert "\r" not in text
    lines = text.splitlines()
    # the first step says it started, then each tenth
    assert len(lines) == 11 and lines[0] == "  1/100 station-days computed"
    assert lines[-1] == "  100/100 station-days computed"


def test_a_terminal_gets_one_line_redrawn():
    out = _Tty()
    p = counter("days", stream=out)
    for k in range(1, 4):
        p(k, 3)
    assert out.getvalue() == "\r  1/3 days\r  2/3 days\r  3/3 days\n"
