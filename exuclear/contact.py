"""Normal contact force laws for a journal in a bearing.

Every law here has the form of MODEL.md section 2,

    F_N = K_eff(delta) * delta^n * (1 + D * delta_dot / v0_eff),   F_N >= 0,

zero for ``delta <= 0``, with ``v0_eff = max(v0, v_min)``.  A law is its parameters
plus two pieces of formula: :meth:`ContactLaw.stiffness` (``K_eff``) and
:attr:`ContactLaw.damping_factor` (``D``); :meth:`ContactLaw.normal_force` is shared.
Units: SI.  Sign convention: ``delta > 0`` is penetration, ``delta_dot > 0`` is
approach (compression), ``v0 > 0`` the approach speed at contact onset.
"""
from __future__ import annotations

import math
from abc import ABC, abstractmethod
from collections.abc import Callable
from dataclasses import dataclass, field
from typing import ClassVar

from ._checks import check_choice, check_open_closed, check_positive, check_real
from .geometry import BearingGeometry

#: Default floor of the onset velocity in the damping term [m/s] (MODEL.md section 2):
#: grazing contact has v0 -> 0 and D * delta_dot / v0 would blow up.
V_MIN_DEFAULT = 1e-3

#: Hertzian exponent for metallic contact (MODEL.md section 2).
EXPONENT_METAL = 1.5


@dataclass(frozen=True)
class ContactLaw(ABC):
    """Base of the normal contact laws; see the module docstring.

    Parameters
    ----------
    geometry : BearingGeometry
        Journal and bearing radii, bearing length.
    E_star : float
        Composite modulus [Pa], eq. (9); see :func:`exuclear.composite_modulus`.
    cr : float
        Coefficient of restitution, ``0 < cr <= 1``.
    v_min : float
        Floor of the onset velocity in the damping term [m/s], > 0.
    exponent : float
        Exponent ``n`` of the penetration (1.5 for metals), > 0.
    """

    geometry: BearingGeometry
    E_star: float
    cr: float = 1.0
    v_min: float = V_MIN_DEFAULT
    exponent: float = EXPONENT_METAL
    name: ClassVar[str] = ""
    _k0: float = field(init=False, repr=False, compare=False)

    def __post_init__(self) -> None:
        if not isinstance(self.geometry, BearingGeometry):
            raise ValueError(f"`geometry` must be a BearingGeometry, got {type(self.geometry).__name__}")
        check_positive("E_star", self.E_star)
        check_open_closed("cr", self.cr, 0.0, 1.0)
        check_positive("v_min", self.v_min)
        check_positive("exponent", self.exponent)
        object.__setattr__(self, "_k0", self._stiffness_constant())

    # -- the two pieces a law defines -------------------------------------------------
    @abstractmethod
    def _stiffness_constant(self) -> float:
        """The delta-independent factor of ``K_eff`` (computed once)."""

    def stiffness(self, delta: float, sqrt: Callable[[float], float] = math.sqrt) -> float:
        """``K_eff(delta)`` [N/m^n]; constant unless the law says otherwise.

        ``sqrt`` is injectable so that a compiled backend can evaluate the same
        formula on symbolic numbers.
        """
        return self._k0

    @property
    @abstractmethod
    def damping_factor(self) -> float:
        """``D`` of the hysteresis term (dimensionless)."""

    # -- shared formula ---------------------------------------------------------------
    def elastic_force(self, delta: float) -> float:
        """``K_eff(delta) * delta^n`` for ``delta > 0``, else 0 [N]."""
        if delta <= 0.0:
            return 0.0
        return self.stiffness(delta) * delta**self.exponent

    def normal_force(self, delta: float, delta_dot: float, v0: float) -> float:
        """Normal contact force ``F_N >= 0`` [N].

        Parameters
        ----------
        delta : float
            Penetration [m]; no force for ``delta <= 0``.
        delta_dot : float
            Penetration rate [m/s].
        v0 : float
            Penetration rate at the onset of the current contact [m/s]; replaced by
            ``v_min`` where smaller (this includes ``v0 <= 0``).
        """
        if delta <= 0.0:
            return 0.0
        v0_eff = v0 if v0 > self.v_min else self.v_min
        f = self.stiffness(delta) * delta**self.exponent * (1.0 + self.damping_factor * delta_dot / v0_eff)
        return 0.0 if f < 0.0 else f  # no adhesion (MODEL.md section 2); a NaN stays NaN, to be caught

    def force_expression(self, delta, delta_dot, v0, ops):
        """:meth:`normal_force` written against a math backend ``ops`` (:mod:`exuclear._ops`),
        for the compiled element; the same formula, with branches as ``ops.where``."""
        v0_eff = ops.max(v0, self.v_min)
        depth = ops.max(delta, 0.0)  # keeps the untaken branch real where floats evaluate both
        f = self.stiffness(depth, ops.sqrt) * depth**self.exponent * (1.0 + self.damping_factor * delta_dot / v0_eff)
        return ops.where(delta > 0.0, ops.max(f, 0.0), 0.0)

    def __call__(self, delta: float, delta_dot: float, v0: float) -> float:
        return self.normal_force(delta, delta_dot, v0)


