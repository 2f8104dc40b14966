"""The README's Python snippets and shell examples run as written; it names no outside path.

Shell examples are the ``python3.11 -m psdbound ...`` lines of its ```bash,
```sh and ```console blocks (a ``$ `` prompt is dropped; of an install line
``pip ... && python3.11 -m psdbound fit`` only the psdbound command runs). The
lines of a block run in order in one fresh folder, through bash, with
``python3.11`` being this interpreter and this checkout on ``PYTHONPATH``.
Station files are named ``"$RINEX"/NAME``; ``RINEX`` is the shared data's
``rinex`` folder (``PSDBOUND_SHARED_DATA``, see conftest.py), and a command that
names a file not there is not run (the test then skips, naming the file). Each command must exit 0,
or the code a trailing ``# exit N`` comment states.
"""

from __future__ import annotations

import os
import re
import subprocess
import sys
from pathlib import Path

import pytest
from conftest import SHARED_RINEX

REPO = Path(__file__).resolve().parents[1]
README = REPO / "README.md"


def test_readme_snippets_run(tmp_path, monkeypatch):
    blocks = re.findall(r"```python\n(.*?)```", README.read_text(), flags=re.S)
    assert len(blocks) >= 2
    monkeypatch.chdir(tmp_path)
    namespace: dict = {}
    for code in blocks:  # in order: the later blocks use what the first wrote
        exec(compile(code, str(README), "exec"), namespace)  # noqa: S102
    assert (tmp_path / "reports" / "demo-lib" / "result.json").is_file()
    ss = namespace["ss"]  # the error model's state-space export, every correlated component
    assert ss.states[0] == "gauss_markov" and all(0.0 < p < 1.0 for p in ss.phi.diagonal())


def test_readme_starts_with_the_two_commands_and_stays_inside_the_repository():
    text = README.read_text()
    first = re.search(r"```bash\n(.*?)```", text, flags=re.S).group(1).strip().splitlines()
    assert first == [
        "python3.11 -m pip install -e . && python3.11 -m psdbound fit",
        'python3.11 -m pip install -e ".[test]" && python3.11 -m pytest -q',
    ]
    assert "../shared" not in text and "method.md" not in text
    for image in re.findall(r"!\[[^]]*\]\(([^)]+)\)", text):
        assert (README.parent / image).is_file(), image


_COMMAND = re.compile(r"python3\.11 -m psdbound\b.*")
_EXIT = re.compile(r"\s+#\s*exit (\d+)\b.*$")


def _shell_blocks() -> list[list[tuple[str, int]]]:
    """Per shell block of the README: its psdbound commands and the exit code each must give."""
    out = []
    for body in re.findall(r"```(?:bash|sh|console)\n(.*?)```", README.read_text(), flags=re.S):
        cmds = []
        for line in body.splitlines():
            m = _COMMAND.search(line.removeprefix("$ "))
            if not m:
                continue
            cmd, code = m.group(0), 0
            if e := _EXIT.search(cmd):
                cmd, code = cmd[: e.start()], int(e.group(1))
            cmds.append((cmd.strip(), code))
        if cmds:
            out.append(cmds)
    return out


def _params():
    for k, cmds in enumerate(_shell_blocks()):
        heavy = any("$RINEX" in c or " campaign " in c for c, _ in cmds)
        name = f"{k}-" + "-".join(c.split()[3] for c, _ in cmds)
        yield pytest.param(cmds, id=name, marks=[pytest.mark.slow] if heavy else [])


def test_readme_shell_examples_are_found():
    blocks = _shell_blocks()
    commands = [c for b in blocks for c, _ in b]
    assert commands[0] == "python3.11 -m psdbound fit"  # of the install line
    for sub in ("fit", "export", "simulate", "campaign", "overbound", "budget"):
        assert any(c.split()[3] == sub for c in commands), sub
    for c in commands:  # station files through $RINEX, so that the test can find them
        assert not re.search(r"(?<![/\w])[A-Z0-9]{4}\w*\.(crx|rnx|\d\d[on])\.gz", c), c


@pytest.mark.parametrize("commands", list(_params()))
def test_readme_shell_examples_run(commands, tmp_path):
    env = {
        **os.environ,
        "RINEX": str(SHARED_RINEX),
        "MPLBACKEND": "Agg",
        "PYTHONPATH": os.pathsep.join([str(REPO), os.environ.get("PYTHONPATH", "")]),
    }
    missing = []
    for cmd, code in commands:
        absent = [
            n for n in re.findall(r'"\$RINEX"/(\S+)', cmd) if not (SHARED_RINEX / n).is_file()
        ]
        if absent:  # a command on station files runs only where they are
            missing.append(str(SHARED_RINEX / absent[0]))
            continue
        line = cmd.replace("python3.11", f'"{sys.executable}"', 1)
        r = subprocess.run(
            ["bash", "-c", line],
            cwd=tmp_path,
            env=env,
            capture_output=True,
            text=True,
            timeout=900,
            stdin=subprocess.DEVNULL,
        )
        assert r.returncode == code, f"{cmd}: exit {r.returncode}, README says {code}\n{r.stderr}"
    if missing:
        pytest.skip(f"real data not available: {', '.join(missing)}")
