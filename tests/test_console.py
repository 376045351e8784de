"""The ``exuclear`` console command (exuclear/cli.py, ``[project.scripts]`` in pyproject.toml).

Each test runs the installed script in a real process where pip made it (next to the
interpreter), else ``python -m exuclear.cli``: the exit status and the exact stderr are
what a shell sees.
"""
from __future__ import annotations

import json
import os
import subprocess
import sys
from pathlib import Path

import pandas as pd
import pytest

from exuclear.cli import SUBCOMMANDS

_SCRIPT = Path(sys.executable).with_name("exuclear")
COMMAND = [str(_SCRIPT)] if _SCRIPT.exists() else [sys.executable, "-m", "exuclear.cli"]


def run(*args: str, cwd=None) -> subprocess.CompletedProcess:
    """The command's process; its stderr without the one-time KernelWarning that an install
    without a compiler gives at import (exuclear/engine/kernel.py), which is not the command's."""
    env = {**os.environ, "MPLBACKEND": "Agg"}
    done = subprocess.run([*COMMAND, *args], capture_output=True, text=True, timeout=120, cwd=cwd, env=env)
    done.stderr = "".join(line for line in done.stderr.splitlines(keepends=True) if "KernelWarning" not in line)
    return done


def test_help_lists_the_subcommands():
    done = run("--help")
    assert done.returncode == 0 and done.stderr == ""
    for name in SUBCOMMANDS:
        assert f"  {name} " in done.stdout


@pytest.mark.parametrize("args, says", [
    ((), "give a subcommand"),
    (("slider_crank",), "unknown subcommand 'slider_crank'"),
    (("slider-crank", "--cr", "2"), "`cr` must lie in (0.0, 1.0], got 2.0"),  # the scene's own check
    (("journal-bearing", "--no-such-option"), "unrecognized arguments: --no-such-option"),
])
def test_bad_input_exits_2_with_one_error_line(args, says):
    done = run(*args)
    assert done.returncode == 2
    lines = done.stderr.splitlines()
    assert len(lines) == 1 and lines[0].startswith("error: ") and says in lines[0], done.stderr
    assert done.stdout == ""


@pytest.mark.parametrize("subcommand", ["slider-crank", "journal-bearing"])
def test_scene_options_are_the_python_m_forms(subcommand):
    # the same parser: the help text of `exuclear X --help` is `python -m MODULE --help`'s
    module = SUBCOMMANDS[subcommand][0]
    ours = run(subcommand, "--help")
    theirs = subprocess.run([sys.executable, "-m", module, "--help"], capture_output=True, text=True, timeout=120)
    assert ours.returncode == theirs.returncode == 0
    assert ours.stdout == theirs.stdout and "--cr" in ours.stdout


def test_journal_bearing_runs_the_paper_impact():
    done = run("journal-bearing", "--cr", "0.9", "--json")
    assert done.returncode == 0, done.stderr
    summary = json.loads(done.stdout)
    # the paper's departure velocity at cr 0.9: 0.269 m/s (Wang et al. 2017, section 4.1);
    # 1e-3 m/s: the paper's rounding
    assert summary["success"] and abs(summary["departure_velocity"] - 0.269) < 1e-3


def test_study_writes_its_table(tmp_path):
    out = tmp_path / "study.csv"
    done = run("study", "journal-bearing", "--cr", "0.5,0.9", "--workers", "1", "--no-progress", "--out", str(out))
    assert done.returncode == 0, done.stderr
    assert "2 runs, 0 failed" in done.stdout
    table = pd.read_csv(out)
    assert sorted(table["cr"]) == [0.5, 0.9] and table["success"].all()


def test_study_without_a_scene_is_bad_input():
    done = run("study")
    assert done.returncode == 2  # python -m exuclear.study's own usage and status
