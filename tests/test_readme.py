"""The README's example runs as printed and gives what its comment says.

Reference: the paper's departure velocity 0.269 m/s at cr 0.9 (docs/physics.md section
6.1); the README quotes 0.2688 m/s, the library's value to four digits.
"""
import contextlib
import io
import pathlib
import re

import pytest

README = pathlib.Path(__file__).resolve().parents[1] / "README.md"


def test_the_readme_example_runs_and_prints_the_departure_velocity(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)  # Exudyn writes its solution file to the working directory
    block = re.search(r"```python\n(.*?)```", README.read_text(encoding="utf-8"), re.S).group(1)
    printed = io.StringIO()
    with contextlib.redirect_stdout(printed):
        exec(compile(block, str(README), "exec"), {})
    first, impacts = printed.getvalue().splitlines()[:2]
    assert float(first) == pytest.approx(-0.2688, abs=5e-5)
    assert impacts.startswith("[ImpactRecord(onset_time=0.0, onset_velocity=0.3")  # one impact, touching at t = 0
