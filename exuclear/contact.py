"""Normal contact force laws for a journal in a bearing: a stiffness model and a damping model.

Every law here has the form of docs/physics.md eq. (9),

    F_N = F_e(delta) * (1 + D * delta_dot / v0_eff),   F_N >= 0,

zero for ``delta <= 0``, with ``v0_eff = max(v0, v_min)``.  Two families supply the two
factors, and a :class:`ContactLaw` is one member of each:

- a :class:`StiffnessModel` gives the elastic force ``F_e(delta)`` of a cylinder in a
  conforming hole (:data:`STIFFNESS_MODELS`), written ``K_eff(delta) * delta^n`` where the
  model is a power law;
- a :class:`DampingModel` gives the constant hysteresis factor ``D`` from the coefficient
  of restitution ``cr`` (:data:`DAMPING_MODELS`).

Every damping model of the literature collected here (Lankarani-Nikravesh, Hunt-Crossley,
Flores et al., Gonthier et al., Hu-Guo, Carvalho-Martins, Zhiying-Qishao, Lee-Wang,
Herbert-McWhannell) writes its dissipation as ``chi delta^n delta_dot`` with
``chi = D K / v0``, that is a constant ``D`` in the formula above; none needs another form.

The five laws exuclear has always offered stay as named pairs with unchanged results
(:data:`CONTACT_LAWS`, :data:`ALIASES`): ``wang-liu`` = ``liu+zhiying-qishao``,
``lankarani-nikravesh`` = ``hertz+lankarani-nikravesh``, ``hertz`` = ``hertz+none``,
``hunt-crossley`` = ``hertz+hunt-crossley``, ``flores`` = ``hertz+flores``.  Any other pair
is named ``"STIFFNESS+DAMPING"``, e.g. ``"pereira+gonthier"``.

The compiled kernel evaluates the same formulas; each stiffness model names its formula by
:attr:`StiffnessModel.kernel_code` and hands the constants it needs over in
:meth:`StiffnessModel.kernel_parameters`.

Units: SI.  Sign convention: ``delta > 0`` is penetration, ``delta_dot > 0`` is approach
(compression), ``v0 > 0`` the approach speed at contact onset.
"""
from __future__ import annotations

import math
import sys
import warnings
from abc import ABC, abstractmethod
from dataclasses import dataclass, field
from typing import ClassVar

from .checks import check_choice, check_open_closed, check_positive, check_real
from .exceptions import ValidityWarning
from .geometry import BearingGeometry

#: Default floor of the onset velocity in the damping term [m/s] (docs/physics.md eq. (17)):
#: grazing contact has v0 -> 0 and D * delta_dot / v0 would blow up.
V_MIN_DEFAULT = 1e-3

#: Hertzian exponent for metallic contact (docs/physics.md section 2.1).
EXPONENT_METAL = 1.5

#: Relative step below which the Newton iteration of the implicit line-contact models
#: stops: Newton converges quadratically there, so the root is then exact to round-off.
IMPLICIT_RTOL = 1e-13
#: Iteration limit of that solve: plain bisection alone would reach round-off in about 60
#: steps, safeguarded Newton needs 4 to 6 on the paper's cases.
IMPLICIT_MAX_ITER = 100

#: Relative tolerance of the restitution relation's roots (:func:`restitution_of_damping`,
#: :func:`damping_for_restitution`): the smallest :func:`scipy.optimize.brentq` accepts,
#: 4 machine epsilons, i.e. round-off (the former bisection stopped at 4 ulp too).
RESTITUTION_RTOL = 4.0 * sys.float_info.epsilon
#: Absolute tolerance of those roots: none beyond the relative one (brentq needs one > 0).
_ROOT_XTOL = 1e-300
#: Iteration limit of those roots: at worst brentq bisects, and from the bracket's end
#: ``1/cr`` down to ``D = 1.5e-16`` (cr = 1 - 1e-16) to round-off takes ~110 halvings.
_ROOT_MAX_ITER = 200

#: Unit conversions of Pereira et al.'s fit, which is written in mm, MPa and N.
_MM = 1e3
_MPA = 1e-6


def _warn_validity(message: str) -> None:
    warnings.warn(message, ValidityWarning, stacklevel=5)


