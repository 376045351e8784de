"""The study runner (exuclear.study): parameter sets, the table on disk, failures,
interrupts and resumption, executors (serial, local processes, a real Dask LocalCluster)
giving equal rows, the scenes' study functions and the command line."""
from __future__ import annotations

import contextlib
import math
import os
import signal
from pathlib import Path

import numpy as np
import pandas as pd
import pytest

from exuclear import study as st
from exuclear.study.cli import _scene_of, _scene_parser
from exuclear.study.runner import _batch_size

# -- cheap study functions (module level: worker processes import them by name) -------------


def square(p: dict) -> dict:
    """x^2 k, an array, and a failure at x = 3."""
    if p["x"] == 3:
        raise RuntimeError("x = 3 is refused")
    return {"y": p["x"] ** 2 * p["k"], "pair": np.array([p["x"], p["k"]], dtype=float), "root": math.sqrt(p["x"])}


CALLS: list[int] = []


def interrupted_at_5(p: dict) -> dict:
    """Raises KeyboardInterrupt at x = 5 while the file ``p["stop"]`` exists (a Ctrl-C
    at a known point); counts its calls in this process."""
    CALLS.append(p["x"])
    if p["x"] == 5 and os.path.exists(p["stop"]):
        raise KeyboardInterrupt
    return {"y": 2.0 * p["x"]}


def sigint_at_2(p: dict) -> dict:
    """Sends this process a SIGINT (a Ctrl-C) during the run at x = 2, while ``p["stop"]`` exists."""
    CALLS.append(p["x"])
    if p["x"] == 2 and os.path.exists(p["stop"]):
        os.kill(os.getpid(), signal.SIGINT)
    return {"y": 3.0 * p["x"]}


def reports_failure(p: dict) -> dict:
    """Finishes every run; x = 1 fails its own criterion, with a message of two lines."""
    CALLS.append(p["x"])
    return {"y": float(p["x"]), "success": p["x"] != 1, "message": 'stopped early,\n"see" below' if p["x"] == 1 else ""}


def crashes_at_2(p: dict) -> dict:
    """Kills its worker process at x = 2 (as a segfault in compiled code would)."""
    if p["x"] == 2:
        os._exit(3)
    return {"y": p["x"] + 0.5}


def warns(p: dict) -> dict:
    """Warns as a scene does for a unit slip at x = 1 (twice: carried once), and a plain
    UserWarning at x = 2 (not carried: shown as usual)."""
    import warnings

    import exuclear

    if p["x"] == 1:
        for _ in range(2):
            warnings.warn("length 15 m: were they given in mm?", exuclear.UnitWarning, stacklevel=2)
    if p["x"] == 2:
        warnings.warn("not exuclear's", UserWarning, stacklevel=2)
    return {"y": float(p["x"]), "message": "own note" if p["x"] == 1 else ""}


def _values(df: pd.DataFrame) -> pd.DataFrame:
    """A table without its wall times, which are the only executor-dependent columns."""
    return df.drop(columns=[c for c in df.columns if "wall_time" in c])


# -- parameter sets ---------------------------------------------------------------------------


def test_parse_values():
    assert st.parse_values("0.3:0.9:0.2") == [0.3, 0.5, 0.7, 0.9]  # stop on the grid is included, no 0.5000000000000001
    assert st.parse_values("200:5000:50") == list(range(200, 5001, 50))  # integers stay integers: 97 speeds
    assert st.parse_values("5e-5,1e-4,2e-4") == [5e-5, 1e-4, 2e-4]
    assert st.parse_values("steel,aluminium") == ["steel", "aluminium"]
    assert st.parse_values("none,coulomb:0.1") == ["none", "coulomb:0.1"]  # not numbers: not a range
    assert st.parse_values("0.25") == [0.25]
    for bad in ("1:0:0.1", "0:1:0", "0:1", "0:1:2:3", "1,,2", ""):
        with pytest.raises(ValueError):
            st.parse_values(bad)


