"""Damping models: the hysteresis factor ``D`` of docs/physics.md eq. (9) from the coefficient of restitution.

Every damping model of the literature collected here (Lankarani-Nikravesh, Hunt-Crossley,
Flores et al., Gonthier et al., Hu-Guo, Carvalho-Martins, Zhiying-Qishao, Lee-Wang,
Herbert-McWhannell) writes its dissipation as ``chi delta^n delta_dot`` with
``chi = D K / v0``, that is a constant ``D`` in ``F_e (1 + D delta_dot / v0)``;
:data:`DAMPING_MODELS` names them (docs/physics.md section 2.2).
"""
from __future__ import annotations

import math
from abc import ABC, abstractmethod
from dataclasses import dataclass, field
from typing import ClassVar

from ..checks import check_choice, check_open_closed
from ._validity import _warn_validity
from .restitution import damping_for_restitution


@dataclass(frozen=True)
class DampingModel(ABC):
    """Hysteresis damping ``D`` (dimensionless) in ``F_e (1 + D delta_dot / v0)``.

    In the notation of the sources, ``F = K delta^n + chi delta^n delta_dot`` with
    ``chi = D K / v0`` (``v0`` the approach speed at impact).  For a single impact of a
    free mass the effective restitution (departure/impact speed) ``e`` of this force is
    a function of ``D`` alone, whatever ``F_e``: see :func:`restitution_of_damping`.

    Parameters
    ----------
    cr : float
        Coefficient of restitution, ``0 < cr <= 1``.
    """

    cr: float = 1.0
    name: ClassVar[str] = ""
    #: False for the elastic model, which dissipates nothing and so takes only cr = 1.
    dissipative: ClassVar[bool] = True
    #: Smallest cr the source establishes the model for (warns below).
    cr_valid_from: ClassVar[float] = 0.0
    _D: float = field(init=False, repr=False, compare=False)

    def __post_init__(self) -> None:
        check_open_closed("cr", self.cr, 0.0, 1.0)
        if self.cr < self.cr_valid_from:
            _warn_validity(f"the {self.name!r} damping model is established for cr >= {self.cr_valid_from:g}, "
                           f"got cr = {self.cr:g}; its effective restitution departs from cr below that")
        object.__setattr__(self, "_D", self._factor())

    @abstractmethod
    def _factor(self) -> float:
        """``D(cr)``."""

    @property
    def factor(self) -> float:
        """``D`` (computed once)."""
        return self._D


@dataclass(frozen=True)
class NoDamping(DampingModel):
    """Elastic contact: ``D = 0``; only ``cr = 1`` is accepted (nothing is dissipated)."""

    name: ClassVar[str] = "none"
    dissipative: ClassVar[bool] = False

    def __post_init__(self) -> None:
        check_open_closed("cr", self.cr, 0.0, 1.0)
        if self.cr != 1.0:
            raise ValueError(f"`cr` must be 1 without damping (damping 'none' dissipates no energy, so every impact "
                             f"returns at its approach speed); got cr = {self.cr}: choose a damping model")
        super().__post_init__()

    def _factor(self) -> float:
        return 0.0


@dataclass(frozen=True)
class LankaraniNikraveshDamping(DampingModel):
    """``D = 3 (1 - cr^2) / 4``.

    Source: H. M. Lankarani, P. E. Nikravesh, "A contact force model with hysteresis
    damping for impact analysis of multibody systems", J. Mech. Des. 112 (1990) 369-376
    (``chi = 3 K (1 - cr^2) / (4 v0)``).  Derived from the energy loss of an impact for
    cr close to 1; its effective restitution is too high for low cr (table of
    ``validation/contact_laws.py``).
    """

    name: ClassVar[str] = "lankarani-nikravesh"

    def _factor(self) -> float:
        return 3.0 * (1.0 - self.cr**2) / 4.0


@dataclass(frozen=True)
class HuntCrossleyDamping(DampingModel):
    """``D = 3 (1 - cr) / 2``.

    Source: K. H. Hunt, F. R. E. Crossley, "Coefficient of restitution interpreted as
    damping in vibroimpact", J. Appl. Mech. 42 (1975) 440-445 (``lambda = 3 (1 - cr) K /
    (2 v0)``, from a linearisation valid for cr close to 1).
    """

    name: ClassVar[str] = "hunt-crossley"

    def _factor(self) -> float:
        return 1.5 * (1.0 - self.cr)


@dataclass(frozen=True)
class FloresDamping(DampingModel):
    """``D = 8 (1 - cr) / (5 cr)``.

    Source: P. Flores, M. Machado, M. T. Silva, J. M. Martins, "On the continuous contact
    force models for soft materials in multibody dynamics", Multibody Syst. Dyn. 25
    (2011) 357-375 (``chi = 8 (1 - cr) K / (5 cr v0)``); meant for the whole range of cr.
    """

    name: ClassVar[str] = "flores"

    def _factor(self) -> float:
        return 8.0 * (1.0 - self.cr) / (5.0 * self.cr)


@dataclass(frozen=True)
class GonthierDamping(DampingModel):
    """``D = (1 - cr^2) / cr``.

    Source: Y. Gonthier, J. McPhee, C. Lange, J.-C. Piedboeuf, "A regularized contact
    model with asymmetric damping and dwell-time dependent friction", Multibody Syst.
    Dyn. 11 (2004) 209-233 (their approximation ``d = (1 - cr^2) / (cr v0)`` of the
    damping of the Hunt-Crossley force).
    """

    name: ClassVar[str] = "gonthier"

    def _factor(self) -> float:
        return (1.0 - self.cr**2) / self.cr


