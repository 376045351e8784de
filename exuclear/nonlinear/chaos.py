"""Telling periodic, quasi-periodic and chaotic responses apart from their Poincare
samples (no exudyn): the 0-1 test for chaos (:func:`test01`) and the verdict
(:func:`classify`).

The 0-1 test follows G. A. Gottwald and I. Melbourne, "On the implementation of the 0-1
test for chaos", SIAM J. Appl. Dyn. Syst. 8 (2009) 129-145, in its correlation form with
the oscillatory term removed (docs/physics.md, section "Nonlinear dynamics").  It needs
samples taken once per forcing period (a Poincare map): oversampled signals (many samples
per period) make even chaos look regular to it.
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

#: Fewest samples the 0-1 test takes: its lags reach a tenth of the series
#: (:data:`LAG_FRACTION`), and the correlation of K_c with the lag needs at least 5 of them.
MIN_SAMPLES = 50
#: Largest lag of the mean square displacement, as a fraction of the series: Gottwald and
#: Melbourne's n_cut = N / 10, so that every lag is averaged over at least 9 N / 10 terms.
LAG_FRACTION = 0.1
#: Number of frequencies c and their interval: Gottwald and Melbourne draw 100 values in
#: (pi/5, 4 pi/5), away from c = 0 and c = pi, where a period-1 or period-2 response
#: resonates; the median over c discards the few that resonate with other periods.
FREQUENCIES = 100
FREQUENCY_BAND = (math.pi / 5.0, 4.0 * math.pi / 5.0)
#: A series whose spread is below this fraction of its size is constant (a period-1
#: response): its translation variables do not grow, and the test reports K = 0.
CONSTANT = 1e-12
#: Longest period :func:`classify` looks for (the papers' period-doubling cascades are
#: read up to period 16 at most).
MAX_PERIOD = 16
#: K above this is chaotic, below regular.  K tends to 1 for chaos and 0 for regular
#: motion; with a few hundred samples chaos gives 0.8-1 and periodic or quasi-periodic
#: motion below 0.2, so the middle divides them.
K_CHAOTIC = 0.5


@dataclass(frozen=True)
class ZeroOneResult:
    """The result of :func:`test01`.

    Attributes
    ----------
    K : float
        The median of ``K_c`` over the frequencies: near 1 chaotic, near 0 regular.
    K_c : ndarray
        ``K`` per frequency ``c``.
    c : ndarray
        The frequencies [rad per sample].
    samples : int
        Length of the series.
    note : str
        Why the test was not run as such ("constant series"), else empty.
    """

    K: float
    K_c: np.ndarray = field(repr=False)
    c: np.ndarray = field(repr=False)
    samples: int
    note: str = ""


def test01(samples: object, *, frequencies: int = FREQUENCIES, seed: int = 0) -> ZeroOneResult:
    """The 0-1 test for chaos (Gottwald and Melbourne 2009) of one scalar series.

    For each frequency ``c`` the series ``phi_j`` drives the translation variables
    ``p_c(n) = sum_{j<=n} phi_j cos(j c)``, ``q_c(n) = sum_{j<=n} phi_j sin(j c)``; their
    mean square displacement ``M_c(n)`` grows linearly in ``n`` for chaos and stays
    bounded for regular motion.  ``D_c(n) = M_c(n) - (E phi)^2 (1 - cos n c) / (1 - cos c)``
    removes the bounded oscillation the mean of ``phi`` causes, ``K_c`` is the
    correlation of ``D_c(n)`` with ``n`` for ``n <= N / 10``, and ``K`` the median over
    :data:`FREQUENCIES` values of ``c`` drawn uniformly in :data:`FREQUENCY_BAND`.

    Parameters
    ----------
    samples : array, shape (N,)
        Once-per-period samples (a Poincare map), transient left out; at least
        :data:`MIN_SAMPLES`.
    frequencies : int
        Number of frequencies ``c``.
    seed : int
        Seed of the frequencies (the same seed, the same ``K``).

    Returns
    -------
    ZeroOneResult
        ``K`` near 1 chaotic, near 0 regular.  A constant series (spread below
        :data:`CONSTANT` of its size) has ``K = 0`` and says so in ``note``.
    """
    phi = np.asarray(samples, dtype=float)
    if phi.ndim != 1:
        raise ValueError(f"`samples` must be a 1-d series, got shape {phi.shape}")
    if phi.size < MIN_SAMPLES:
        raise ValueError(f"`samples` must hold at least {MIN_SAMPLES} values for the 0-1 test (its lags reach a tenth "
                         f"of the series), got {phi.size}")
    if not np.all(np.isfinite(phi)):
        raise ValueError("`samples` must be finite")
    if isinstance(frequencies, bool) or not isinstance(frequencies, int) or frequencies < 1:
        raise ValueError(f"`frequencies` must be a positive integer, got {frequencies!r}")
    c = np.random.default_rng(seed).uniform(*FREQUENCY_BAND, frequencies)
    n_samples = phi.size
    if np.ptp(phi) <= CONSTANT * max(1.0, float(np.max(np.abs(phi)))):
        return ZeroOneResult(0.0, np.zeros(frequencies), c, n_samples, "constant series (period 1): K = 0")
    n_cut = max(int(LAG_FRACTION * n_samples), 1)
    j = np.arange(1, n_samples + 1)
    p = np.cumsum(phi[:, None] * np.cos(np.outer(j, c)), axis=0)  # (N, frequencies)
    q = np.cumsum(phi[:, None] * np.sin(np.outer(j, c)), axis=0)
    lags = np.arange(1, n_cut + 1)
    count = n_samples - n_cut  # every lag averaged over the same terms
    msd = np.array([np.mean((p[n:n + count] - p[:count]) ** 2 + (q[n:n + count] - q[:count]) ** 2, axis=0)
                    for n in lags])  # (n_cut, frequencies)
    mean = float(np.mean(phi))
    d = msd - mean**2 * (1.0 - np.cos(np.outer(lags, c))) / (1.0 - np.cos(c))
    k_c = np.array([_correlation(lags, d[:, i]) for i in range(frequencies)])
    return ZeroOneResult(float(np.median(k_c)), k_c, c, n_samples)


#: Its name starts with "test": pytest would collect it from a test module that imports it.
test01.__test__ = False


def _correlation(x: np.ndarray, y: np.ndarray) -> float:
    """Pearson's correlation; 0 where ``y`` does not vary (a bounded, regular D_c)."""
    sy = np.std(y)
    if sy <= CONSTANT * max(1.0, float(np.max(np.abs(y)))):
        return 0.0
    return float(np.mean((x - x.mean()) * (y - y.mean())) / (np.std(x) * sy))


