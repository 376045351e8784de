"""Time scales of a clearance joint, for choosing steps (no exudyn).

A journal pressed against its bearing by a force ``F`` oscillates on the contact's
tangent stiffness ``k = dF_e/d delta`` at the penetration ``delta_F`` where the elastic
force equals ``F`` (docs/physics.md eq. 9 with ``delta_dot = 0``).  With ``m`` the
effective mass of the joint's relative motion, the **contact period** is

    T_c = 2 pi sqrt(m / k(delta_F))

(exuclear's estimate: the linearised contact mode).  For the Wang-Liu law of the paper's
slider-crank (``F`` ~ 30 N, ``m`` ~ 0.2 kg) it is about 0.3 ms; for a steel pendulum of
0.6 kg hanging on a 10 um pin, about 0.4 ms.  An implicit method without error control
needs steps of a fraction of ``T_c`` wherever a contact can open (:data:`STEPS_PER_CONTACT_PERIOD`);
:func:`step_from_contact_periods` is that rule for a whole run (``SolverSettings(step="auto")``).
"""
from __future__ import annotations

import math
from collections.abc import Iterable

from .contact import ContactLaw, restitution_of_damping

#: Steps per contact period below which a contact that opens is not resolved.  With
#: generalized-alpha at 1e-3 s (2.3 contact periods) a resting pendulum leaves the wall
#: 68 times in 2 s; at 1e-4 s (a quarter period) and below it stays in contact, as DOPRI5
#: and physics say (issue 15).  Ten leaves a margin of 2.5 for the crude effective mass.
STEPS_PER_CONTACT_PERIOD = 10

#: Steps a run takes at least with an automatic step, the bound where no clearance joint
#: sets a shorter one (a model without such joints).  It resolves a motion of a tenth of
#: the run's duration with 100 steps, and is no statement about the model's own frequencies.
MIN_STEPS_PER_RUN = 1000

#: Relative tolerance of :func:`penetration_at`, far below the central difference's
#: step (:data:`_STIFFNESS_EPS`), so that the stiffness is taken where the force is.
PENETRATION_RTOL = 1e-12
#: Iterations of that bisection at most; from c = 1 mm to 1e-12 of a 1e-15 m root takes 80.
PENETRATION_MAX_ITER = 200

#: Relative perturbation of the penetration for the tangent stiffness (central difference).
_STIFFNESS_EPS = 1e-6


def penetration_at(law: ContactLaw, force: float) -> float:
    """Penetration [m] at which the elastic force ``F_e`` equals ``force`` [N] > 0.

    Bisection on ``(0, c]`` to :data:`PENETRATION_RTOL` (the elastic forces grow
    monotonically); beyond the clearance the returned value is ``c``, which no steady
    contact reaches.  Bisection, not a faster method, because the implicit line-contact
    laws have no force (NaN) beyond their largest penetration, which may lie below ``c``:
    there the excess force is taken as ``+inf`` (above any force), which bisection,
    working with signs only, handles as it should.  Written here, not taken from
    :func:`scipy.optimize.bisect`: every joint's first run asks for it (the contact period
    of :mod:`exuclear.engine.steering`), and importing ``scipy.optimize`` costs more than a
    small model's whole run.
    """
    if not force > 0.0:
        raise ValueError(f"`force` must be positive, got {force}")
    hi = law.geometry.clearance
    if law.elastic_force(hi) <= force:
        return hi
    lo = 0.0
    for _ in range(PENETRATION_MAX_ITER):
        mid = 0.5 * (lo + hi)
        f = law.elastic_force(mid)
        if math.isnan(f) or f >= force:  # NaN: beyond the law's largest penetration
            hi = mid
        else:
            lo = mid
        if hi - lo <= PENETRATION_RTOL * hi:
            break
    return 0.5 * (lo + hi)


def contact_stiffness(law: ContactLaw, delta: float) -> float:
    """Tangent stiffness ``dF_e/d delta`` [N/m] of the elastic force at ``delta`` > 0."""
    h = _STIFFNESS_EPS * delta
    return (law.elastic_force(delta + h) - law.elastic_force(delta - h)) / (2.0 * h)


def contact_period(law: ContactLaw, mass: float, force: float) -> float:
    """The contact period ``T_c`` [s] (module docstring) of an effective ``mass`` [kg]
    pressed against the wall by ``force`` [N]."""
    if not mass > 0.0 or not math.isfinite(mass):
        raise ValueError(f"`mass` must be positive and finite, got {mass}")
    k = contact_stiffness(law, penetration_at(law, force))
    return 2.0 * math.pi * math.sqrt(mass / k)


#: Gauss-Legendre nodes and weights on [0, 1] (4 points) for :func:`stored_energy` (which
#: :func:`impact_duration` integrates), in the variable ``w`` with ``delta = delta_max w^2``: a power law
#: ``K delta^n`` then integrates as ``2 K delta_max^(n+1) w^(2n+1)``, a polynomial of degree
#: 3 (n = 1) or 4 (n = 1.5) that four points integrate exactly.
_GAUSS_NODES = (0.0694318442029737, 0.3300094782075719, 0.6699905217924281, 0.9305681557970263)
_GAUSS_WEIGHTS = (0.1739274225687269, 0.3260725774312731, 0.3260725774312731, 0.1739274225687269)
#: Relative tolerance of the impact's depth in :func:`impact_duration` (a step threshold, not a result).
_DEPTH_RTOL = 1e-6


def stored_energy(law: ContactLaw, delta: float) -> float:
    """Elastic energy [J] the law stores at penetration ``delta`` > 0: ``int_0^delta F_e``
    (:data:`_GAUSS_NODES`)."""
    total = 0.0
    for w, g in zip(_GAUSS_NODES, _GAUSS_WEIGHTS):
        total += g * 2.0 * w * law.elastic_force(delta * w * w)
    return delta * total