# ======================================================================================
# stiffness models: the elastic force of a cylinder in a conforming hole
# ======================================================================================
@dataclass(frozen=True)
class StiffnessModel(ABC):
    """Elastic normal force ``F_e(delta)`` [N] of a journal pressed into its bearing.

    Parameters
    ----------
    geometry : BearingGeometry
        ``R_J``, ``R_B`` (radial clearance ``c = Delta R = R_B - R_J``) and the length ``L``.
    E_star : float
        Composite modulus [Pa], ``1 / ((1 - nu1^2)/E1 + (1 - nu2^2)/E2)`` (the paper's eq. 9).
    """

    geometry: BearingGeometry
    E_star: float
    name: ClassVar[str] = ""
    #: Which formula the compiled kernel evaluates (see :meth:`kernel_parameters`).
    kernel_code: ClassVar[int] = -1

    def __post_init__(self) -> None:
        if not isinstance(self.geometry, BearingGeometry):
            raise ValueError(f"`geometry` must be a BearingGeometry, got {type(self.geometry).__name__}")
        check_positive("E_star", self.E_star)
        self._setup()

    @abstractmethod
    def _setup(self) -> None:
        """Compute the model's constants once (stored with ``object.__setattr__``)."""

    @property
    @abstractmethod
    def exponent(self) -> float:
        """``n`` in ``K_eff(delta) delta^n``; 1 for the implicit line-contact models."""

    @property
    @abstractmethod
    def k0(self) -> float:
        """The model's leading constant (the first of :meth:`kernel_parameters`)."""

    @abstractmethod
    def stiffness(self, delta: float) -> float:
        """``K_eff(delta) = F_e(delta) / delta^n`` [N/m^n] for ``delta >= 0``."""

    @abstractmethod
    def elastic_force(self, delta: float) -> float:
        """``F_e(delta)`` [N] for ``delta > 0``, else 0."""

    @abstractmethod
    def kernel_parameters(self) -> tuple[float, ...]:
        """The constants the compiled kernel needs for this :attr:`kernel_code` (at most 6)."""



@dataclass(frozen=True)
class _PowerLaw(StiffnessModel):
    """``F_e = K delta^n`` with constant ``K`` and ``n``; ``kernel_parameters() = (K, n)``."""

    _K: float = field(init=False, repr=False, compare=False)
    _n: float = field(init=False, repr=False, compare=False)

    @property
    def exponent(self) -> float:
        return self._n

    @property
    def k0(self) -> float:
        return self._K

    def stiffness(self, delta: float) -> float:
        return self._K

    def elastic_force(self, delta: float) -> float:
        if delta <= 0.0:
            return 0.0
        return self.stiffness(delta) * delta**self._n


    def kernel_parameters(self) -> tuple[float, ...]:
        return (self._K, self._n)


@dataclass(frozen=True)
class PointContact(_PowerLaw):
    """Hertz point contact, as Lankarani and Nikravesh use it for a journal in a bearing.

    ``F_e = K delta^n`` with ``K = (4/3) E* sqrt(R_B R_J / (R_B - R_J))`` [N/m^1.5] and
    ``n = 1.5``: the Hertz law of two spheres of radii ``R_J`` and ``-R_B``.  For cylinders
    it is an approximation (their contact is a line, not a point), stiffer than the line
    contact models at large penetration and softer at small; kept because it is the
    classical choice (docs/physics.md eq. (13); H. M. Lankarani, P. E. Nikravesh, J. Mech. Des.
    112 (1990) 369-376, eq. 4 with the radii of the joint).  No range of validity beyond
    ``delta << c``.  ``exponent`` may be changed (other materials).

    Kernel code 0: ``F_e = p[0] * delta^p[1]``.
    """

    exponent_: float = EXPONENT_METAL
    name: ClassVar[str] = "hertz"
    kernel_code: ClassVar[int] = 0

    def _setup(self) -> None:
        check_positive("exponent", self.exponent_)
        g = self.geometry
        object.__setattr__(self, "_K", 4.0 / 3.0 * self.E_star * math.sqrt(g.bearing_radius * g.journal_radius
                                                                            / g.clearance))
        object.__setattr__(self, "_n", self.exponent_)


@dataclass(frozen=True)
class Liu(StiffnessModel):
    """Liu's improved elastic-foundation model of conformal cylinders, as used by Wang-Liu.

    ``F_e = K0 sqrt(1 / (2 (c + delta))) delta^n`` with ``K0 = pi E* L / 2`` and ``n = 1.5``,
    that is ``F_e = (pi/2) E* L delta sqrt(delta / (2 (c + delta)))`` [N].  Source:
    X. Wang, G. Liu, S. Ma, R. Tong, J. Mech. Sci. Technol. 31(2) (2017) 587-597, eq. (7),
    after C. S. Liu, K. Zhang, L. Yang, "The compliance contact model of cylindrical
    joints with clearances", Acta Mech. Sinica 21 (2005) 451-458.  Derived for a small
    clearance and a contact arc that may approach the whole half-circumference; no
    numerical range is given by the source.  ``exponent`` may be changed.

    Kernel code 1: ``F_e = p[0] * sqrt(1 / (2 (p[1] + delta))) * delta^p[2]``.
    """

    exponent_: float = EXPONENT_METAL
    name: ClassVar[str] = "liu"
    kernel_code: ClassVar[int] = 1
    _K0: float = field(init=False, repr=False, compare=False)
    _c: float = field(init=False, repr=False, compare=False)

    def _setup(self) -> None:
        check_positive("exponent", self.exponent_)
        object.__setattr__(self, "_K0", math.pi * self.E_star * self.geometry.length / 2.0)
        object.__setattr__(self, "_c", self.geometry.clearance)

    @property
    def exponent(self) -> float:
        return self.exponent_

    @property
    def k0(self) -> float:
        return self._K0

    def stiffness(self, delta: float) -> float:
        return self._K0 * math.sqrt(1.0 / (2.0 * (self._c + delta)))

    def elastic_force(self, delta: float) -> float:
        if delta <= 0.0:
            return 0.0
        return self.stiffness(delta) * delta**self.exponent_


    def kernel_parameters(self) -> tuple[float, ...]:
        return (self._K0, self._c, self.exponent_)