@dataclass(frozen=True)
class Classification:
    """The verdict of :func:`classify`.  ``str()`` starts with :attr:`kind`.

    Attributes
    ----------
    kind : str
        ``"period-N"`` (N from 1 to the longest period looked for), ``"quasi-periodic"``,
        ``"chaotic"``, or ``"aperiodic"`` (not periodic, and too few samples for the 0-1
        test with no exponent given to tell the other two apart).
    period : int
        N of a period-N response; 0 otherwise.
    K : float
        The 0-1 test's K (median over the columns), NaN where it was not run (a periodic
        response, or too few samples).
    exponent : float
        The largest Lyapunov exponent given to :func:`classify`, NaN if none.
    note : str
        Where the evidence disagrees (a positive exponent for a periodic-looking series,
        K against the exponent), else empty.
    """

    kind: str
    period: int = 0
    K: float = math.nan
    exponent: float = math.nan
    note: str = ""

    def __str__(self) -> str:
        evidence = [f"K = {self.K:.2f}"] if math.isfinite(self.K) else []
        if math.isfinite(self.exponent):
            evidence.append(f"largest exponent {self.exponent:+.3g} 1/s")
        if self.note:
            evidence.append(self.note)
        return self.kind + (f" ({'; '.join(evidence)})" if evidence else "")


