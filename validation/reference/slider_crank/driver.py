"""The public driver: :func:`simulate` checks its inputs, integrates the phases
(:mod:`.phases`) and samples them (:mod:`.outputs`); the ideal mechanism is its closed
form (:func:`.mechanism.ideal_kinematics`)."""
from __future__ import annotations

import time

import numpy as np

from exuclear.models.slider_crank import SliderCrankParams
from validation.reference.slider_crank.mechanism import _laws, _mechanism, ideal_kinematics
from validation.reference.slider_crank.outputs import Result, _output_times, _sample
from validation.reference.slider_crank.phases import _integrate

#: solve_ivp methods accepted; DOP853 and RK45 (explicit) and Radau (implicit, stiff) are tested.
METHODS = ("DOP853", "RK45", "RK23", "Radau", "BDF", "LSODA")

def _check(method: str, t_end: float, rtol: float, atol: float, max_step: float | None, output_step: float) -> None:
    if method not in METHODS:
        raise ValueError(f"unknown `method` {method!r}; known: {', '.join(METHODS)}")
    for name, value in (("t_end", t_end), ("rtol", rtol), ("atol", atol), ("output_step", output_step)):
        if not value > 0.0:
            raise ValueError(f"`{name}` must be positive, got {value}")
    if max_step is not None and not max_step > 0.0:
        raise ValueError(f"`max_step` must be positive or None, got {max_step}")


def simulate(params: SliderCrankParams, t_end: float | None = None, method: str = "DOP853", rtol: float = 1e-10,
             atol: float = 1e-13, max_step: float | None = None, output_step: float = 1e-5) -> Result:
    """Simulate the slider-crank with its clearance joint (or the ideal one) by SciPy.

    Parameters
    ----------
    params : SliderCrankParams
        Mechanism and joint (attribute access only); ``params.ideal`` selects the closed
        form of :func:`ideal_kinematics`.
    t_end : float, optional
        End time [s]; default ``params.end_time`` (its revolutions at its crank speed).
    method : str
        A :func:`scipy.integrate.solve_ivp` method of :data:`METHODS`.
    rtol, atol : float
        Tolerances; ``atol`` meets angles [rad], positions [m] (penetrations of order
        1e-6 m), velocities and the energy integrals [J].
    max_step : float, optional
        Largest step [s]; default unbounded.
    output_step : float
        Interval of the output grid [s]; values come from each phase's dense output.

    Returns
    -------
    Result
    """
    t_end = params.end_time if t_end is None else t_end
    _check(method, t_end, rtol, atol, max_step, output_step)
    times = _output_times(t_end, output_step)
    if params.ideal:
        start = time.perf_counter()
        columns = ideal_kinematics(params, times)
        return Result(columns, np.array([]), 0, time.perf_counter() - start, 0, True, "closed form (ideal joint)")
    m, laws = _mechanism(params), _laws(params)
    options = {"method": method, "rtol": rtol, "atol": atol, "max_step": np.inf if max_step is None else max_step}
    start = time.perf_counter()
    phases, onsets, n_rhs, success, message = _integrate(m, laws, t_end, options)
    wall_time = time.perf_counter() - start
    if not success:
        times = times[times <= phases[-1].t_stop]
    columns, energy = _sample(m, laws, phases, times)
    return Result(columns, np.array(onsets), len(onsets), wall_time, n_rhs, success, message, energy)