@dataclass(frozen=True)
class Pereira(_PowerLaw):
    """Pereira, Ramalho and Ambrosio's power law fitted to finite-element line contact.

    ``F_e = (a Delta R + b) L E* delta^n / Delta R`` with, for internal contact,
    ``a = 0.965``, ``b = 0.0965 mm``, ``n = Y Delta R^-0.005`` and
    ``Y = 1.51 [ln(Delta R / 1 um)]^-0.151`` for ``5 um <= Delta R <= 0.34954 mm``,
    ``Y = 0.0151 Delta R + 1.151`` for ``0.34954 mm <= Delta R <= 10 mm`` (``Delta R`` in
    mm where the fit says so: the formula is stated in mm, MPa and N and converted to SI
    here; the two branches of ``Y`` meet at 0.34954 mm, which confirms those units).
    Source: C. M. Pereira, A. L. Ramalho, J. A. Ambrosio, "A critical overview of internal
    and external cylinder contact force models", Nonlinear Dyn. 63 (2011) 681-697, their
    internal-contact model.  Range of validity: the clearance range of the fit, 5 um to
    10 mm (warns outside, :class:`ValidityWarning`; below 1 um ``Y`` is undefined).

    At the paper's geometry (``Delta R`` = 0.1 mm, L = 15 mm, steel) ``n = 1.213`` and the
    force is within 3 % of Johnson's at 1 um penetration.

    Kernel code 6 (a power law like code 0): ``F_e = p[0] * delta^p[1]``.
    """

    name: ClassVar[str] = "pereira"
    kernel_code: ClassVar[int] = 6
    #: The fit's coefficients for internal contact and its clearance range [mm].
    A: ClassVar[float] = 0.965
    B_MM: ClassVar[float] = 0.0965
    RANGE_MM: ClassVar[tuple[float, float]] = (0.005, 10.0)
    BRANCH_MM: ClassVar[float] = 0.34954

    def _setup(self) -> None:
        g = self.geometry
        dr_mm = g.clearance * _MM
        low, high = self.RANGE_MM
        if dr_mm * 1e3 <= 1.0:
            raise ValueError(f"the pereira stiffness model is undefined for a clearance of 1 um or less "
                             f"(ln(Delta R / 1 um) <= 0), got {g.clearance:g} m")
        if not low <= dr_mm <= high:
            _warn_validity(f"the pereira stiffness model was fitted for clearances of {low:g} to {high:g} mm; "
                           f"the clearance {dr_mm:g} mm is outside that range")
        if dr_mm <= self.BRANCH_MM:
            y = 1.51 * math.log(dr_mm * 1e3) ** -0.151
        else:
            y = 0.0151 * dr_mm + 1.151
        n = y * dr_mm**-0.005
        # F [N] = (a dR_mm + b) L_mm E_MPa / dR_mm * delta_mm^n, written in SI:
        k = (self.A * dr_mm + self.B_MM) * (g.length * _MM) * (self.E_star * _MPA) / dr_mm * _MM**n
        object.__setattr__(self, "_K", k)
        object.__setattr__(self, "_n", n)


