"""Friction laws: the friction coefficient as a function of the tangential slip.

A friction law returns ``mu(v_T)``, odd in ``v_T``; the joint then applies
``F_T = mu(v_T) F_N`` against the slip (docs/physics.md section 3, eqs. (20)-(23); the paper's eqs. 10-11).
Units: m/s for velocities.
"""
from __future__ import annotations

import math
from abc import ABC, abstractmethod
from dataclasses import dataclass
from typing import ClassVar

from .checks import check_nonnegative, check_positive, warn_at_caller
from .contact import ValidityWarning

#: Friction coefficients above this warn (:class:`~exuclear.ValidityWarning`), they are not
#: refused.  Source: engineering tables of static friction coefficients, here Lawrence
#: Berkeley Laboratory's compilation (www-eng.lbl.gov/~ajdemell/coefficients_of_friction.html;
#: P. J. Blau, Tribol. Int. 34 (2001) 585-591, on how such tables may be used): clean, dry
#: steel on steel 0.74 to 0.78 static and 0.42 sliding, greased metals mostly 0.05 to 0.3,
#: the paper's Table 1 0.3 / 0.25; only clean, dry soft metals (aluminium on aluminium 1.05 to
#: 1.35, copper on copper 1.0 to 1.2, cast iron on cast iron 1.1) reach 1 or more.  A bearing
#: above 1 is unusual enough to ask whether a percentage or a typo was meant.
MU_WARN = 1.0


def _check_coefficient(name: str, mu: float) -> float:
    """``mu`` >= 0 (``ValueError`` otherwise); a :class:`ValidityWarning` above :data:`MU_WARN`."""
    mu = check_nonnegative(name, mu)
    if mu > MU_WARN:
        warn_at_caller(f"friction coefficient `{name}` = {mu:g} is above {MU_WARN:g}: dry steel on steel is about "
                       "0.75 (static), greased metals 0.05 to 0.3, and only clean, dry soft metals reach 1 to 1.35; "
                       "was a percentage or another value meant?", ValidityWarning)
    return mu


def _sign(x: float) -> float:
    """-1, 0 or 1."""
    return 1.0 if x > 0.0 else (-1.0 if x < 0.0 else 0.0)


def smooth_step(x: float, x0: float, h0: float, x1: float, h1: float) -> float:
    """Cubic step ``S(x; x0, h0, x1, h1) = h0 + (h1 - h0) s^2 (3 - 2 s)`` (docs/physics.md eq. (21)).

    ``s = clip((x - x0) / (x1 - x0), 0, 1)``; value and slope are continuous, with zero
    slope at both ends.
    """
    s = min(max((x - x0) / (x1 - x0), 0.0), 1.0)
    return h0 + (h1 - h0) * s * s * (3.0 - 2.0 * s)


class FrictionLaw(ABC):
    """Base of the friction laws: ``coefficient(v_t) -> mu``.

    The compiled kernel (``exuclear/_kernel/laws.hpp``,
    ``friction_coefficient``) writes the same formulas in the same order; a law it does
    not know runs with the Python kernel only.
    """

    name: ClassVar[str] = ""
    #: False where the law is identically zero, so the joint can skip friction work.
    active: ClassVar[bool] = True

    @abstractmethod
    def coefficient(self, v_t: float) -> float:
        """Friction coefficient ``mu`` for the tangential slip ``v_t`` [m/s]; odd in ``v_t``."""

    @property
    def smoothing_speed(self) -> float:
        """Half-width [m/s] of the band ``|v_t| <`` it where ``mu`` is the smoothed sign, a
        steep function of the slip (0: none)."""
        return 0.0

    def __call__(self, v_t: float) -> float:
        return self.coefficient(v_t)


@dataclass(frozen=True)
class NoFriction(FrictionLaw):
    """Frictionless contact, ``mu = 0`` (the default for the journal-bearing check)."""

    name: ClassVar[str] = "none"
    active: ClassVar[bool] = False

    def coefficient(self, v_t: float) -> float:
        return 0.0