def _conformal_hertz_constant(law: ContactLaw) -> float:
    """``(4/3) E* sqrt(R_B R_J / (R_B - R_J))``: Hertz stiffness of a cylinder in a hole."""
    g = law.geometry
    return 4.0 / 3.0 * law.E_star * math.sqrt(g.bearing_radius * g.journal_radius / g.clearance)


@dataclass(frozen=True)
class WangLiu(ContactLaw):
    """Wang-Liu law, the paper's eqs. (7)-(8); the default of exuclear.

    ``K_eff(delta) = (pi E* L / 2) * sqrt(1 / (2 (c + delta)))`` (Liu's improved
    elastic-foundation stiffness for conformal cylinders) and
    ``D = 3 (1 - cr^2) exp(2 (1 - cr)) / 4`` (hysteresis factor of Zhiying and Qishao,
    2006).  Source: X. Wang, G. Liu, S. Ma, R. Tong, J. Mech. Sci. Technol. 31(2)
    (2017) 587-597, eqs. (7)-(8); MODEL.md section 2.
    """

    name: ClassVar[str] = "wang-liu"

    def _stiffness_constant(self) -> float:
        return math.pi * self.E_star * self.geometry.length / 2.0

    def stiffness(self, delta: float, sqrt: Callable[[float], float] = math.sqrt) -> float:
        return self._k0 * sqrt(1.0 / (2.0 * (self.geometry.clearance + delta)))

    @property
    def damping_factor(self) -> float:
        return 3.0 * (1.0 - self.cr**2) * math.exp(2.0 * (1.0 - self.cr)) / 4.0


@dataclass(frozen=True)
class LankaraniNikravesh(ContactLaw):
    """Lankarani-Nikravesh law.

    ``K = (4/3) E* sqrt(R_B R_J / (R_B - R_J))`` and ``D = 3 (1 - cr^2) / 4``.
    Source: H. M. Lankarani, P. E. Nikravesh, "A contact force model with hysteresis
    damping for impact analysis of multibody systems", J. Mech. Des. 112 (1990)
    369-376; MODEL.md section 2.
    """

    name: ClassVar[str] = "lankarani-nikravesh"

    def _stiffness_constant(self) -> float:
        return _conformal_hertz_constant(self)

    @property
    def damping_factor(self) -> float:
        return 3.0 * (1.0 - self.cr**2) / 4.0


@dataclass(frozen=True)
class Hertz(ContactLaw):
    """Hertz law, elastic only: the Lankarani-Nikravesh stiffness and ``D = 0``.

    ``cr`` must be 1 (the law dissipates nothing).  Source: MODEL.md section 2.
    """

    name: ClassVar[str] = "hertz"

    def __post_init__(self) -> None:
        super().__post_init__()
        if self.cr != 1.0:
            raise ValueError(f"`cr` must be 1 for the elastic Hertz law, got {self.cr}")

    def _stiffness_constant(self) -> float:
        return _conformal_hertz_constant(self)

    @property
    def damping_factor(self) -> float:
        return 0.0


@dataclass(frozen=True)
class HuntCrossley(ContactLaw):
    """Hunt-Crossley law with the Lankarani-Nikravesh (Hertz) stiffness.

    ``D = 3 (1 - cr) / 2``.  Source: K. H. Hunt, F. R. E. Crossley, "Coefficient of
    restitution interpreted as damping in vibroimpact", J. Appl. Mech. 42 (1975)
    440-445 (the relation ``chi = 3 (1 - cr) / (2 v0)`` in their notation).
    """

    name: ClassVar[str] = "hunt-crossley"

    def _stiffness_constant(self) -> float:
        return _conformal_hertz_constant(self)

    @property
    def damping_factor(self) -> float:
        return 1.5 * (1.0 - self.cr)


@dataclass(frozen=True)
class Flores(ContactLaw):
    """Flores et al. (2011) law with the Lankarani-Nikravesh (Hertz) stiffness.

    ``D = 8 (1 - cr) / (5 cr)``.  Source: P. Flores, M. Machado, M. T. Silva,
    J. M. Martins, "On the continuous contact force models for soft materials in
    multibody dynamics", Multibody Syst. Dyn. 25 (2011) 357-375 (their
    hysteresis factor ``chi = 8 (1 - cr) K / (5 cr v0)``).
    """

    name: ClassVar[str] = "flores"

    def _stiffness_constant(self) -> float:
        return _conformal_hertz_constant(self)

    @property
    def damping_factor(self) -> float:
        return 8.0 * (1.0 - self.cr) / (5.0 * self.cr)


#: Name -> law class, the names used on the API and the command line.
CONTACT_LAWS: dict[str, type[ContactLaw]] = {
    cls.name: cls for cls in (WangLiu, LankaraniNikravesh, Hertz, HuntCrossley, Flores)
}

DEFAULT_LAW = WangLiu.name


def contact_law(
    name: str,
    geometry: BearingGeometry,
    E_star: float,
    cr: float = 1.0,
    v_min: float = V_MIN_DEFAULT,
    exponent: float = EXPONENT_METAL,
) -> ContactLaw:
    """Build a contact law by its name in :data:`CONTACT_LAWS`."""
    cls = CONTACT_LAWS[check_choice("law", name, CONTACT_LAWS)]
    return cls(geometry, check_real("E_star", E_star), cr, v_min, exponent)