@dataclass(frozen=True)
class _LogLineContact(StiffnessModel):
    """Line contact of a cylinder in a conforming hole, implicit in the force.

    ``delta = s (ln(C / s) + beta)`` with ``s = F_e / (pi L E*)`` [m]; each model gives
    ``C`` [m] and ``beta``.  The leading ``F / (pi L E*)`` is fixed by plane elasticity (the
    compliance of two half-planes under a line load), the models differ in the constant
    of the logarithm, that is in where the approach is measured.

    ``delta(s)`` increases on ``0 < s < s_peak = C exp(beta - 1)`` up to
    ``delta_peak = s_peak`` and has no root beyond: there the force is NaN (a run stops
    with a non-finite state; the default penetration limit, half the clearance, lies
    below ``delta_peak`` for every model here).

    The root is found by safeguarded Newton iteration on ``s`` in the bracket
    ``(lo, hi) = (0, s_peak)``, starting from ``s = delta / (ln(C/delta) + beta)`` (an
    upper bound of the root) where that lies in the bracket, else its midpoint::

        s_peak = C * exp(beta - 1)                           # constant
        if delta >= s_peak: return NaN
        lo, hi = 0, s_peak
        s = delta / (ln(C / delta) + beta)  if 0 < that < s_peak  else s_peak / 2
        repeat at most IMPLICIT_MAX_ITER times:
            r = s * (ln(C / s) + beta) - delta
            if r > 0: hi = s  else: lo = s
            s_new = s - r / (ln(C / s) + beta - 1)
            if not lo < s_new < hi: s_new = (lo + hi) / 2
            if |s_new - s| <= IMPLICIT_RTOL * s_new: s = s_new; stop
            s = s_new
        F_e = pi L E* * s

    Kernel parameters: ``(pi L E*, C, beta, IMPLICIT_RTOL, IMPLICIT_MAX_ITER)``.
    """

    _ks: float = field(init=False, repr=False, compare=False)
    _C: float = field(init=False, repr=False, compare=False)
    _beta: float = field(init=False, repr=False, compare=False)
    _s_peak: float = field(init=False, repr=False, compare=False)

    @abstractmethod
    def _log_constants(self) -> tuple[float, float]:
        """``(C, beta)`` of the model."""

    def _setup(self) -> None:
        c, beta = self._log_constants()
        object.__setattr__(self, "_ks", math.pi * self.geometry.length * self.E_star)
        object.__setattr__(self, "_C", c)
        object.__setattr__(self, "_beta", beta)
        object.__setattr__(self, "_s_peak", c * math.exp(beta - 1.0))

    @property
    def exponent(self) -> float:
        return 1.0

    @property
    def k0(self) -> float:
        return self._ks

    @property
    def max_penetration(self) -> float:
        """``delta_peak`` [m]: the largest penetration the formula has a force for."""
        return self._s_peak

    def _solve(self, delta: float) -> float:
        """``s`` with ``s (ln(C/s) + beta) = delta`` (see the class docstring)."""
        c, beta, hi = self._C, self._beta, self._s_peak
        if delta >= hi:
            return math.nan  # beyond the model's largest penetration: no force exists
        lo = 0.0
        s = delta / (math.log(c / delta) + beta)
        if not lo < s < hi:
            s = 0.5 * hi
        for _ in range(IMPLICIT_MAX_ITER):
            log_term = math.log(c / s) + beta
            r = s * log_term - delta
            if r > 0.0:
                hi = s
            else:
                lo = s
            s_new = s - r / (log_term - 1.0)
            if not lo < s_new < hi:
                s_new = 0.5 * (lo + hi)
            if abs(s_new - s) <= IMPLICIT_RTOL * s_new:
                return s_new
            s = s_new
        return s

    def elastic_force(self, delta: float) -> float:
        if delta <= 0.0:
            return 0.0
        return self._ks * self._solve(delta)

    def stiffness(self, delta: float) -> float:
        """``F_e(delta) / delta`` (the secant stiffness; 0 at ``delta = 0``, where ``F_e ~ delta / ln(1/delta)``)."""
        if delta <= 0.0:
            return 0.0
        return self.elastic_force(delta) / delta

    def kernel_parameters(self) -> tuple[float, ...]:
        return (self._ks, self._C, self._beta, IMPLICIT_RTOL, float(IMPLICIT_MAX_ITER))


@dataclass(frozen=True)
class Johnson(_LogLineContact):
    """Johnson's approach of two cylinders in line contact, for a journal in a hole.

    ``delta = (F / (pi L E*)) [ln(4 pi L E* Delta R / F) - 1]``, i.e. ``C = 4 Delta R``,
    ``beta = -1`` (see :class:`_LogLineContact` for the solve).  Johnson's approach of two
    cylinders, ``delta = (F / (pi L E*)) [ln(4 R_1 / b) + ln(4 R_2 / b) - 1]`` with the Hertz
    half-width ``b = 2 sqrt(F R* / (pi L E*))``, becomes this with ``R_1 R_2 / R* = Delta R``
    for the conforming pair (``R* = R_J R_B / Delta R``).  Source: K. L. Johnson, Contact
    Mechanics, Cambridge University Press 1985, section 5.6 (approach of cylinders), in the
    internal-contact form of Pereira et al., Nonlinear Dyn. 63 (2011) 681-697.  Valid for
    a contact half-width small against the radii; the formula has no solution above
    ``delta = 4 Delta R / e^2 = 0.54 Delta R``.

    Kernel code 2 (the implicit solve of :class:`_LogLineContact`).
    """

    name: ClassVar[str] = "johnson"
    kernel_code: ClassVar[int] = 2

    def _log_constants(self) -> tuple[float, float]:
        return 4.0 * self.geometry.clearance, -1.0


@dataclass(frozen=True)
class Radzimovsky(_LogLineContact):
    """Radzimovsky's approach of two cylinders, for a journal in a hole.

    ``delta = (F / (pi L E*)) [2/3 + ln(4 R_J / b) + ln(4 R_B / b)]`` with the Hertz
    half-width ``b = 2 sqrt(F R* / (pi L E*))``, ``R* = R_J R_B / Delta R``, which is
    ``delta = (F / (pi L E*)) [ln(4 pi L E* Delta R / F) + 2/3]``: ``C = 4 Delta R``,
    ``beta = 2/3``.  Source: E. I. Radzimovsky, "Stress distribution and strength
    condition of two rolling cylinders pressed together", Univ. Illinois Eng. Exp. Station
    Bulletin 408 (1953), as compiled by Pereira et al., Nonlinear Dyn. 63 (2011)
    681-697.  Compilations differ in the half-width ``b``: some use ``1.6 sqrt(F R / (L E))``
    with other moduli; the Hertz half-width is used here (the quantity the formula
    names), which moves ``beta`` by at most ``2 ln 1.25 = 0.45``.  Solvable up to
    ``delta = 4 Delta R e^(-1/3) = 2.87 Delta R``.

    Kernel code 3 (the implicit solve of :class:`_LogLineContact`).
    """

    name: ClassVar[str] = "radzimovsky"
    kernel_code: ClassVar[int] = 3

    def _log_constants(self) -> tuple[float, float]:
        return 4.0 * self.geometry.clearance, 2.0 / 3.0