def impact_duration(law: ContactLaw, mass: float, speed: float) -> float:
    """Duration [s] of an elastic impact of an effective ``mass`` [kg] arriving at ``speed``
    [m/s] on the law's elastic force.

    The journal penetrates to ``delta_max``, where the stored energy equals the kinetic
    energy, ``int_0^delta_max F_e = m v^2 / 2`` (:func:`stored_energy`), and the contact
    lasts about ``T = pi delta_max / v``: exact for a linear spring (half a period
    ``pi sqrt(m/k)``); for Hertz's ``K delta^1.5`` the exact duration is ``2.94 delta_max / v``
    (Johnson, *Contact Mechanics*, 1985, section 11.4, eq. (11.24)), 7 % shorter.  The
    damping of the law is left out: the estimate sets a step threshold.  Beyond the
    clearance the depth is taken as ``c``.
    """
    if not mass > 0.0 or not math.isfinite(mass):
        raise ValueError(f"`mass` must be positive and finite, got {mass}")
    if not speed != 0.0 or not math.isfinite(speed):
        raise ValueError(f"`speed` must be non-zero and finite, got {speed}")
    energy = 0.5 * mass * speed * speed
    hi = law.geometry.clearance
    if not stored_energy(law, hi) > energy:  # NaN (beyond a line-contact law's range) counts as above
        depth = hi
    else:
        lo = 0.0
        for _ in range(PENETRATION_MAX_ITER):
            mid = 0.5 * (lo + hi)
            e = stored_energy(law, mid)
            if math.isnan(e) or e >= energy:
                hi = mid
            else:
                lo = mid
            if hi - lo <= _DEPTH_RTOL * hi:
                break
        depth = 0.5 * (lo + hi)
    return math.pi * depth / abs(speed)


#: Samples of the compression phase in which :func:`closed_form_impact` looks for the peak force.
IMPACT_PEAK_SAMPLES = 64
#: Relative tolerance of the bisections of :func:`closed_form_impact`.
IMPACT_DEPTH_RTOL = 1e-10


def impact_restitution(law: ContactLaw, speed: float) -> float:
    """The restitution of the joint's law for an impact at ``speed`` [m/s] > 0: its damping
    factor ``D``, taken at ``D speed / v_min`` below ``v_min`` (docs/physics.md eq. (9):
    the onset velocity in the damping term is at least ``v_min``)."""
    d = law.damping_factor * min(1.0, speed / law.v_min)
    return restitution_of_damping(d) if d > 0.0 else 1.0


def closed_form_impact(law: ContactLaw, mass: float, speed: float) -> tuple[float, float, float]:
    """Peak force [N], duration [s] and largest penetration [m] of one impact of ``mass``
    [kg] at ``speed`` [m/s] on ``F_e(delta) (1 + D' delta_dot / speed)`` (``D'`` as in
    :func:`impact_restitution`).  Along the compression ``u = delta_dot / speed`` falls from 1
    to 0 and ``int_0^delta F_e = m speed^2 ((1 - u) / D' - ln((1 + D') / (1 + D' u)) / D'^2)``
    (Lankarani and Nikravesh 1990, eq. (13), for any ``F_e``; ``(1 - u^2) / 2`` for ``D' = 0``);
    the peak is the largest force over :data:`IMPACT_PEAK_SAMPLES` points of it.  The duration is
    ``pi delta_max / speed`` (:func:`impact_duration`'s estimate)."""
    d = law.damping_factor * min(1.0, speed / law.v_min)
    scale = mass * speed * speed

    def energy(u: float) -> float:  # the stored energy at the rate ratio u
        if d < 1e-8:  # the series' first term: the logarithm's difference loses its digits
            return 0.5 * scale * (1.0 - u * u)
        return scale * ((1.0 - u) / d - math.log((1.0 + d) / (1.0 + d * u)) / (d * d))

    def depth(target: float) -> float:  # the penetration that stores ``target``
        lo, hi = 0.0, law.geometry.clearance
        if not stored_energy(law, hi) > target:
            return hi
        while hi - lo > IMPACT_DEPTH_RTOL * hi:
            mid = 0.5 * (lo + hi)
            lo, hi = (lo, mid) if stored_energy(law, mid) >= target else (mid, hi)
        return 0.5 * (lo + hi)

    delta_max = depth(energy(0.0))
    peak = law.elastic_force(delta_max)
    for k in range(1, IMPACT_PEAK_SAMPLES):
        u = k / IMPACT_PEAK_SAMPLES
        peak = max(peak, law.elastic_force(depth(energy(u))) * (1.0 + d * u))
    return peak, math.pi * delta_max / speed, delta_max


def reduced_mass(m1: float, m2: float) -> float:
    """``m1 m2 / (m1 + m2)``; an infinite mass (the ground) leaves the other."""
    if math.isinf(m1):
        return m2
    if math.isinf(m2):
        return m1
    return m1 * m2 / (m1 + m2)


def step_from_contact_periods(contact_periods: Iterable[float], end_time: float) -> float:
    """The automatic fixed step [s] of a run of ``end_time`` [s] whose clearance joints
    have the ``contact_periods`` [s]: a tenth of the shortest
    (:data:`STEPS_PER_CONTACT_PERIOD`), and no more than ``end_time /``
    :data:`MIN_STEPS_PER_RUN`."""
    step = end_time / MIN_STEPS_PER_RUN
    for period in contact_periods:
        if not period > 0.0 or not math.isfinite(period):
            raise ValueError(f"contact periods must be positive and finite, got {period}")
        step = min(step, period / STEPS_PER_CONTACT_PERIOD)
    return step