@dataclass(frozen=True)
class HuGuoDamping(DampingModel):
    """``D = 3 (1 - cr) / (2 cr)``.

    Source: S. Hu, X. Guo, "A dissipative contact force model for impact analysis in
    multibody dynamics", Multibody Syst. Dyn. 35 (2015) 131-151.  Compilations quote the
    factor both as ``3 (1 - cr) / (2 cr)`` and as half of it, ``3 (1 - cr) / (4 cr)``.  The
    paper itself could not be read here; the first form is used because it is the one
    that does what the paper claims, a restitution close to cr over the whole range: its
    exact effective restitution (:func:`restitution_of_damping`) stays within 0.035 of cr
    for cr >= 0.1 (largest gap at cr = 0.2), while the half form gives 0.15 at cr = 0.1,
    0.66 at cr = 0.5 and 0.45 at cr = 0.3 (``validation/contact_laws.py`` tabulates both).
    """

    name: ClassVar[str] = "hu-guo"

    def _factor(self) -> float:
        return 3.0 * (1.0 - self.cr) / (2.0 * self.cr)


@dataclass(frozen=True)
class CarvalhoMartinsDamping(DampingModel):
    """The exact damping of the Hunt-Crossley form: ``D`` with ``e(D) = cr``.

    For ``m x'' = -F_e(x) (1 + D x' / v0)`` the first integral
    ``m v dv / (1 + D v / v0) = -F_e(x) dx`` closes over an impact for any ``F_e`` and
    gives the departure speed ``e v0`` through ``(1 + D) / (1 - D e) = exp(D (1 + e))``.
    This model takes the root ``D > 0`` of that relation at ``e = cr`` (:func:`damping_for_restitution`, to
    round-off, once, at construction; ``D -> 3 (1 - cr) / 2`` as ``cr -> 1``, Hunt and
    Crossley's value).  Source: A. S. Carvalho, J. M. Martins, "Exact restitution and
    generalizations for the Hunt-Crossley contact model", Mech. Mach. Theory 139 (2019)
    174-194, which derives this exact restitution; their explicit approximations of the
    root are not used (the paper could not be read here: the relation above is derived
    in this docstring and checked against an independent integration in the tests).
    Valid for every cr in (0, 1].
    """

    name: ClassVar[str] = "carvalho-martins"

    def _factor(self) -> float:
        return damping_for_restitution(self.cr)


@dataclass(frozen=True)
class ZhiyingQishaoDamping(DampingModel):
    """``D = 3 (1 - cr^2) exp(2 (1 - cr)) / 4``.

    Source: Q. Zhiying, L. Qishao, "Analysis of impact process based on restitution
    coefficient", J. Dyn. Control 4 (2006) 294-298, as used by X. Wang, G. Liu, S. Ma,
    R. Tong, J. Mech. Sci. Technol. 31(2) (2017) 587-597, eq. (8).  Wang et al. claim it
    for cr >= 0.3 (docs/physics.md section 2.2); warns below.
    """

    name: ClassVar[str] = "zhiying-qishao"
    cr_valid_from: ClassVar[float] = 0.3

    def _factor(self) -> float:
        return 3.0 * (1.0 - self.cr**2) * math.exp(2.0 * (1.0 - self.cr)) / 4.0


@dataclass(frozen=True)
class LeeWangDamping(DampingModel):
    """``D = 3 (1 - cr) / 4``.

    Source: T. W. Lee, A. C. Wang, "On the dynamics of intermittent-motion mechanisms,
    part 1: dynamic model and response", J. Mech. Transm. Autom. Des. 105 (1983) 534-540
    (``chi = 3 K (1 - cr) / (4 v0)``); half the Hunt-Crossley factor, so its effective
    restitution is well above cr unless cr is close to 1.
    """

    name: ClassVar[str] = "lee-wang"

    def _factor(self) -> float:
        return 0.75 * (1.0 - self.cr)


@dataclass(frozen=True)
class HerbertMcWhannellDamping(DampingModel):
    """``D = 6 (1 - cr) / ((2 cr - 1)^2 + 3)``.

    Source: R. G. Herbert, D. C. McWhannell, "Shape and frequency composition of pulses
    from an impact pair", J. Eng. Ind. 99 (1977) 513-518 (``chi = 6 (1 - cr) K /
    (((2 cr - 1)^2 + 3) v0)``).
    """

    name: ClassVar[str] = "herbert-mcwhannell"

    def _factor(self) -> float:
        return 6.0 * (1.0 - self.cr) / ((2.0 * self.cr - 1.0) ** 2 + 3.0)


#: Name -> damping model class.
DAMPING_MODELS: dict[str, type[DampingModel]] = {
    cls.name: cls for cls in (NoDamping, LankaraniNikraveshDamping, HuntCrossleyDamping, FloresDamping,
                              GonthierDamping, HuGuoDamping, CarvalhoMartinsDamping, ZhiyingQishaoDamping,
                              LeeWangDamping, HerbertMcWhannellDamping)
}


def damping_model(name: str, cr: float = 1.0) -> DampingModel:
    """Build a damping model by its name in :data:`DAMPING_MODELS`."""
    return DAMPING_MODELS[check_choice("damping", name, DAMPING_MODELS, ignore_case=True)](cr)