@dataclass(frozen=True)
class ESDU78035(_LogLineContact):
    """The ESDU-78035 line-contact formula for a pin in a hole.

    ``delta = F (s_i + s_j) / L [ln(4 L Delta R / (F (s_i + s_j))) + 1]`` with
    ``s_k = (1 - nu_k^2) / (pi E_k)``, i.e. ``s_i + s_j = 1 / (pi E*)``: ``C = 4 Delta R``,
    ``beta = 1``.  Source: ESDU 78035, "Contact phenomena I: stresses, deflections and
    contact dimensions for normally-loaded unlubricated elastic components", Engineering
    Sciences Data Unit, London 1978, as compiled by Pereira et al. (2011) and by
    P. Flores et al., Kinematics and Dynamics of Multibody Systems with Imperfect Joints,
    Springer 2008.  Compilations differ by a factor pi in the compliance; the form with
    ``s_k`` containing pi is used because it is the only one whose leading term
    ``F / (pi L E*) ln(1/F)`` agrees with plane elasticity (and with Johnson's).  Solvable
    up to ``delta = 4 Delta R``.

    Kernel code 4 (the implicit solve of :class:`_LogLineContact`).
    """

    name: ClassVar[str] = "esdu-78035"
    kernel_code: ClassVar[int] = 4

    def _log_constants(self) -> tuple[float, float]:
        return 4.0 * self.geometry.clearance, 1.0


@dataclass(frozen=True)
class DubowskyFreudenstein(_LogLineContact):
    """Dubowsky and Freudenstein's pin-in-hole compliance.

    ``delta = F (s_i + s_j) / L [ln(L^3 Delta R / (F (s_i + s_j) R_J R_B)) + 1]`` with
    ``s_k = (1 - nu_k^2) / (pi E_k)``, i.e. ``C = L^2 Delta R / (R_J R_B)``, ``beta = 1``
    (``F`` the total force).  Source: S. Dubowsky, F. Freudenstein, "Dynamic analysis of
    mechanical systems with clearances, part 1: formation of dynamic model", J. Eng. Ind.
    93 (1971) 305-309, as compiled by Pereira et al. (2011).  This is the dimensionally
    consistent reading (with ``L^3`` and the total force); the same choice of ``s_k`` as
    for :class:`ESDU78035`.  Solvable up to ``delta = C`` (2.3 ``Delta R`` at the paper's
    geometry).

    Kernel code 5 (the implicit solve of :class:`_LogLineContact`).
    """

    name: ClassVar[str] = "dubowsky-freudenstein"
    kernel_code: ClassVar[int] = 5

    def _log_constants(self) -> tuple[float, float]:
        g = self.geometry
        return g.length**2 * g.clearance / (g.journal_radius * g.bearing_radius), 1.0


#: Name -> stiffness model class.
STIFFNESS_MODELS: dict[str, type[StiffnessModel]] = {
    cls.name: cls for cls in (PointContact, Liu, Johnson, Radzimovsky, ESDU78035, DubowskyFreudenstein, Pereira)
}

#: Stiffness models whose exponent is a free parameter (the others fix their own).
_FREE_EXPONENT = (PointContact, Liu)


def stiffness_model(name: str, geometry: BearingGeometry, E_star: float, exponent: float | None = None) -> StiffnessModel:
    """Build a stiffness model by its name in :data:`STIFFNESS_MODELS`.

    ``exponent`` (default 1.5) applies to ``hertz`` and ``liu``; the other models fix it.
    """
    cls = STIFFNESS_MODELS[check_choice("stiffness", name, STIFFNESS_MODELS)]
    E_star = check_real("E_star", E_star)
    if cls in _FREE_EXPONENT:
        return cls(geometry, E_star, EXPONENT_METAL if exponent is None else exponent)
    if exponent is not None:
        raise ValueError(f"`exponent` is fixed by the {name!r} stiffness model; leave it out")
    return cls(geometry, E_star)


# ======================================================================================
# damping models: the hysteresis factor D from the coefficient of restitution
# ======================================================================================
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
    #: False for the elastic model: it dissipates nothing, so it takes only cr = 1.
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
    for cr >= 0.3 (docs/physics.md section 8); warns below.
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
    return DAMPING_MODELS[check_choice("damping", name, DAMPING_MODELS)](cr)


#: Below this ``|x|``, :func:`_x_minus_log1p` sums its series: ``x - ln(1 + x)`` ~ ``x^2 / 2``
#: is then far smaller than ``x``, and the direct difference would keep only the
#: round-off of ``x``; at 0.1 the series needs 15 terms for round-off.
_SERIES_BELOW = 0.1


def _x_minus_log1p(x: float) -> float:
    """``x - ln(1 + x)`` (>= 0) for ``x > -1``, to round-off also where it is tiny against ``x``.

    The two sides of the restitution relation (:func:`restitution_of_damping`) agree to
    first order in ``D``; written with this function their difference keeps its digits.
    """
    if abs(x) >= _SERIES_BELOW:
        return x - math.log1p(x)
    total, term, k = 0.0, -x, 1  # sum over k >= 2 of (-x)^k / k
    while True:
        k += 1
        term *= -x
        step = term / k
        if total + step == total:
            return total
        total += step


