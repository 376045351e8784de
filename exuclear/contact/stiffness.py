"""Stiffness models: the elastic force ``F_e(delta)`` of a body in a conforming hole.

Each takes a :class:`~exuclear.contact.pair.ContactGeometry`: Hertz's point contact
(:class:`PointContact`) serves every joint type; the line-contact models (a cylinder in a
bore) need its length and refuse a point contact (:func:`~exuclear.contact.pair.line_length`).

The first factor of docs/physics.md eq. (9) (section 2.2); :data:`STIFFNESS_MODELS` names
them.  Each model names its formula for the compiled kernel by
:attr:`StiffnessModel.kernel_code` and hands the constants it needs over in
:meth:`StiffnessModel.kernel_parameters`.  Units: SI; ``delta > 0`` is penetration.
"""
from __future__ import annotations

import math
from abc import ABC, abstractmethod
from dataclasses import dataclass, field
from typing import ClassVar

from ..checks import check_choice, check_positive, check_real
from ._validity import _warn_validity
from .pair import ContactGeometry, line_length

#: Hertzian exponent for metallic contact (docs/physics.md section 2.1, eq. (9)).
EXPONENT_METAL = 1.5

#: Relative step below which the Newton iteration of the implicit line-contact models
#: stops: Newton converges quadratically there, so the root is then exact to round-off.
IMPLICIT_RTOL = 1e-13
#: Iteration limit of that solve: plain bisection alone would reach round-off in about 60
#: steps, safeguarded Newton needs 4 to 6 on the paper's cases.
IMPLICIT_MAX_ITER = 100

#: Unit conversions of Pereira et al.'s fit, which is written in mm, MPa and N.
_MM = 1e3
_MPA = 1e-6


@dataclass(frozen=True)
class StiffnessModel(ABC):
    """Elastic normal force ``F_e(delta)`` [N] of a journal pressed into its bearing.

    Parameters
    ----------
    geometry : ContactGeometry
        The radii ``R_J``, ``R_B`` of the inner and outer body (radial clearance
        ``c = Delta R = R_B - R_J``) and, for a line contact, the length ``L``.
    E_star : float
        Composite modulus [Pa], ``1 / ((1 - nu1^2)/E1 + (1 - nu2^2)/E2)`` (the paper's eq. 9).
    """

    geometry: ContactGeometry
    E_star: float
    name: ClassVar[str] = ""
    #: Which formula the compiled kernel evaluates (see :meth:`kernel_parameters`).
    kernel_code: ClassVar[int] = -1

    def __post_init__(self) -> None:
        if not isinstance(self.geometry, ContactGeometry):
            raise ValueError(f"`geometry` must be a ContactGeometry (a joint type's geometry), got "
                             f"{type(self.geometry).__name__}")
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
        """The constants the compiled kernel needs for this :attr:`kernel_code` (at most 5: the
        parameter matrix's ``stiffness_constants``)."""



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
        object.__setattr__(self, "_K", 4.0 / 3.0 * self.E_star * math.sqrt(g.outer_radius * g.inner_radius
                                                                            / g.clearance))
        object.__setattr__(self, "_n", self.exponent_)


@dataclass(frozen=True)
class GivenStiffness(_PowerLaw):
    """A given ``F_e = K delta^n``, for a contact without radii of curvature (a slider's
    corner against a flat wall, :mod:`exuclear.prismatic`): ``K`` [N/m^n] and the exponent
    ``n`` are the user's (Flores, Ambrosio, Claro, Lankarani 2008 take Hertz's form with a
    fitted ``K``).  ``E_star`` is not read.

    Kernel code 0: ``F_e = p[0] * delta^p[1]``.
    """

    K: float = 0.0
    exponent_: float = EXPONENT_METAL
    name: ClassVar[str] = "given"
    kernel_code: ClassVar[int] = 0

    def _setup(self) -> None:
        object.__setattr__(self, "_K", check_positive("stiffness", self.K))
        object.__setattr__(self, "_n", check_positive("exponent", self.exponent_))


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
        object.__setattr__(self, "_K0", math.pi * self.E_star * line_length(self.geometry, self.name) / 2.0)
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
        length = line_length(g, self.name)
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
        k = (self.A * dr_mm + self.B_MM) * (length * _MM) * (self.E_star * _MPA) / dr_mm * _MM**n
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
        length = line_length(self.geometry, self.name)
        c, beta = self._log_constants()
        object.__setattr__(self, "_ks", math.pi * length * self.E_star)
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
            slope = log_term - 1.0  # d(s ln(C/s) + beta s)/ds: 0 at the peak, where Newton has no step
            s_new = s - r / slope if slope > 0.0 else math.nan
            if not lo < s_new < hi:  # NaN included: bisect
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
    geometry).  The radii enter only as the relative curvature ``Delta R / (R_J R_B) = 1/R_J -
    1/R_B`` (:attr:`ContactGeometry.relative_curvature`), and ``C`` stays finite as ``R_B``
    grows: its limit ``C = L^2 / R_J`` is a cylinder of radius ``R_J`` on a flat, which is how
    a slider's rounded corner edge takes this model (:func:`exuclear.joint.make_prismatic_joint`).
    The other line models measure the approach between the two centres (``C = 4 Delta R``)
    or fit a conforming pair, and have no flat limit.

    Kernel code 5 (the implicit solve of :class:`_LogLineContact`).
    """

    name: ClassVar[str] = "dubowsky-freudenstein"
    kernel_code: ClassVar[int] = 5

    def _log_constants(self) -> tuple[float, float]:
        g = self.geometry
        return g.length**2 * g.relative_curvature, 1.0


#: Name -> stiffness model class.
STIFFNESS_MODELS: dict[str, type[StiffnessModel]] = {
    cls.name: cls for cls in (PointContact, Liu, Johnson, Radzimovsky, ESDU78035, DubowskyFreudenstein, Pereira)
}

#: Stiffness models whose exponent is a free parameter (the others fix their own).
_FREE_EXPONENT = (PointContact, Liu)


def stiffness_model(name: str, geometry: ContactGeometry, E_star: float, exponent: float | None = None) -> StiffnessModel:
    """Build a stiffness model by its name in :data:`STIFFNESS_MODELS`.

    ``exponent`` (default 1.5) applies to ``hertz`` and ``liu``; the other models fix it.
    """
    cls = STIFFNESS_MODELS[check_choice("stiffness", name, STIFFNESS_MODELS, ignore_case=True)]
    E_star = check_real("E_star", E_star)
    if cls in _FREE_EXPONENT:
        return cls(geometry, E_star, EXPONENT_METAL if exponent is None else exponent)
    if exponent is not None:
        raise ValueError(f"`exponent` is fixed by the {name!r} stiffness model; leave it out")
    return cls(geometry, E_star)