def test_grid_order_and_empty_axis():
    runs = st.grid(cr=[0.3, 0.9], rpm=[500, 1000, 1500], law="wang-liu")
    assert len(runs) == 6
    assert runs[0] == {"cr": 0.3, "rpm": 500, "law": "wang-liu"} and runs[1]["rpm"] == 1000  # last axis fastest
    with pytest.raises(ValueError, match="`rpm` are empty"):
        st.grid(cr=[0.3], rpm=[])


def test_sample_seeded_latin_hypercube():
    a = st.sample({"cr": (0.3, 0.9), "clearance": (1e-5, 1e-3)}, 8, seed=4, log=["clearance"], fixed={"law": "flores"})
    b = st.sample({"cr": (0.3, 0.9), "clearance": (1e-5, 1e-3)}, 8, seed=4, log=["clearance"], fixed={"law": "flores"})
    assert a == b  # same seed, same sets
    assert a != st.sample({"cr": (0.3, 0.9), "clearance": (1e-5, 1e-3)}, 8, seed=5, log=["clearance"])
    # Latin hypercube: each of the 8 strata of each axis holds exactly one point
    cr_strata = sorted(int((r["cr"] - 0.3) / 0.6 * 8) for r in a)
    c_strata = sorted(int((math.log(r["clearance"]) - math.log(1e-5)) / math.log(100) * 8) for r in a)
    assert cr_strata == list(range(8)) and c_strata == list(range(8))
    assert all(r["law"] == "flores" for r in a)
    with pytest.raises(ValueError, match="low < high"):
        st.sample({"cr": (0.9, 0.3)}, 4, seed=0)


def test_run_id_depends_on_values_only():
    assert st.run_id({"a": 1.0, "b": "x"}) == st.run_id({"b": "x", "a": np.float64(1.0)})
    assert st.run_id({"a": 1.0}) != st.run_id({"a": 1.0 + 1e-15})  # floats are compared exactly


# -- the table ------------------------------------------------------------------------------


def test_failed_run_is_a_row_and_table_reads_back(tmp_path: Path):
    out = tmp_path / "square.csv"
    df = st.run_study(square, st.grid(x=range(5), k=[0.5, 2.0]), out, workers=1, progress=False)
    assert len(df) == 10 and df["run_id"].is_unique
    bad = df[df["x"] == 3]
    assert list(bad["success"]) == [False, False]
    assert list(bad["message"]) == ["RuntimeError: x = 3 is refused"] * 2
    good = df[df["success"]]
    assert good["y"].tolist() == [0.0, 0.0, 0.5, 2.0, 2.0, 8.0, 8.0, 32.0]  # x^2 k, exactly
    assert good["pair"].iloc[3] == [1.0, 2.0]  # arrays come back as lists
    back = st.load_table(out).set_index("run_id").loc[df["run_id"]].reset_index()[df.columns]
    pd.testing.assert_frame_equal(back, df, check_exact=True)


def test_arrays_kept_in_memory(tmp_path: Path):
    """keep_arrays: the arrays come back as the runs returned them, from worker processes
    as from a serial run, equal to the lists of the text table; only without a file."""
    runs = st.grid(x=range(5), k=[0.5, 2.0])
    serial = st.run_study(square, runs, workers=1, progress=False, keep_arrays=True)
    processes = st.run_study(square, runs, workers=2, progress=False, keep_arrays=True)
    text = st.run_study(square, runs, workers=1, progress=False)
    good = serial["success"].to_numpy()
    assert all(isinstance(v, np.ndarray) for v in serial["pair"][good])
    for a, b, c in zip(serial["pair"][good], processes["pair"][good], text["pair"][good]):
        np.testing.assert_array_equal(a, b)
        assert a.tolist() == c
    assert serial["pair"][~good].isna().all()  # the failed runs returned nothing
    pd.testing.assert_frame_equal(_values(processes.drop(columns="pair")), _values(serial.drop(columns="pair")),
                                  check_exact=True)
    with pytest.raises(ValueError, match="keep_arrays"):
        st.run_study(square, runs, tmp_path / "t.csv", workers=1, progress=False, keep_arrays=True)