def restitution_of_damping(D: float) -> float:
    """Effective restitution ``e`` of one impact under ``F_e(delta) (1 + D delta_dot / v0)``.

    Exact for a free mass and any elastic force ``F_e``: the root ``0 < e <= 1`` of
    ``D (1 + e) = ln(1 + D) - ln(1 - D e)`` (see :class:`CarvalhoMartinsDamping`), found by
    Brent's method (:func:`scipy.optimize.brentq`) to round-off (:data:`RESTITUTION_RTOL`).
    ``D = 0`` gives 1.  Both sides agree to first order in ``D`` (the relation's slope in
    ``e`` is about ``-D^2``); their difference is written with :func:`_x_minus_log1p`, so
    that it keeps its digits and the root is exact to round-off for small ``D`` too (the
    difference taken directly left an error of about ``2e-16 / D``).
    """
    from scipy.optimize import brentq

    D = check_real("D", D)
    if D < 0.0:
        raise ValueError(f"`D` must be non-negative, got {D}")
    if D == 0.0:
        return 1.0

    def r(e: float) -> float:  # D (1 + e) - ln(1 + D) + ln(1 - D e); decreases in e, r(0) > 0
        return _x_minus_log1p(D) - _x_minus_log1p(-D * e)

    # r(1) < 0, and r -> -inf at e = 1/D (the log's pole): end the bracket just before it
    hi = min(1.0, math.nextafter(1.0 / D, 0.0))
    if not r(hi) < 0.0:  # no sign change that floating point can see
        if D < 1.0:  # r(1) ~ -2 D^3 / 3 underflows (D below ~1e-100): e = 1 - 2 D / 3 to round-off
            return 1.0 - 2.0 * D / 3.0
        return hi  # large D: 1 - D e = (1 + D) exp(-D (1 + e)) is below round-off, e is 1/D to an ulp
    return brentq(r, 0.0, hi, xtol=_ROOT_XTOL, rtol=RESTITUTION_RTOL, maxiter=_ROOT_MAX_ITER)


def damping_for_restitution(cr: float) -> float:
    """The ``D > 0`` whose exact effective restitution is ``cr`` (inverse of :func:`restitution_of_damping`).

    The root of ``h(D) = ln(1 + D) - ln(1 - cr D) - D (1 + cr)`` by Brent's method
    (:func:`scipy.optimize.brentq`) to round-off (:data:`RESTITUTION_RTOL`).  ``h`` is
    negative on ``(0, root)``, positive beyond, and tends to ``+inf`` at ``D = 1/cr``;
    ``D = 0`` is a trivial root, which the bracket leaves out by starting at
    ``3 (1 - cr) / 4``, half of the root's limit ``3 (1 - cr) / 2`` as ``cr -> 1`` (below
    the root on a grid of 1000 values of cr in (0, 1); a bracket without the root would
    raise ``ValueError``, never return a wrong one).  ``h`` is written
    with :func:`_x_minus_log1p`, so that ``h ~ -(1 - cr^2) D^2 / 2`` keeps its digits up
    to ``cr = 1 - 1e-16``.  For small cr (below about 0.03) the root lies within an ulp of
    ``1/cr``, where ``h`` cannot be told from 0 in floating point; that neighbour of
    ``1/cr`` is returned.
    """
    from scipy.optimize import brentq

    cr = check_open_closed("cr", cr, 0.0, 1.0)
    if cr == 1.0:
        return 0.0

    def h(d: float) -> float:  # ln(1 + d) - ln(1 - cr d) - d (1 + cr)
        return _x_minus_log1p(-cr * d) - _x_minus_log1p(d)

    lo = 0.75 * (1.0 - cr)  # half of Hunt and Crossley's factor, the root's limit as cr -> 1
    hi = math.nextafter(1.0 / cr, 0.0)  # h(hi) is finite
    if not h(hi) > 0.0:
        return hi  # small cr: 1 - cr D = (1 + D) exp(-D (1 + cr)) is below round-off, D is 1/cr to an ulp
    return brentq(h, lo, hi, xtol=_ROOT_XTOL, rtol=RESTITUTION_RTOL, maxiter=_ROOT_MAX_ITER)


# ======================================================================================
# eq. (9): the normal force from an elastic force and a damping factor
# ======================================================================================
def damped_normal_force(elastic_force: float, damping_factor: float, v_min: float, delta_dot: float,
                        v0: float) -> float:
    """``F_N = max(0, F_e (1 + D delta_dot / max(v0, v_min)))`` [N], docs/physics.md eq. (9),
    for a penetration ``delta > 0`` whose elastic force is ``elastic_force`` [N].

    The one statement of eq. (9): :meth:`ContactLaw.normal_force` gives it the law's
    ``F_e(delta)``, an end face of the spatial joint ``K_f delta`` (eq. (53)).  No adhesion;
    a NaN stays NaN, to be caught.
    """
    v0_eff = v0 if v0 > v_min else v_min
    f = elastic_force * (1.0 + damping_factor * delta_dot / v0_eff)
    return 0.0 if f < 0.0 else f


