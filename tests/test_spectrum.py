"""exuclear.spectrum.amplitude_spectrum: the one amplitude spectrum of the figures, the
slider-crank metrics and the convergence check.

Analytic cases: a sinusoid of amplitude A whose frequency falls on a bin shows a peak of
A with every window (the window's mean is divided out), the mean is removed, and
non-uniform samples are resampled onto the uniform grid first.
"""
from __future__ import annotations

import numpy as np
import pytest

from exuclear.spectrum import amplitude_spectrum

DT = 1e-4
#: 0.5 s of samples: bins of 2 Hz, and 8 Hz in 4 segments of 0.125 s: 40 Hz is a bin of both
T = np.arange(0.0, 0.5 + DT / 2, DT)


@pytest.mark.parametrize("window, segments", [("boxcar", 1), ("hann", 1), ("hann", 4)])
def test_a_sinusoid_on_a_bin_shows_its_amplitude(window, segments):
    y = 3.0 + 0.7 * np.sin(2 * np.pi * 40.0 * T)
    f, a = amplitude_spectrum(T, y, DT, window=window, segments=segments)
    k = int(np.argmax(a))
    assert f[k] == pytest.approx(40.0)
    # 1e-9: linear resampling of samples already on the grid is exact, the FFT adds round-off
    assert a[k] == pytest.approx(0.7, rel=1e-9)
    assert a[0] < 1e-9  # the mean (3.0) is removed


def test_the_whole_record_without_a_window_is_the_plain_fft():
    # the former plotting.uniform_spectrum: 2 |rfft| / n of the mean-free samples (bins 1 .. n/2 - 1)
    rng = np.random.default_rng(0)
    t = np.sort(rng.uniform(0.0, 0.2, 3000))
    y = np.sin(2 * np.pi * 40.0 * t) + 0.1 * rng.standard_normal(t.size)
    f, a = amplitude_spectrum(t, y, DT)
    samples = np.interp(np.arange(t[0], t[-1], DT), t, y)
    plain = 2.0 * np.abs(np.fft.rfft(samples - samples.mean())) / samples.size
    assert np.allclose(f, np.fft.rfftfreq(samples.size, DT))
    assert np.allclose(a[1:-1], plain[1:-1], rtol=1e-12, atol=1e-15)