def test_own_failure_status_resume_and_retry(tmp_path: Path):
    out = tmp_path / "t.csv"
    CALLS.clear()
    df = st.run_study(reports_failure, st.grid(x=range(3)), out, workers=1, progress=False)
    assert df["success"].tolist() == [True, False, True]
    assert df["message"][1] == 'stopped early,\n"see" below'  # quoted in the CSV, read back whole
    CALLS.clear()
    again = st.run_study(reports_failure, st.grid(x=range(3)), out, workers=1, progress=False)
    assert CALLS == []  # all done: nothing runs again
    pd.testing.assert_frame_equal(again, df, check_exact=True)
    st.run_study(reports_failure, st.grid(x=range(3)), out, workers=1, progress=False, retry_failed=True)
    assert CALLS == [1] and len(pd.read_csv(out)) == 3  # only the failed run is redone, and replaces its row


@pytest.mark.parametrize("workers", [1, 2])
def test_a_run_s_warnings_are_in_its_row(tmp_path: Path, workers: int):
    # a unit slip (UnitWarning) was a successful row with an empty message (issue 21)
    with pytest.warns(UserWarning, match="not exuclear's") if workers == 1 else contextlib.nullcontext():
        df = st.run_study(warns, st.grid(x=range(3)), tmp_path / "w.csv", workers=workers, progress=False)
    assert df["message"].tolist() == ["", "own note; UnitWarning: length 15 m: were they given in mm?", ""]
    assert df["success"].all() and st.warned(df).tolist() == [False, True, False]
    on_disk = st.load_table(tmp_path / "w.csv").sort_values("x")  # in the order the runs finished
    assert st.warned(on_disk).tolist() == [False, True, False]


def test_the_summary_counts_warnings_and_says_what_ran_now(tmp_path: Path, capsys):
    # the case: 15 for a length in metres is a 33 kN "success" in the slider-crank
    out = tmp_path / "units.csv"
    args = ["--no-progress", "--workers", "1", "--out", str(out)]
    assert st.main(["journal-bearing", "--length", "0.015,15", *args]) == 0
    said = capsys.readouterr()
    assert said.out.strip() == f"2 runs, 0 failed, 1 with warnings (see their message); table {out}"
    assert "warning: UnitWarning: the length 15 m is above 1 m" in said.err  # before the runs, one line
    row = st.load_table(out).set_index("length").loc[15.0]
    assert row["success"] and row["message"].startswith("UnitWarning: the length 15 m is above 1 m")
    # resumed: a resumed study's summary counted all rows as if run now
    assert st.main(["journal-bearing", "--length", "0.015,15,0.02", *args]) == 0
    assert capsys.readouterr().out.strip() == (f"3 runs (1 ran now, 2 taken from {out}), 0 failed, 1 with warnings "
                                               f"(see their message); table {out}")
    table = st.run_study(st.scene("journal-bearing"), st.grid(length=[0.015, 0.02]), out, workers=1, progress=False)
    assert (table.attrs["ran"], table.attrs["resumed"]) == (0, 2)


def test_bad_input_before_any_run(tmp_path: Path):
    sc = st.scene("slider-crank")
    out = tmp_path / "never.csv"
    with pytest.raises(ValueError, match="unknown parameter 'speed'"):
        st.run_study(sc, [{"speed": 100}], out, workers=1, progress=False)
    with pytest.raises(ValueError, match="cr"):  # the joint refuses cr > 1
        st.run_study(sc, st.grid(cr=[0.5, 1.5]), out, workers=1, progress=False)
    with pytest.raises(ValueError, match="rpm"):
        st.run_study(sc, [{"rpm": 0}], out, workers=1, progress=False)
    with pytest.raises(ValueError, match="no runs"):
        st.run_study(sc, [], out, workers=1, progress=False)
    with pytest.raises(ValueError, match="workers"):
        st.run_study(sc, [{}], out, workers=0, progress=False)
    with pytest.raises(ValueError, match=".csv"):
        st.run_study(sc, [{}], tmp_path / "t.xlsx", workers=1, progress=False)
    assert not out.exists()  # nothing ran


def test_table_of_another_study_is_refused(tmp_path: Path):
    out = tmp_path / "t.csv"
    st.run_study(square, [{"x": 1, "k": 1.0}], out, workers=1, progress=False)
    with pytest.raises(ValueError, match="another study"):
        st.run_study(st.Study(square, {"x": 0, "q": 1.0}), [{"x": 1}], out, workers=1, progress=False)