# ======================================================================================
# a contact law: one stiffness model and one damping model
# ======================================================================================
@dataclass(frozen=True)
class ContactLaw:
    """A normal contact law: a stiffness model and a damping model (module docstring).

    Parameters
    ----------
    stiffness_model : StiffnessModel
        Elastic force ``F_e(delta)``; carries the geometry and ``E_star``.
    damping_model : DampingModel
        Hysteresis factor ``D``; carries ``cr``.
    v_min : float
        Floor of the onset velocity in the damping term [m/s], > 0.
    """

    stiffness_model: StiffnessModel
    damping_model: DampingModel
    v_min: float = V_MIN_DEFAULT
    _k0: float = field(init=False, repr=False, compare=False)
    _D: float = field(init=False, repr=False, compare=False)

    def __post_init__(self) -> None:
        if not isinstance(self.stiffness_model, StiffnessModel):
            raise ValueError(f"`stiffness_model` must be a StiffnessModel, got {type(self.stiffness_model).__name__}")
        if not isinstance(self.damping_model, DampingModel):
            raise ValueError(f"`damping_model` must be a DampingModel, got {type(self.damping_model).__name__}")
        check_positive("v_min", self.v_min)
        object.__setattr__(self, "_k0", self.stiffness_model.k0)
        object.__setattr__(self, "_D", self.damping_model.factor)

    # -- what the engine glue reads ---------------------------------------------------
    @property
    def name(self) -> str:
        """``"STIFFNESS+DAMPING"``; the five named laws return their own name."""
        return f"{self.stiffness_model.name}+{self.damping_model.name}"

    @property
    def geometry(self) -> BearingGeometry:
        return self.stiffness_model.geometry

    @property
    def E_star(self) -> float:
        return self.stiffness_model.E_star

    @property
    def cr(self) -> float:
        return self.damping_model.cr

    @property
    def exponent(self) -> float:
        return self.stiffness_model.exponent

    @property
    def damping_factor(self) -> float:
        """``D`` of the hysteresis term (dimensionless)."""
        return self._D

    @property
    def kernel_code(self) -> int:
        """The stiffness model's formula in the compiled kernel."""
        return self.stiffness_model.kernel_code

    def kernel_parameters(self) -> tuple[float, ...]:
        """The stiffness model's constants for the compiled kernel."""
        return self.stiffness_model.kernel_parameters()

    def stiffness(self, delta: float) -> float:
        """``K_eff(delta)`` [N/m^n]."""
        return self.stiffness_model.stiffness(delta)

    # -- the shared formula -----------------------------------------------------------
    def elastic_force(self, delta: float) -> float:
        """``F_e(delta) = K_eff(delta) delta^n`` for ``delta > 0``, else 0 [N]."""
        return self.stiffness_model.elastic_force(delta)

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
        return damped_normal_force(self.stiffness_model.elastic_force(delta), self._D, self.v_min, delta_dot, v0)


    def __call__(self, delta: float, delta_dot: float, v0: float) -> float:
        return self.normal_force(delta, delta_dot, v0)


def compose_law(stiffness: str, damping: str, geometry: BearingGeometry, E_star: float, cr: float = 1.0,
                v_min: float = V_MIN_DEFAULT, exponent: float | None = None) -> ContactLaw:
    """The contact law of the stiffness model ``stiffness`` and the damping model ``damping``.

    ``cr`` must be 1 with ``damping="none"``; ``exponent`` applies to the ``hertz`` and
    ``liu`` stiffness models only (default 1.5).
    """
    return ContactLaw(stiffness_model(stiffness, geometry, E_star, exponent), damping_model(damping, cr), v_min)


# -- the five named laws (unchanged results) ---------------------------------------------
class _NamedLaw(ContactLaw):
    """A named pair; built like the former classes: ``(geometry, E_star, cr, v_min, exponent)``."""

    name: ClassVar[str] = ""
    _stiffness: ClassVar[type[StiffnessModel]] = PointContact
    _damping: ClassVar[type[DampingModel]] = NoDamping

    def __init__(self, geometry: BearingGeometry, E_star: float, cr: float = 1.0, v_min: float = V_MIN_DEFAULT,
                 exponent: float = EXPONENT_METAL) -> None:
        super().__init__(self._stiffness(geometry, E_star, exponent), self._damping(cr), v_min)


class WangLiu(_NamedLaw):
    """Wang-Liu law, the paper's eqs. (7)-(8); the default of exuclear: :class:`Liu`
    stiffness and :class:`ZhiyingQishaoDamping`.  Source: X. Wang, G. Liu, S. Ma, R. Tong,
    J. Mech. Sci. Technol. 31(2) (2017) 587-597; docs/physics.md eqs. (11)-(12)."""

    name: ClassVar[str] = "wang-liu"
    _stiffness: ClassVar[type[StiffnessModel]] = Liu
    _damping: ClassVar[type[DampingModel]] = ZhiyingQishaoDamping


