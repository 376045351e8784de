"""Amplitude spectra of recorded signals (no exudyn; scipy.signal imported on use).

Outputs of a run sit at the solver's accepted steps, which are not uniform; a spectrum
needs uniform samples.  :func:`amplitude_spectrum` resamples linearly and hands the
samples to Welch's method (:func:`scipy.signal.welch`), which serves the three uses in
exuclear: the whole record without a window (the slider-crank figures and metrics), the
whole record with a Hann window (a part of a run, which is not periodic), and averaged
Hann-windowed segments (the convergence check's comparison of two runs' spectra).
"""
from __future__ import annotations

import numpy as np


def amplitude_spectrum(t: np.ndarray, y: np.ndarray, dt: float, *, window: str = "boxcar", segments: int = 1,
                       grid: np.ndarray | None = None) -> tuple[np.ndarray, np.ndarray]:
    """One-sided amplitude spectrum of ``y(t)`` resampled with step ``dt``.

    Parameters
    ----------
    t, y : array, shape (n,)
        Sample times [s] (increasing, not necessarily uniform) and values.
    dt : float
        Step of the uniform resampling [s].
    window : str
        Window of each segment, a name :func:`scipy.signal.get_window` knows:
        ``"boxcar"`` (none; for records that hold whole periods) or ``"hann"`` (a part of
        a run: keeps the leakage of the jump between the record's ends out of the
        spectrum).
    segments : int
        1: the whole record at once.  More: segments of ``len // segments`` samples,
        overlapping by half (so about ``2 segments - 1`` of them), whose power spectra
        are averaged (Welch), for a smoother spectrum at a coarser resolution.
    grid : array, optional
        The uniform sample times, step ``dt``; default ``np.arange(t[0], t[-1], dt)``.

    Returns
    -------
    f, amplitude : array, shape (m,)
        Frequencies [Hz] and amplitudes (units of ``y``).  The mean of every segment is
        removed, and the amplitude is corrected for the window's mean: a sinusoid of
        amplitude ``A`` on a frequency bin shows a peak of ``A`` (bins 0 and Nyquist,
        which have no negative twin, show ``A / sqrt(2)``).
    """
    from scipy.signal import welch

    if grid is None:
        grid = np.arange(t[0], t[-1], dt)
    samples = np.interp(grid, t, y)
    f, power = welch(samples, fs=1.0 / dt, window=window, nperseg=len(samples) // segments, detrend="constant",
                     scaling="spectrum")
    return f, np.sqrt(2.0 * power)  # welch's power of a sinusoid of amplitude A is A^2 / 2