def _study_module(tmp_path: Path, body: str):
    """A module ``user_study`` in ``tmp_path`` whose ``run`` has ``body``, imported afresh
    (a user who edits the study function between two runs of the same script)."""
    import importlib
    import sys

    (tmp_path / "user_study.py").write_text(f"def run(p):\n    {body}\n")
    sys.modules.pop("user_study", None)
    importlib.invalidate_caches()
    sys.path.insert(0, str(tmp_path))
    try:
        return importlib.import_module("user_study")
    finally:
        sys.path.remove(str(tmp_path))


def test_a_table_knows_its_study_and_refuses_another_losing_nothing(tmp_path: Path):
    out = tmp_path / "x.csv"
    first = _study_module(tmp_path, 'return {"y": 2.0 * p["x"]}')
    st.run_study(first.run, st.grid(x=[1, 2]), out, workers=1, progress=False)
    sidecar = tmp_path / "x.csv.study.json"
    assert "user_study.run" in sidecar.read_text()
    table, identity = out.read_bytes(), sidecar.read_bytes()
    # the same study resumes: nothing runs again
    again = st.run_study(first.run, st.grid(x=[1, 2]), out, workers=1, progress=False)
    assert again.attrs["ran"] == 0 and list(again["y"]) == [2.0, 4.0]
    # the function changed (a new metric): its old rows are not its rows
    changed = _study_module(tmp_path, 'return {"y": 2.0 * p["x"], "z": 1.0}')
    with pytest.raises(ValueError, match=r"another study.*function's code.*delete .*x\.csv.*another `out`"):
        st.run_study(changed.run, st.grid(x=[1, 2]), out, workers=1, progress=False)
    # another default of a parameter: refused too
    with pytest.raises(ValueError, match="its parameters"):
        st.run_study(st.Study(first.run, {"x": 0}), st.grid(x=[1, 2]), out, workers=1, progress=False)
    assert out.read_bytes() == table and sidecar.read_bytes() == identity  # nothing lost or rewritten
    # keeping both: another `out` takes the changed study
    both = st.run_study(changed.run, st.grid(x=[1, 2]), tmp_path / "x2.csv", workers=1, progress=False)
    assert list(both["z"]) == [1.0, 1.0]


# -- interrupt and resume ---------------------------------------------------------------------


@pytest.mark.parametrize("workers", [1, 2])
def test_interrupt_then_resume_loses_and_repeats_nothing(tmp_path: Path, workers: int):
    stop = tmp_path / "stop"
    stop.touch()
    out = tmp_path / "t.csv"
    runs = st.grid(x=range(10), stop=[str(stop)])
    CALLS.clear()
    with pytest.raises(KeyboardInterrupt):
        st.run_study(interrupted_at_5, runs, out, workers=workers, batch_size=1, progress=False)
    kept = pd.read_csv(out)
    assert kept["run_id"].is_unique and 5 not in set(kept["x"])
    if workers == 1:
        assert sorted(kept["x"]) == [0, 1, 2, 3, 4] and CALLS == [0, 1, 2, 3, 4, 5]  # in order, stopped at 5
    stop.unlink()  # the "Ctrl-C" does not come again
    CALLS.clear()
    df = st.run_study(interrupted_at_5, runs, out, workers=workers, batch_size=1, progress=False)
    assert df["x"].tolist() == list(range(10)) and df["success"].all()
    assert df["y"].tolist() == [2.0 * x for x in range(10)]
    on_disk = pd.read_csv(out)
    assert len(on_disk) == 10 and on_disk["run_id"].is_unique  # nothing lost, nothing twice
    if workers == 1:
        assert sorted(CALLS) == sorted(set(range(10)) - set(kept["x"]))  # only the missing runs ran


def test_ctrl_c_in_serial_study_finishes_the_run_and_stops(tmp_path: Path):
    """A Ctrl-C inside a run (where a solver callback would swallow KeyboardInterrupt)
    lets that run finish and be recorded, then stops the study.  Python's own Ctrl-C handler
    is installed for the test: a shell that starts the tests as a background job has them
    ignore SIGINT, where no Ctrl-C can reach the study."""
    handler = signal.signal(signal.SIGINT, signal.default_int_handler)
    try:
        _ctrl_c_in_serial_study(tmp_path)
    finally:
        signal.signal(signal.SIGINT, handler)