class LankaraniNikravesh(_NamedLaw):
    """Lankarani-Nikravesh law: :class:`PointContact` stiffness and
    :class:`LankaraniNikraveshDamping`; docs/physics.md eqs. (13)-(14)."""

    name: ClassVar[str] = "lankarani-nikravesh"
    _damping: ClassVar[type[DampingModel]] = LankaraniNikraveshDamping


class Hertz(_NamedLaw):
    """Hertz law, elastic only: :class:`PointContact` stiffness, no damping; ``cr`` must be 1."""

    name: ClassVar[str] = "hertz"

    def __init__(self, geometry: BearingGeometry, E_star: float, cr: float = 1.0, v_min: float = V_MIN_DEFAULT,
                 exponent: float = EXPONENT_METAL) -> None:
        if check_open_closed("cr", cr, 0.0, 1.0) != 1.0:
            raise ValueError(f"`cr` must be 1 for the elastic Hertz law, got {cr}")
        super().__init__(geometry, E_star, cr, v_min, exponent)


class HuntCrossley(_NamedLaw):
    """Hunt-Crossley law: :class:`PointContact` stiffness and :class:`HuntCrossleyDamping`."""

    name: ClassVar[str] = "hunt-crossley"
    _damping: ClassVar[type[DampingModel]] = HuntCrossleyDamping


class Flores(_NamedLaw):
    """Flores et al. (2011) law: :class:`PointContact` stiffness and :class:`FloresDamping`."""

    name: ClassVar[str] = "flores"
    _damping: ClassVar[type[DampingModel]] = FloresDamping


#: Name -> law class, the five named laws of the API and the command line.
CONTACT_LAWS: dict[str, type[ContactLaw]] = {
    cls.name: cls for cls in (WangLiu, LankaraniNikravesh, Hertz, HuntCrossley, Flores)
}

#: The named laws as (stiffness, damping) pairs.
ALIASES: dict[str, tuple[str, str]] = {
    cls.name: (cls._stiffness.name, cls._damping.name) for cls in (WangLiu, LankaraniNikravesh, Hertz, HuntCrossley,
                                                                    Flores)
}

DEFAULT_LAW = WangLiu.name

#: Separator of a pair's name, ``"STIFFNESS+DAMPING"``.
PAIR_SEPARATOR = "+"


def pair_name(stiffness: str | None = None, damping: str | None = None) -> str:
    """``"STIFFNESS+DAMPING"``; a missing member is that of the default law (``liu``,
    ``zhiying-qishao``)."""
    default_s, default_d = ALIASES[DEFAULT_LAW]
    return f"{stiffness or default_s}{PAIR_SEPARATOR}{damping or default_d}"


def split_law_name(name: str) -> tuple[str, str]:
    """``(stiffness, damping)`` of a law name: a named law or ``"STIFFNESS+DAMPING"``.

    ``ValueError`` listing the known names for an unknown one.
    """
    if isinstance(name, str) and PAIR_SEPARATOR in name:
        stiffness, _, damping = name.partition(PAIR_SEPARATOR)
        check_choice("stiffness", stiffness, STIFFNESS_MODELS)
        check_choice("damping", damping, DAMPING_MODELS)
        return stiffness, damping
    return ALIASES[check_choice("law", name, CONTACT_LAWS)]


def is_elastic(name: str) -> bool:
    """True if the law named ``name`` has no damping (it then takes only ``cr = 1``);
    False for dissipative and for unknown names (which fail where the law is built)."""
    try:
        return not DAMPING_MODELS[split_law_name(name)[1]].dissipative
    except ValueError:
        return False


def contact_law(
    name: str,
    geometry: BearingGeometry,
    E_star: float,
    cr: float = 1.0,
    v_min: float = V_MIN_DEFAULT,
    exponent: float | None = None,
) -> ContactLaw:
    """Build a contact law by its name: one of :data:`CONTACT_LAWS` or ``"STIFFNESS+DAMPING"``
    with names of :data:`STIFFNESS_MODELS` and :data:`DAMPING_MODELS`."""
    if isinstance(name, str) and PAIR_SEPARATOR in name:
        return compose_law(*split_law_name(name), geometry, E_star, cr, v_min, exponent)
    cls = CONTACT_LAWS[check_choice("law", name, CONTACT_LAWS)]
    return cls(geometry, check_real("E_star", E_star), cr, v_min, EXPONENT_METAL if exponent is None else exponent)


def law_and_restitution(law: str | None = None, stiffness: str | None = None, damping: str | None = None,
                        cr: float | None = None, default_law: str = DEFAULT_LAW,
                        default_cr: float = 0.9) -> tuple[str, float]:
    """The law name and ``cr`` a command line's options ask for.

    ``law`` or the pair ``stiffness``/``damping`` (not both; a missing member of the pair
    is that of the default law); ``cr`` defaults to ``default_cr`` for a law with damping
    and to 1 for an elastic one, so that ``--law hertz`` alone is accepted.  Unknown names
    raise ``ValueError`` listing the known ones.
    """
    if stiffness is not None or damping is not None:
        if law is not None:
            raise ValueError("give either `law` or `stiffness`/`damping`, not both")
        law = pair_name(stiffness, damping)
    elif law is None:
        law = default_law
    split_law_name(law)
    if cr is None:
        cr = 1.0 if is_elastic(law) else default_cr
    return law, cr