def period_of(samples: object, *, rtol: float = 1e-3, atol: float = 0.0, max_period: int = MAX_PERIOD) -> int:
    """The smallest N <= ``max_period`` with ``|x[k + N] - x[k]| <= atol + rtol * scale``
    for every k and column (``scale``: the column's largest ``|x|``), or 0 if none.

    The tolerance is tied to the size of the samples, not to their spread: a period-1
    response has almost no spread, and a tolerance relative to it would call it
    aperiodic.  ``x[k + N]`` must be compared at least twice (``2 N`` samples or more).
    """
    x = _columns(samples)
    tol = atol + rtol * np.max(np.abs(x), axis=0)
    for n in range(1, max_period + 1):
        if x.shape[0] < 2 * n:
            break
        if np.all(np.abs(x[n:] - x[:-n]) <= tol):
            return n
    return 0


def _columns(samples: object) -> np.ndarray:
    x = np.asarray(samples, dtype=float)
    if x.ndim == 1:
        x = x[:, None]
    if x.ndim != 2 or x.shape[0] < 2:
        raise ValueError(f"`samples` must be an array of shape (n,) or (n, m) with n >= 2, got shape {np.shape(samples)}")
    if not np.all(np.isfinite(x)):
        raise ValueError("`samples` must be finite")
    return x


def classify(samples: object, *, exponent: float | None = None, rtol: float = 1e-3, atol: float = 0.0,
             max_period: int = MAX_PERIOD, k_chaotic: float = K_CHAOTIC) -> Classification:
    """Periodic (and its period), quasi-periodic or chaotic, from Poincare samples.

    1. Period: :func:`period_of` (the samples repeat every N within the tolerance
       ``atol + rtol * scale``; give a tolerance above the integration error of the
       samples and below the distance between the points of a period-N orbit).
    2. Otherwise, chaotic or quasi-periodic: by the largest Lyapunov exponent where it
       is given (positive: chaotic), else by the 0-1 test (:func:`test01`, the median of
       its K over the columns, above ``k_chaotic``: chaotic).  Both given and
       disagreeing: the exponent decides, and ``note`` says so.

    Parameters
    ----------
    samples : array, shape (n,) or (n, m)
        Once-per-period samples of one or more quantities, transient left out.
    exponent : float, optional
        The largest Lyapunov exponent [1/s] (:func:`exuclear.nonlinear.lyapunov`).
    rtol, atol : float
        Tolerance of the period test, relative to each column's largest ``|x|`` and
        absolute (in the samples' units).
    max_period : int
        Longest period looked for (at most :data:`MAX_PERIOD`).
    k_chaotic : float
        K above which the 0-1 test calls a series chaotic.
    """
    x = _columns(samples)
    if isinstance(max_period, bool) or not isinstance(max_period, int) or not 1 <= max_period <= MAX_PERIOD:
        raise ValueError(f"`max_period` must be an integer from 1 to {MAX_PERIOD}, got {max_period!r}")
    for name, value in (("rtol", rtol), ("atol", atol)):
        if not (isinstance(value, (int, float)) and math.isfinite(value) and value >= 0.0):
            raise ValueError(f"`{name}` must be a non-negative number, got {value!r}")
    lam = math.nan if exponent is None else float(exponent)
    n = period_of(x, rtol=rtol, atol=atol, max_period=max_period)
    if n:
        note = "a positive exponent: the period test's tolerance may be too loose" if lam > 0.0 else ""
        return Classification(f"period-{n}", n, exponent=lam, note=note)
    k = float(np.median([test01(col).K for col in x.T])) if x.shape[0] >= MIN_SAMPLES else math.nan
    if math.isfinite(lam):
        chaotic = lam > 0.0
        note = ""
        if math.isfinite(k) and (k > k_chaotic) != chaotic:
            note = f"the 0-1 test says {'chaotic' if k > k_chaotic else 'regular'}; the exponent decides"
        return Classification("chaotic" if chaotic else "quasi-periodic", 0, k, lam, note)
    if not math.isfinite(k):
        return Classification("aperiodic", 0, k, lam, f"{x.shape[0]} samples: too few for the 0-1 test "
                              f"(at least {MIN_SAMPLES}) and no exponent given")
    return Classification("chaotic" if k > k_chaotic else "quasi-periodic", 0, k, lam)