def _ctrl_c_in_serial_study(tmp_path: Path) -> None:
    stop = tmp_path / "stop"
    stop.touch()
    out = tmp_path / "t.csv"
    runs = st.grid(x=range(6), stop=[str(stop)])
    CALLS.clear()
    with pytest.raises(KeyboardInterrupt):
        st.run_study(sigint_at_2, runs, out, workers=1, progress=False)
    assert CALLS == [0, 1, 2] and pd.read_csv(out)["x"].tolist() == [0, 1, 2]
    stop.unlink()
    CALLS.clear()
    df = st.run_study(sigint_at_2, runs, out, workers=1, progress=False)
    assert CALLS == [3, 4, 5] and df["y"].tolist() == [0.0, 3.0, 6.0, 9.0, 12.0, 15.0]


def test_crashed_worker_is_a_row(tmp_path: Path):
    df = st.run_study(crashes_at_2, st.grid(x=range(6)), tmp_path / "t.csv", workers=2, progress=False)
    assert df["x"].tolist() == list(range(6))
    assert df["success"].tolist() == [True, True, False, True, True, True]
    assert "killed its worker" in df["message"][2]
    assert df["y"][df["success"]].tolist() == [0.5, 1.5, 3.5, 4.5, 5.5]


# -- executors --------------------------------------------------------------------------------


def test_dask_local_cluster_rows_equal_serial_rows(tmp_path: Path):
    """A real dask.distributed LocalCluster (2 worker processes) against a serial run and
    local worker processes: equal value by value (wall times aside)."""
    pytest.importorskip("dask.distributed")
    jb = st.scene("journal-bearing")
    runs = st.grid(cr=[0.3, 0.5, 0.9], length=[15e-3, 30e-3])
    serial = st.run_study(jb, runs, tmp_path / "serial.csv", workers=1, progress=False)
    processes = st.run_study(jb, runs, tmp_path / "processes.csv", workers=2, progress=False)
    dask = st.run_study(jb, runs, tmp_path / "dask.csv", workers=2, scheduler="local", batch_size=2, progress=False)
    assert serial["success"].all() and len(serial) == 6
    pd.testing.assert_frame_equal(_values(processes), _values(serial), check_exact=True)
    pd.testing.assert_frame_equal(_values(dask), _values(serial), check_exact=True)
    # the paper's departure velocities at L = 15 mm (README table: 0.098, 0.145, 0.269 m/s),
    # to the 0.2 % the README reports against the paper's three digits
    paper = serial[serial["length"] == 15e-3]["departure_velocity"].to_numpy()
    np.testing.assert_allclose(paper, [0.098, 0.145, 0.269], rtol=2e-3)


def test_batch_size():
    assert _batch_size([0.0, 0], 100, 2) == 1  # nothing measured yet
    assert _batch_size([1.0, 100], 10_000, 2) == 100  # 10 ms runs: 1 s of work per task
    assert _batch_size([1.0, 100], 400, 2) == 50  # ... but 4 tasks per worker over what is left
    assert _batch_size([20.0, 10], 10_000, 2) == 1  # 2 s runs: one per task


# -- the scenes ------------------------------------------------------------------------------


def test_ideal_slider_acceleration_matches_finite_differences():
    from exuclear.models.slider_crank import ideal_slider_acceleration

    r, l, w = 0.05, 0.30, 52.36
    theta = np.linspace(0.0, 2.0 * math.pi, 361)
    h = 1e-4 / w  # central difference in time; its error ~ h^2 x'''' / 12 ~ 1e-9 m/s^2 here

    def x(t):
        return r * np.cos(w * t) + np.sqrt(l**2 - (r * np.sin(w * t)) ** 2)

    t = theta / w
    fd = (x(t + h) - 2.0 * x(t) + x(t - h)) / h**2
    # round-off of the difference quotient: 4 eps x / h^2 ~ 4e-16 * 0.35 / 3.6e-12 ~ 4e-5 m/s^2
    np.testing.assert_allclose(ideal_slider_acceleration(theta, w, r, l), fd, rtol=0.0, atol=1e-3)
    assert ideal_slider_acceleration(np.array([0.0]), w, r, l)[0] == pytest.approx(-r * w**2 * (1 + r / l))