@dataclass(frozen=True)
class Coulomb(FrictionLaw):
    """Coulomb friction with a constant ``mu``, smoothed over ``|v_T| < v_eps``.

    ``mu(v_T) = S(v_T; -v_eps, -mu, v_eps, mu)`` (docs/physics.md eq. (23)): the sign
    function replaced by the cubic step of eq. (21) so that the force is continuous in ``v_T``.

    Parameters
    ----------
    mu : float
        Friction coefficient, >= 0; above :data:`MU_WARN` (1) it warns
        (:class:`~exuclear.ValidityWarning`): unusual for metal bearings.
    v_eps : float
        Half-width of the smoothing band [m/s], > 0.  The default 1e-4 m/s is the
        paper's stiction velocity ``v_s`` (Table 1).
    """

    mu: float
    v_eps: float = 1e-4
    name: ClassVar[str] = "coulomb"

    def __post_init__(self) -> None:
        _check_coefficient("mu", self.mu)
        check_positive("v_eps", self.v_eps)

    @property
    def smoothing_speed(self) -> float:
        return self.v_eps

    def coefficient(self, v_t: float) -> float:
        # S(v; -a, -mu, a, mu) is odd in v; evaluating it at |v| keeps that exact in floats
        return _sign(v_t) * smooth_step(abs(v_t), -self.v_eps, -self.mu, self.v_eps, self.mu)


@dataclass(frozen=True)
class ModifiedCoulomb(FrictionLaw):
    """The paper's modified Coulomb law, eq. (11) (docs/physics.md eq. (22)).

    - ``|v_T| >= v_d``: ``mu = mu_d sign(v_T)``
    - ``v_s <= |v_T| < v_d``: ``mu = S(|v_T|; v_s, mu_s, v_d, mu_d) sign(v_T)``
    - ``|v_T| < v_s``: ``mu = S(v_T; -v_s, -mu_s, v_s, mu_s)``

    Parameters
    ----------
    mu_s, mu_d : float
        Static and dynamic friction coefficients, >= 0; above :data:`MU_WARN` (1) they
        warn (:class:`~exuclear.ValidityWarning`).
    v_s, v_d : float
        Stiction and dynamic-transition velocities [m/s], ``0 < v_s < v_d``.
    """

    mu_s: float
    mu_d: float
    v_s: float
    v_d: float
    name: ClassVar[str] = "paper"

    def __post_init__(self) -> None:
        _check_coefficient("mu_s", self.mu_s)
        _check_coefficient("mu_d", self.mu_d)
        v_s = check_positive("v_s", self.v_s)
        v_d = check_positive("v_d", self.v_d)
        if v_s >= v_d:
            raise ValueError(f"`v_s` must be smaller than `v_d`, got v_s = {v_s}, v_d = {v_d}")

    @classmethod
    def paper(cls) -> ModifiedCoulomb:
        """The paper's Table 1: mu_s = 0.3, mu_d = 0.25, v_s = 0.1 mm/s, v_d = 10 mm/s."""
        return cls(mu_s=0.3, mu_d=0.25, v_s=1e-4, v_d=1e-2)

    @property
    def smoothing_speed(self) -> float:
        return self.v_s

    def coefficient(self, v_t: float) -> float:
        speed = abs(v_t)
        # each branch is evaluated at |v| and signed afterwards, so that mu(-v) = -mu(v) exactly
        if speed < self.v_s:
            mu = smooth_step(speed, -self.v_s, -self.mu_s, self.v_s, self.mu_s)
        elif speed < self.v_d:
            mu = smooth_step(speed, self.v_s, self.mu_s, self.v_d, self.mu_d)
        else:
            mu = self.mu_d
        return _sign(v_t) * mu


NO_FRICTION = NoFriction()

#: Names understood by :func:`friction_law`.
FRICTION_NAMES = ("none", "coulomb:MU", "paper")


def friction_law(spec: str | FrictionLaw) -> FrictionLaw:
    """Friction law from a command-line style name (in any case).

    ``"none"``; ``"coulomb:MU"`` (smoothed Coulomb with constant ``MU``); ``"paper"``
    (eq. 11 with the Table 1 values).  A :class:`FrictionLaw` is returned unchanged.
    """
    if isinstance(spec, FrictionLaw):
        return spec
    if isinstance(spec, str):
        spec = spec.lower()  # "Coulomb:0.1" as "coulomb:0.1"
    if spec == "none":
        return NO_FRICTION
    if spec == "paper":
        return ModifiedCoulomb.paper()
    if isinstance(spec, str) and spec.startswith("coulomb:"):
        text = spec.split(":", 1)[1]
        try:
            mu = float(text)
        except ValueError:
            raise ValueError(f"`friction` coulomb:MU needs a number for MU, got {text!r}") from None
        if not math.isfinite(mu):
            raise ValueError(f"`friction` coulomb:MU needs a finite MU, got {text!r}")
        return Coulomb(mu)
    raise ValueError(f"unknown `friction` {spec!r}; known: {', '.join(FRICTION_NAMES)}")
