"""The README's Python snippets run as written, and it names no path outside the repository."""

from __future__ import annotations

import re
from pathlib import Path

README = Path(__file__).resolve().parents[1] / "README.md"


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
        'python3.11 -m pip install -e . && python3.11 -m psdbound fit',
        'python3.11 -m pip install -e ".[test]" && python3.11 -m pytest -q',
    ]
    assert "../shared" not in text and "method.md" not in text
    for image in re.findall(r"!\[[^]]*\]\(([^)]+)\)", text):
        assert (README.parent / image).is_file(), image