def test_slider_crank_study_paper_case():
    """Two revolutions of the paper's case (cr 0.9, one start-up revolution)."""
    from exuclear.models.slider_crank import study

    row = study({"cr": 0.9, "startup": 1.0, "revolutions": 1.0})
    assert row["success"], row["message"]
    assert row["impacts"] == 22  # README: 22 impacts in two revolutions at cr = 0.9 (minimal default)
    # after the start-up bounces the journal stays in permanent contact (README): no new onset
    assert row["impacts_per_rev"] == 0.0
    assert 1.0 < row["max_ecc_over_c"] < 1.05  # in contact, penetration a few % of c at most (README: micrometres)
    # energy audit within 1 % of the contact's gross work: validation/hard_cases/common.py AUDIT_LIMIT
    assert abs(row["energy_residual_rel"]) < 0.01
    assert row["contact_dissipated"] > 0.0


def test_journal_bearing_study_energy_audit():
    from exuclear.models.journal_bearing import study

    row = study({"cr": 0.5})
    assert row["success"] and row["impacts"] == 1
    assert row["effective_restitution"] == pytest.approx(0.4826, abs=5e-5)  # README table, 4 digits
    # kinetic energy lost = energy the contact dissipated: the trapezoid rule over 1e-8 s
    # outputs of a 40 us impact errs far below 1e-4 of it
    assert abs(row["energy_residual_rel"]) < 1e-4



def test_guided_slider_crank_study_rows_are_the_scene_s_own_runs(tmp_path: Path):
    """The Flores-Leine-Glocker slider-crank through the runner: a row is the scene's direct
    run with the same parameters, elastic corners keep the energy, damped ones lose some."""
    from exuclear.models import guided_slider_crank as gsc

    sc = st.scene("guided-slider-crank")
    assert sc.function is gsc.study
    # the study's defaults are the paper's benchmark, the rod at -75 rad/s (Flores, Leine,
    # Glocker 2010, section 4) from the crank's 150 rad/s
    params, end_time = gsc.study_params({})
    assert params == gsc.GuidedSliderCrankParams.benchmark() and params.rod_speed == -75.0
    assert end_time == gsc.BENCHMARK_END_TIME
    # the first seven contacts (tests/test_guided_slider_crank_scene.py), at two stiffnesses,
    # and elastic frictionless corners over two rattling contacts
    short = 0.01
    runs = [*st.grid(stiffness=[1e9, 1e10], end_time=[short]),
            {"damping": "none", "friction": "none", "end_time": 0.02}]
    table = st.run_study(sc, runs, tmp_path / "gsc.csv", workers=1, progress=False)
    assert table["success"].all(), table["message"].tolist()
    p = gsc.GuidedSliderCrankParams.benchmark()
    direct = gsc.run(p, gsc.default_settings(p, short))
    row = table.iloc[1]
    assert row["stiffness"] == 1e10 and row["impacts"] == len(direct.impacts) >= 6
    # the same deterministic run: equal to round-off (the floats' trip through the CSV's text)
    assert row["crank_speed_end"] == pytest.approx(direct.crank_speed[-1], rel=1e-14)
    assert row["max_y_over_c"] == pytest.approx(np.abs(direct.slider[:, 1]).max() / p.clearance, rel=1e-14)
    assert row["peak_force"] == pytest.approx(max(i.peak_force for i in direct.impacts), rel=1e-14)
    assert row["steps"] == direct.steps
    # damping and friction only take energy: the damped runs lose some
    assert (table["energy_lost"].iloc[:2] > 0.0).all()
    elastic = table.iloc[2]
    assert elastic["impacts"] >= 2
    # elastic corners without friction conserve the energy; the bound of the scene's own
    # energy test (tests/test_guided_slider_crank_scene.py, generalized-alpha at 1e-6 s)
    assert abs(elastic["energy_lost_rel"]) < 1e-6


@pytest.mark.parametrize(("values", "named"), [
    ({"clearance": -1e-3}, "`clearance` must be positive"), ({"stiffness": 0.0}, "`stiffness` must be positive"),
    ({"exponent": -1.0}, "`exponent` must be positive"), ({"cr": 1.5}, "`cr` must lie in"),
    ({"damping": "soft"}, "unknown `damping`"), ({"end_time": 0.0}, "`end_time` must be positive"),
    ({"crank_speed": "fast"}, "`crank_speed` must be a real number"), ({"gravity": -9.81}, "`gravity`"),
    ({"backend": "gpu"}, "unknown `backend`"), ({"rpm": 100}, "unknown parameter 'rpm'")])
def test_guided_slider_crank_study_refuses_bad_values_naming_them(tmp_path: Path, values, named):
    out = tmp_path / "never.csv"
    with pytest.raises(ValueError, match=named):
        st.run_study(st.scene("guided-slider-crank"), [{"end_time": 1e-3}, values], out, workers=1, progress=False)
    assert not out.exists()  # refused before any run


def test_guided_slider_crank_study_command_line(tmp_path: Path, capsys):
    out = tmp_path / "gsc.csv"
    assert st.main(["guided-slider-crank", "--clearance", "-1e-3", "--no-progress", "--out", str(out)]) == 2
    assert "`clearance` must be positive, got -0.001" in capsys.readouterr().err and not out.exists()
    help_text = _scene_parser(st.scene("guided-slider-crank"), "study").format_help()
    assert "corner stiffness K [N/m^n]" in help_text and "simulated time [s]" in help_text

# -- command line -----------------------------------------------------------------------------


def test_command_line(tmp_path: Path, capsys):
    out = tmp_path / "cli.csv"
    assert st.main(["journal-bearing", "--cr", "0.3:0.9:0.6", "--workers", "1", "--no-progress", "--out", str(out)]) == 0
    table = st.load_table(out).sort_values("cr")
    assert table["cr"].tolist() == [0.3, 0.9] and table["success"].all()
    assert st.main(["journal-bearing", "--cr", "0.5,2", "--workers", "1", "--out", str(tmp_path / "x.csv")]) == 2
    assert "cr" in capsys.readouterr().err and not (tmp_path / "x.csv").exists()
    assert st.main(["no-such-scene", "--out", str(out)]) == 2
    sampled = tmp_path / "sampled.csv"
    assert st.main(["journal-bearing", "--cr", "0.3:0.9", "--length", "0.02", "--sample", "3", "--seed", "1",
                    "--workers", "1", "--no-progress", "--out", str(sampled)]) == 0
    table = st.load_table(sampled)
    assert len(table) == 3 and table["cr"].between(0.3, 0.9).all() and (table["length"] == 0.02).all()
    pytest.importorskip("matplotlib")
    fig = tmp_path / "fig.png"
    assert st.main(["plot", str(out), "--metric", "peak_force", "--x", "cr", "--out", str(fig)]) == 0
    assert fig.stat().st_size > 0


def test_a_negative_value_gets_the_rule_it_breaks(tmp_path: Path, capsys):
    # argparse read "-1e-4" as an option and said "expected one argument" (issue 21)
    out = tmp_path / "neg.csv"
    assert st.main(["slider-crank", "--clearance", "-1e-4", "--no-progress", "--out", str(out)]) == 2
    assert "`clearance` must be positive, got -0.0001" in capsys.readouterr().err
    assert st.main(["slider-crank", "--gravity", "-1,0", "--no-progress", "--out", str(out)]) == 2
    assert "`gravity` must be non-negative, got -1" in capsys.readouterr().err
    assert not out.exists()


def test_python_m_exuclear_study_prints_no_runpy_warning(tmp_path: Path):
    # `import exuclear` used to import exuclear.study, and runpy then warned that the module
    # was in sys.modules before it ran it as __main__: in the parent and again in every
    # spawned worker (3 times with 2 workers), through the progress bar
    import subprocess
    import sys

    import exuclear

    assert exuclear.run_study is st.run_study and exuclear.Study is st.Study  # still the top-level names
    helped = subprocess.run([sys.executable, "-m", "exuclear.study", "--help"], capture_output=True, text=True)
    assert helped.returncode == 0 and "RuntimeWarning" not in helped.stderr, helped.stderr
    ran = subprocess.run([sys.executable, "-m", "exuclear.study", "journal-bearing", "--cr", "0.5,0.9", "--workers", "2",
                          "--no-progress", "--out", str(tmp_path / "two.csv")], capture_output=True, text=True)
    assert ran.returncode == 0, ran.stderr
    assert "RuntimeWarning" not in ran.stderr, ran.stderr  # a KernelWarning (no compiler) may stand there
    assert st.load_table(tmp_path / "two.csv")["success"].all()


@pytest.mark.parametrize("name, module", [("slider-crank", "slider_crank"), ("journal-bearing", "journal_bearing")])
def test_the_study_speaks_the_scene_s_option_names(name, module):
    # the study said --bearing-length and --journal-material where the scene's command line
    # says --length and --journal (issue 21): every spelling of a study parameter on the
    # scene's command line is one of the study's too
    import importlib

    scene_parser = importlib.import_module(f"exuclear.models.{module}")._parser()
    study = st.scene(name)
    study_parser = _scene_parser(study, "study")

    def spellings(parser, dest):
        return {flag for action in parser._actions if action.dest == dest for flag in action.option_strings}

    for parameter in study.parameters:
        assert spellings(scene_parser, parameter) <= spellings(study_parser, parameter), parameter
    assert {"--length", "--bearing-length", "--journal", "--journal-material"} <= set(study_parser._option_string_actions)
    assert "--method" not in study_parser._option_string_actions  # the scenes' solver; the study's draw is --sampling
    # the API takes the other spellings too, under the parameter's own name (one run id)
    field = "bearing_length" if name == "slider-crank" else "length"
    assert study.complete({"length": 0.02})[field] == 0.02 and study.complete({"bearing_length": 0.02})[field] == 0.02
    assert st.run_id(study.complete({"journal": "aluminium"})) == st.run_id(study.complete({"journal_material": "aluminium"}))
    with pytest.raises(ValueError, match="given twice"):
        study.complete({"length": 0.02, "bearing_length": 0.03})


def test_plot_axes_say_what_and_in_which_unit(tmp_path: Path):
    # the axes were labelled with raw column names, no units (issue 21)
    pytest.importorskip("matplotlib")
    from matplotlib.figure import Figure

    from exuclear.study.plot import axis_label, plot_metric

    out = tmp_path / "labels.csv"
    assert st.main(["journal-bearing", "--cr", "0.5,0.9", "--length", "0.01,0.02", "--workers", "1", "--no-progress",
                    "--out", str(out)]) == 0
    table = st.load_table(out)
    study = _scene_of(table)  # what the command line labels by when no --scene is given
    assert study is not None and study.name == "journal-bearing"
    ax = plot_metric(table, "peak_force", "cr", by="length", ax=Figure().subplots(), columns=study.columns)
    assert (ax.get_xlabel(), ax.get_ylabel()) == ("coefficient of restitution", "peak contact force [N]")
    assert ax.get_legend().get_title().get_text() == "bearing length L [m]"
    heat = plot_metric(table, "contact_duration", "cr", y="length", ax=Figure().subplots(), columns=study.columns)
    assert heat.get_ylabel() == "bearing length L [m]"
    assert heat.figure.axes[-1].get_ylabel() == "contact duration [s]"  # the colour bar
    # the labels come from the scene's own tables: the parameter field's help, the metric's entry
    from exuclear.models.journal_bearing import STUDY_METRICS, JournalBearingParams

    assert JournalBearingParams.__dataclass_fields__["length"].metadata["help"] == "bearing length L [m]"
    assert STUDY_METRICS["peak_force"].unit == "N"
    assert axis_label("wall_time") == "wall time of the run [s]" and axis_label("no_such_column") == "no_such_column"
    assert st.main(["plot", str(out), "--metric", "peak_force", "--x", "cr", "--scene", "no-such-scene",
                    "--out", str(tmp_path / "x.png")]) == 2
