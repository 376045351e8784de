"""The three film models (short, long, finite bearing) and the lubricant that picks one.

Each :class:`FilmLaw` is a viscosity and a bearing with one call signature; the models
differ only in the force in the frame of the line of centres (:meth:`FilmLaw.components`,
physics.md eqs. (58)-(67)).  :class:`Lubrication` is what a user gives: a viscosity and a
model's name.  Pure physics: no exudyn, no state.
"""
from __future__ import annotations

import math
from abc import ABC, abstractmethod
from dataclasses import dataclass, field
from typing import ClassVar

from ..checks import check_choice, check_open, check_positive, warn_unit
from ..geometry import BearingGeometry
from .loads import EPS_CAP_DEFAULT, EPS_FILM_DEFAULT, FilmKinematics, FilmLoad, blend_eccentricity, film_kinematics, relative_clearance

#: A viscosity above this [Pa s] (honey, bitumen) is more likely one given in mPa s.
VISCOSITY_WARN_ABOVE = 10.0


# -- the three models -----------------------------------------------------------------------------
@dataclass(frozen=True)
class FilmLaw(ABC):
    """A film law bound to a bearing: viscosity and geometry, one call signature.

    ``load(ex, ey, vx, vy, omega_journal, omega_bearing) -> FilmLoad`` for ``eps < 1``
    (physics.md eqs. (68)-(69)); the model supplies the force in the frame of the line of
    centres, :meth:`components`.  :meth:`blended_load` is the film as the joint applies
    it near the wall (eq. (70)).

    Parameters
    ----------
    viscosity : float
        Dynamic viscosity ``eta`` [Pa s], > 0.
    geometry : BearingGeometry
        ``R = journal_radius``, ``c = clearance``, ``B = length``.
    eps_film, eps_cap : float
        Thresholds of the blend to metal contact, eq. (70); ``0 < eps_film < eps_cap < 1``.
    """

    viscosity: float
    geometry: BearingGeometry
    eps_film: float = EPS_FILM_DEFAULT
    eps_cap: float = EPS_CAP_DEFAULT
    name: ClassVar[str] = ""

    def __post_init__(self) -> None:
        check_positive("viscosity", self.viscosity)
        if not isinstance(self.geometry, BearingGeometry):
            raise ValueError(f"`geometry` must be a BearingGeometry, got {self.geometry!r}")
        check_open("eps_film", self.eps_film, 0.0, 1.0)
        check_open("eps_cap", self.eps_cap, self.eps_film, 1.0)

    @property
    def width_ratio(self) -> float:
        """``B / D``."""
        return self.geometry.length / (2.0 * self.geometry.journal_radius)

    @abstractmethod
    def components(self, eps: float, eps_dot: float, omega_eff: float) -> tuple[float, float]:
        """Film force on the journal along ``n`` and along ``n`` turned +90 degrees [N].

        Parameters
        ----------
        eps : float
            Eccentricity ratio, ``0 <= eps < 1``.
        eps_dot : float
            Its rate [1/s]; positive when the journal approaches the wall.
        omega_eff : float
            ``omega_J + omega_B - 2 dphi/dt`` [rad/s], eq. (56).
        """

    def load(self, ex: float, ey: float, vx: float, vy: float, omega_journal: float = 0.0,
             omega_bearing: float = 0.0) -> FilmLoad:
        """Film force and viscous torques for the journal at ``e`` moving at ``de/dt``.

        ``ValueError`` for ``eps >= 1`` (the film alone is singular at the wall; the joint
        uses :meth:`blended_load`).
        """
        kin = film_kinematics(ex, ey, vx, vy, omega_journal, omega_bearing, self.geometry.clearance)
        if not kin.eps < 1.0:
            raise ValueError(f"the film needs eccentricity ratio `eps` < 1 (journal off the wall), got {kin.eps}; "
                             "use `blended_load` at and beyond the wall")
        return self._assemble(kin, kin.eps, kin.eps_dot, omega_journal, omega_bearing)

    def blended_load(self, ex: float, ey: float, vx: float, vy: float, omega_journal: float = 0.0,
                     omega_bearing: float = 0.0) -> FilmLoad:
        """The film as the joint applies it: :meth:`load` at the blended eccentricity of
        eq. (70), defined for every ``eps`` (finite at and beyond the wall); the joint adds
        its dry contact law, which acts from ``eps = 1`` on (physics.md section 10.5)."""
        kin = film_kinematics(ex, ey, vx, vy, omega_journal, omega_bearing, self.geometry.clearance)
        eps_b, eps_dot_b = blend_eccentricity(kin.eps, kin.eps_dot, self.eps_film, self.eps_cap)
        return self._assemble(kin, eps_b, eps_dot_b, omega_journal, omega_bearing)

    def _assemble(self, kin: FilmKinematics, eps: float, eps_dot: float, omega_journal: float,
                  omega_bearing: float) -> FilmLoad:
        f_n, f_perp = self.components(eps, eps_dot, kin.omega_eff)
        nx, ny = kin.nx, kin.ny
        fx = f_n * nx - f_perp * ny      # n turned +90 degrees is (-n_y, n_x)
        fy = f_n * ny + f_perp * nx
        # eq. (69): Couette shear over the whole circumference, and the pressure's share
        g = self.geometry
        couette = (2.0 * math.pi * self.viscosity * g.journal_radius ** 3 * g.length * (omega_journal - omega_bearing)
                   / (g.clearance * math.sqrt(1.0 - eps * eps)))
        # (e x F)_z with the true e, so that M_J + M_B + e x F = 0 holds also where the film
        # is evaluated at a blended eccentricity (the film carries no net moment)
        e_cross_f = kin.eps * g.clearance * (nx * fy - ny * fx)
        return FilmLoad(fx, fy, -couette - 0.5 * e_cross_f, couette - 0.5 * e_cross_f, f_n, -f_perp, kin.eps,
                        kin.omega_eff)

    def __call__(self, ex: float, ey: float, vx: float, vy: float, omega_journal: float = 0.0,
                 omega_bearing: float = 0.0) -> FilmLoad:
        return self.load(ex, ey, vx, vy, omega_journal, omega_bearing)


@dataclass(frozen=True)
class ShortBearing(FilmLaw):
    """Ocvirk's short bearing, dynamic form, half-Sommerfeld (Guembel) cavitation.

    Reynolds' equation without the circumferential pressure flow (``B/D -> 0``) gives the
    full-film pressure (physics.md eq. (58); Pinkus and Sternlicht, Theory of Hydrodynamic
    Lubrication, 1961; Flores et al., Mech. Mach. Theory 41 (2006) 247)

        p = 3 eta (B^2/4 - z^2) (eps omega_eff sin(theta) - 2 eps_dot cos(theta)) / (c^2 (1 + eps cos(theta))^3)

    **Cavitation**: the positive part of this pressure (Guembel); its positive region is
    a half circle, starting where the bracket changes sign, so it turns with the squeeze
    (for rotation alone it is ``0 < theta < pi``, the classical pi film).  The forces are
    its integrals, in closed form with Sommerfeld's substitution (eq. (59)); for rotation
    alone they are Ocvirk's:

        F = eta omega R B^3 / (4 c^2) eps sqrt(pi^2 (1 - eps^2) + 16 eps^2) / (1 - eps^2)^2,
        tan(beta) = pi sqrt(1 - eps^2) / (4 eps)
    """

    name: ClassVar[str] = "short"

    def components(self, eps: float, eps_dot: float, omega_eff: float) -> tuple[float, float]:
        g = self.geometry
        s = math.sqrt(1.0 - eps * eps)
        rot = eps * omega_eff * s
        c1, s1, c2, s2, length = self._arc(2.0 * eps_dot * eps, -2.0 * eps_dot, rot)
        # g_n, g_t between the arc's ends, from their cosines and sines
        d_cos, d_sin = c2 - c1, s2 - s1
        d_cos2 = (c2 * c2 - s2 * s2) - (c1 * c1 - s1 * s1)  # cos(2 g2) - cos(2 g1)
        d_sin2 = 2.0 * (s2 * c2 - s1 * c1)                  # sin(2 g2) - sin(2 g1)
        # g_n: antiderivative of (rot sin - 2 eps_dot (cos - eps)) (cos - eps)
        in_n = (rot * (-0.25 * d_cos2 + eps * d_cos)
                - 2.0 * eps_dot * ((0.5 + eps * eps) * length + 0.25 * d_sin2 - 2.0 * eps * d_sin))
        # g_t: antiderivative of (rot sin - 2 eps_dot (cos - eps)) sin
        in_t = rot * (0.5 * length - 0.25 * d_sin2) - 2.0 * eps_dot * (-0.25 * d_cos2 + eps * d_cos)
        scale = self.viscosity * g.length ** 3 * g.journal_radius / (2.0 * g.clearance ** 2)  # eq. (60)
        s2_ = s * s
        return scale * in_n / (s2_ * s2_ * s), scale * in_t / (s2_ * s2_)

    @staticmethod
    def _arc(a0: float, a1: float, b1: float) -> tuple[float, float, float, float, float]:
        """The arc of positive pressure (eq. (59)): ``(cos g1, sin g1, cos g2, sin g2, g2 - g1)``.

        The pressure's sign in ``gamma`` is ``a0 + a1 cos + b1 sin`` (``a0 = 2 eps_dot eps``,
        ``a1 = -2 eps_dot``, ``b1 = eps omega_eff s``), positive on one arc around the phase of
        ``(a1, b1)``, of half-width ``arccos(-a0 / |(a1, b1)|)``; its ends' cosines and sines
        follow without trigonometric calls, only its length needs ``arccos``.
        """
        amplitude = math.sqrt(a1 * a1 + b1 * b1)
        if a0 >= amplitude:  # positive everywhere (the whole circle), or zero everywhere
            return 1.0, 0.0, 1.0, 0.0, (2.0 * math.pi if a0 > 0.0 else 0.0)
        if a0 <= -amplitude:  # negative everywhere
            return 1.0, 0.0, 1.0, 0.0, 0.0
        cp, sp = a1 / amplitude, b1 / amplitude    # the phase
        ch = -a0 / amplitude                       # cos(half)
        sh = math.sqrt(1.0 - ch * ch)              # sin(half) >= 0
        return (cp * ch + sp * sh, sp * ch - cp * sh, cp * ch - sp * sh, sp * ch + cp * sh, 2.0 * math.acos(ch))


#: Halley's iteration for the long bearing's cavitation boundaries (:func:`_root_in_unit_interval`)
#: converges cubically: once a step is below ``_ROOT_RTOL`` of the root, what is left is of the
#: order of its cube, round-off (measured: at most 4e-16 relative).  ``_ROOT_ITERATIONS`` is far
#: more than needed (4 on average); a step that leaves the bracket is replaced by bisection.
_ROOT_RTOL = 1e-6
_ROOT_ITERATIONS = 100


def _root_in_unit_interval(k0: float, k1: float, k2: float, k3: float, k4: float, p_one: float) -> float:
    """The root in ``[0, 1]`` of ``p = k0 + k1 x + k2 x^2 + k3 x^3 + k4 x^4``, given ``p(1) = p_one``
    of the sign opposite to ``k0``'s (or 0) and one root there: Halley's iteration from the
    secant's root, kept inside the bracket by bisection (physics.md eq. (62c))."""
    if p_one == 0.0:
        return 1.0
    lo, hi = 0.0, 1.0
    x = k0 / (k0 - p_one)
    for _ in range(_ROOT_ITERATIONS):
        x2 = x * x  # p, p', p'' in Estrin's order (the compiled kernel's: shorter dependency chains)
        p = (k0 + k1 * x) + (k2 + k3 * x) * x2 + k4 * (x2 * x2)
        dp = (k1 + 2.0 * k2 * x) + (3.0 * k3 + 4.0 * k4 * x) * x2
        ddp = 2.0 * k2 + (6.0 * k3 + 12.0 * k4 * x) * x
        if p == 0.0:
            break
        if (p > 0.0) == (k0 > 0.0):
            lo = x
        else:
            hi = x
        den = dp * dp - 0.5 * p * ddp
        nxt = x - p * dp / den if den != 0.0 else -1.0
        halley = lo <= nxt <= hi
        if not halley:  # the step left the bracket: bisect
            nxt = 0.5 * (lo + hi)
        change = abs(nxt - x)
        x = nxt
        if halley and change <= _ROOT_RTOL * x:
            break
    return x


@dataclass(frozen=True)
class LongBearing(FilmLaw):
    """Sommerfeld's long bearing, half-Sommerfeld (Guembel) cavitation.

    Reynolds' equation without the axial flow (``B/D -> infinity``) gives the full-film
    pressure (physics.md eq. (61); A. Sommerfeld, Z. Math. Phys. 50 (1904) 97 for the
    rotation, the squeeze part integrated the same way)

        p = 6 eta R^2 / c^2 [eps omega_eff sin(theta) (2 + eps cos(theta)) / ((2 + eps^2) (1 + eps cos(theta))^2)
                             + eps_dot (3 eps - 4 cos(theta) - 2 eps cos^2(theta)) / ((2 + 3 eps^2) (1 + eps cos(theta))^2)]

    The rotation part is Sommerfeld's (zero at the largest gap); the squeeze part's level
    makes ``integral of h^3 p dtheta`` vanish, which is the limit of a finite bearing open
    to ambient pressure at its ends (exuclear's choice, eq. (62); it keeps the long model
    the large-``B/D`` limit of the Reynolds reference).  **Cavitation**: the positive part
    of this pressure (Guembel), on the one arc where it is positive, whose ends are the two
    zeros of a trigonometric polynomial (eqs. (62a)-(62c), :meth:`_arc`); forces in closed
    form by parts and Sommerfeld's substitution (eq. (63)).  For rotation alone, ``F_r = 12 eta omega R^3 B eps^2 / (c^2 (2 + eps^2)
    (1 - eps^2))`` and ``F_t = 6 pi eta omega R^3 B eps / (c^2 (2 + eps^2) sqrt(1 - eps^2))``.
    """

    name: ClassVar[str] = "long"

    def components(self, eps: float, eps_dot: float, omega_eff: float) -> tuple[float, float]:
        g = self.geometry
        s = math.sqrt(1.0 - eps * eps)
        rho = eps * omega_eff * s / (2.0 + eps * eps)
        sigma = eps_dot / (2.0 + 3.0 * eps * eps)
        c1, s1, c2, s2, length = self._arc(eps, rho, sigma)
        # g_n, g_t between the arc's ends, from their cosines and sines
        d_cos, d_sin = c2 - c1, s2 - s1
        d_cos2 = (c2 * c2 - s2 * s2) - (c1 * c1 - s1 * s1)  # cos(2 g2) - cos(2 g1)
        d_sin2 = 2.0 * (s2 * c2 - s1 * c1)                  # sin(2 g2) - sin(2 g1)
        two_eps_dot = 2.0 * eps_dot
        # g_n: antiderivative of rho (2 cos + eps) sin + 2 eps_dot sin^2
        in_n = rho * (-0.5 * d_cos2 - eps * d_cos) + two_eps_dot * (0.5 * length - 0.25 * d_sin2)
        # g_t: antiderivative of (cos - eps) (rho (2 cos + eps) + 2 eps_dot sin)
        in_t = (rho * (s * s * length + 0.5 * d_sin2 - eps * d_sin)
                + two_eps_dot * (-0.25 * d_cos2 + eps * d_cos))
        scale = 6.0 * self.viscosity * g.journal_radius ** 3 * g.length / g.clearance ** 2  # eq. (63)
        s2_ = s * s
        return -scale * in_n / (s2_ * s), scale * in_t / (s2_ * s2_)

    @staticmethod
    def _arc(eps: float, rho: float, sigma: float) -> tuple[float, float, float, float, float]:
        """The arc of positive pressure, physics.md eqs. (62a)-(62c): ``(cos g1, sin g1, cos g2,
        sin g2, g2 - g1)`` of its ends ``g1 < g2`` in Sommerfeld's variable, for
        ``rho = eps omega_eff s / (2 + eps^2)`` and ``sigma = eps_dot / (2 + 3 eps^2)``.

        The pressure's sign ``g = a0 + a1 cos + b1 sin + a2 cos 2gamma + b2 sin 2gamma`` has,
        unless the squeeze ``sigma`` is 0, exactly two zeros, both simple, one in ``(0, pi)`` and
        one in ``(pi, 2 pi)``: ``g(0) = -sigma (1 - eps)^2 (4 - eps)`` and ``g(pi) = sigma
        (1 + eps)^2 (4 + eps)`` (eq. (62a)).  The positive part is one arc, from the first zero to the second
        for ``sigma > 0`` (around the smallest gap), from the second to the first (plus 2 pi) for
        ``sigma < 0``.  With ``tau = tan(gamma / 2)``, ``(1 + tau^2)^2 g`` is the quartic
        ``k0 + k1 tau + ... + k4 tau^4`` (eq. (62b)); the sign of ``g`` at ``pi/2`` (``3 pi/2``)
        tells which quarter circle holds each zero, and there it is the only root in ``[0, 1]`` of
        the quartic in ``t = |tau|`` or ``u = 1 / |tau|`` (eq. (62c)).  The compiled kernel
        iterates the two roots side by side; each takes the same steps as here.
        """
        if sigma == 0.0:  # rotation alone: g = rho sin (2 - eps^2 - eps cos), zero at 0 and pi
            if rho > 0.0:
                return 1.0, 0.0, -1.0, 0.0, math.pi
            if rho < 0.0:
                return -1.0, 0.0, 1.0, 0.0, math.pi
            return 1.0, 0.0, 1.0, 0.0, 0.0  # no film pressure at all
        # sign of p in gamma (eq. (62a)): rho sin (2 - eps^2 - eps cos) + sigma (q0 + q1 cos + q2 cos^2)
        eps3 = eps * eps * eps
        q0, q2 = 7.0 * eps - 2.0 * eps3, 2.0 * eps + 3.0 * eps3
        a0, b1, a2, b2 = sigma * (q0 + 0.5 * q2), rho * (2.0 - eps * eps), 0.5 * sigma * q2, -0.5 * rho * eps
        # eq. (62b); k0 = g(0) and k4 = g(pi) in their factored forms, whose signs are exact
        k0 = -sigma * (1.0 - eps) * (1.0 - eps) * (4.0 - eps)
        k1, k2, k3 = 2.0 * b1 + 4.0 * b2, 2.0 * a0 - 6.0 * a2, 2.0 * b1 - 4.0 * b2
        k4 = sigma * (1.0 + eps) * (1.0 + eps) * (4.0 + eps)
        # the zero in (0, pi): in (0, pi/2) (tau = t) where g(pi/2) has the sign of g(pi), else in
        # [pi/2, pi) (tau = 1 / u)
        q_plus = k0 + k1 + k2 + k3 + k4  # 4 g(pi/2)
        first_t = (q_plus > 0.0) != (k0 > 0.0) and q_plus != 0.0
        x = (_root_in_unit_interval(k0, k1, k2, k3, k4, q_plus) if first_t
             else _root_in_unit_interval(k4, k3, k2, k1, k0, q_plus))
        # the ends from tau: cos = (1 - tau^2) / (1 + tau^2), sin = 2 tau / (1 + tau^2), gamma = 2 arctan(tau)
        d = 1.0 + x * x
        c1, s1 = ((1.0 - x * x) / d if first_t else (x * x - 1.0) / d), 2.0 * x / d
        g1 = 2.0 * math.atan(x) if first_t else math.pi - 2.0 * math.atan(x)
        # the zero in (pi, 2 pi): in (3 pi/2, 2 pi) (tau = -t) where g(3 pi/2) has the sign of g(pi),
        # else in (pi, 3 pi/2] (tau = -1 / u)
        q_minus = k0 - k1 + k2 - k3 + k4  # 4 g(3 pi/2)
        second_t = (q_minus > 0.0) != (k0 > 0.0) and q_minus != 0.0
        x = (_root_in_unit_interval(k0, -k1, k2, -k3, k4, q_minus) if second_t
             else _root_in_unit_interval(k4, -k3, k2, -k1, k0, q_minus))
        d = 1.0 + x * x
        c2, s2 = ((1.0 - x * x) / d if second_t else (x * x - 1.0) / d), -2.0 * x / d
        g2 = 2.0 * math.pi - 2.0 * math.atan(x) if second_t else math.pi + 2.0 * math.atan(x)
        if sigma > 0.0:  # around pi: from the first zero to the second
            return c1, s1, c2, s2, g2 - g1
        return c2, s2, c1, s1, 2.0 * math.pi - (g2 - g1)  # around 0: from the second to the first, + 2 pi


def _polynomial(coefficients: tuple[float, ...], x: float) -> float:
    return sum(a * x ** k for k, a in enumerate(coefficients))


#: Butenschoen's fits (1976), polynomials in B/D, lowest power first (physics.md eqs. (64)-(66)).
#: a1, a2 as DIN 31652-2 gives them; a3-a9 transcribed from the coefficient list of MBDyn's
#: hydrodynamic plain bearing (Butenschoen's model), values only; tests/test_film.py checks the
#: fits against Butenschoen's published table (So within 5 %, attitude within 1.6 deg).
_A1 = (1.1642, -1.9456, 7.1161, -10.1073, 5.0141)
_A2 = (-1.000026, -0.023634, -0.4215, -0.038817, -0.090551)
_A3 = (1.152624, -0.104565)
_A4 = (-2.5905, 0.798745)
_A5 = (8.73393, -2.3291)
_A6 = (-13.3414, 3.424337)
_A7 = (6.6294, -1.591732)
_A8 = (0.70038, 3.2415, -12.2486, 18.895, -9.3561)
_A9 = (-0.999935, 0.0157434, -0.74224, 0.42278, -0.368928)
#: The range of B/D the fits were made for (Butenschoen 1976; DIN 31652-2).
FINITE_WIDTH_RANGE = (1.0 / 8.0, 1.0)
#: How fast a rotating film turns with the squeeze (eq. (66a)): the share of the approaching
#: squeeze number is ``1/2 + arctan(SQUEEZE_TURN r) / pi`` with ``r`` the squeeze over the wedge.
#: Fitted to the Reynolds reference under Butenschoen's conditions (Reynolds' condition, supply
#: groove at the largest gap; B/D = 1/8 and 1, eps = 0.5 and 0.9, r = 0.01 to 10), which it meets
#: within 0.016 of that share (tests/test_reynolds.py); the short model's own arc turns alike.
SQUEEZE_TURN = 1.3


@dataclass(frozen=True)
class FiniteBearing(FilmLaw):
    """Butenschoen's finite-width bearing, ``1/8 <= B/D <= 1`` (physics.md eqs. (64)-(67)), with ``D``
    the journal's or the bearing's diameter (``B/D`` below is the journal's).

    Rotation (Butenschoen 1976, as DIN 31652-2 gives it): Ocvirk's Sommerfeld number times a
    fitted correction, and a fitted attitude angle,

        So_D = (B/D)^2 eps sqrt(pi^2 (1 - eps^2) + 16 eps^2) / (2 (1 - eps^2)^2) * a1 (eps - 1) / (a2 + eps)
        beta = arctan(pi sqrt(1 - eps^2) / (2 eps)) (a3 + a4 eps + a5 eps^2 + a6 eps^3 + a7 eps^4)

    Squeeze (Butenschoen 1976): the short bearing's half-film squeeze number times a fit,

        So_V = 4 (B/D)^2 / (1 - eps^2)^(5/2) [(pi/2 - arccos(eps)/2) (1 + 2 eps^2) + 3/2 eps sqrt(1 - eps^2)]
               * a8 (1 - eps) / (-a9 - eps)

    with ``eps`` replaced by ``-eps`` when the journal moves away from the wall (the film
    then forms on the wide side).  ``a1 ... a9`` are polynomials in ``B/D`` (module
    constants ``_A1`` ... ``_A9``).  The force is the sum ``|F_D| = So_D B D eta |omega_eff| /
    psi^2`` at ``beta`` from the line of centres, behind it in the sense of ``omega_eff``,
    plus ``|F_V| = So_V B D eta |eps_dot| / psi^2`` against the squeeze.  **Cavitation**:
    that of Butenschoen's Reynolds solutions, which the fits reproduce (a film from the
    largest gap that ends with zero pressure and pressure gradient: Reynolds' condition;
    physics.md section 10.3).  Superposing rotation and squeeze is Butenschoen's
    approximation.
    """

    name: ClassVar[str] = "finite"
    _coefficients: tuple[float, ...] = field(init=False, repr=False, compare=False)

    def __post_init__(self) -> None:
        super().__post_init__()
        bd = self.width_ratio
        # D is the journal's diameter here and the bearing's in DIN 31652; they differ by the
        # clearance ratio c / R, a width within the fits' range by either is accepted (the fits
        # evaluated at the journal's B/D, at most c / R beyond their range, nothing clamped)
        g = self.geometry
        bd_bearing = g.length / (2.0 * g.bearing_radius)
        low, high = FINITE_WIDTH_RANGE
        if bd_bearing > high:
            raise ValueError(f"the `finite` film model (Butenschoen's fits) needs B/D <= 1 (D the bearing's "
                             f"diameter 2 `bearing_radius`, which is c/R = {relative_clearance(g):.3g} larger than the "
                             f"journal's), got B/D = {bd_bearing:.12g} (`length` {g.length:.6g} m); use model='long' "
                             "for wider bearings")
        if bd < low:
            raise ValueError(f"the `finite` film model (Butenschoen's fits) needs B/D >= 1/8 (D the journal's "
                             f"diameter 2 `journal_radius`, which is c/R = {relative_clearance(g):.3g} smaller than the "
                             f"bearing's), got B/D = {bd:.12g} (`length` {g.length:.6g} m); use model='short' "
                             "for narrower bearings")
        object.__setattr__(self, "_coefficients", tuple(_polynomial(a, bd) for a in
                                                        (_A1, _A2, _A3, _A4, _A5, _A6, _A7, _A8, _A9)))

    def rotation(self, eps: float) -> tuple[float, float]:
        """``(So_D, beta)`` for rotation alone, eqs. (64)-(65); ``beta`` in rad."""
        a1, a2, a3, a4, a5, a6, a7 = self._coefficients[:7]
        bd = self.width_ratio
        one_m = 1.0 - eps * eps
        so = (bd * bd * eps / (2.0 * one_m * one_m) * math.sqrt(math.pi ** 2 * one_m + 16.0 * eps * eps)
              * a1 * (eps - 1.0) / (a2 + eps))
        base = math.atan2(math.pi * math.sqrt(one_m), 2.0 * eps)  # pi/2 at eps = 0
        beta = base * (a3 + a4 * eps + a5 * eps ** 2 + a6 * eps ** 3 + a7 * eps ** 4)
        return so, beta

    def squeeze(self, eps_signed: float) -> float:
        """``So_V``, eq. (66); ``eps_signed = eps`` approaching the wall, ``-eps`` leaving it."""
        a8, a9 = self._coefficients[7:]
        bd = self.width_ratio
        x = eps_signed
        one_m = 1.0 - x * x
        return (4.0 * bd * bd * one_m ** -2.5
                * ((0.5 * math.pi - 0.5 * math.acos(x)) * (1.0 + 2.0 * x * x) + 1.5 * x * math.sqrt(one_m))
                * a8 * (1.0 - x) / (-a9 - x))

    def components(self, eps: float, eps_dot: float, omega_eff: float) -> tuple[float, float]:
        g = self.geometry
        psi = relative_clearance(g)
        unit = g.length * 2.0 * g.journal_radius * self.viscosity / (psi * psi)  # B D eta / psi^2, eq. (67)
        so_d, beta = self.rotation(eps)
        f_d = so_d * unit * abs(omega_eff)
        # the load -F_D lies beta from n, behind it in the sense of omega_eff: F_D on the journal
        # has components (-cos(beta), sin(beta) sign(omega_eff)) along (n, n turned +90 degrees)
        sign = 1.0 if omega_eff >= 0.0 else -1.0
        f_v = self.turning_squeeze(eps, eps_dot, omega_eff) * unit * eps_dot  # signed: against the squeeze
        return -f_d * math.cos(beta) - f_v, sign * f_d * math.sin(beta)

    def turning_squeeze(self, eps: float, eps_dot: float, omega_eff: float) -> float:
        """``So_V`` of a rotating film, eq. (66a): the approaching and the leaving number of
        eq. (66) weighted by how far the squeeze has turned the film::

            w = 1/2 + arctan(SQUEEZE_TURN r) / pi,    r = 2 eps_dot / (eps |omega_eff| sqrt(1 - eps^2)),
            So_V = w So_V(eps) + (1 - w) So_V(-eps)

        Without rotation ``w`` is 1 approaching and 0 leaving (Butenschoen's switch, exactly);
        with rotation it passes 1/2 at ``eps_dot = 0`` and turns over a squeeze of the
        wedge's order, as the cavitated film does (physics.md section 10.3), so that the
        force is smooth in ``eps_dot`` wherever the film rotates.
        """
        wedge = eps * abs(omega_eff) * math.sqrt(1.0 - eps * eps)
        w = 0.5 + math.atan2(2.0 * SQUEEZE_TURN * eps_dot, wedge) / math.pi  # atan2(0, 0) = 0: no force anyway
        if w == 1.0:  # approaching without rotation, or a squeeze far beyond the wedge
            return self.squeeze(eps)
        if w == 0.0:
            return self.squeeze(-eps)
        return w * self.squeeze(eps) + (1.0 - w) * self.squeeze(-eps)


#: Model name -> film law class.
FILM_MODELS: dict[str, type[FilmLaw]] = {cls.name: cls for cls in (ShortBearing, LongBearing, FiniteBearing)}


@dataclass(frozen=True)
class Lubrication:
    """The lubricant of a joint: what a user gives, before the joint's geometry is known.

    Parameters
    ----------
    viscosity : float
        Dynamic viscosity ``eta`` [Pa s], > 0 (an SAE 30 oil near 40 degC: ~0.1 Pa s).
    model : str
        ``"short"``, ``"long"`` or ``"finite"`` (:data:`FILM_MODELS`).
    eps_film : float
        Below this eccentricity ratio the film acts alone (eq. (70)), default 0.9.
    eps_cap : float
        The film's eccentricity ratio tends to this at and beyond the wall (eq. (70)),
        ``eps_film < eps_cap < 1``, default 0.97.
    """

    viscosity: float
    model: str = "short"
    eps_film: float = EPS_FILM_DEFAULT
    eps_cap: float = EPS_CAP_DEFAULT

    def __post_init__(self) -> None:
        if check_positive("viscosity", self.viscosity) > VISCOSITY_WARN_ABOVE:
            warn_unit(f"the viscosity {self.viscosity:.3g} Pa s is above {VISCOSITY_WARN_ABOVE:g} Pa s; it is in Pa s: "
                      "was it given in mPa s (cP)?")
        check_choice("model", self.model, FILM_MODELS)
        check_open("eps_film", self.eps_film, 0.0, 1.0)
        check_open("eps_cap", self.eps_cap, self.eps_film, 1.0)

    def law(self, geometry: BearingGeometry) -> FilmLaw:
        """The film law of this lubricant in a bearing of ``geometry``."""
        return FILM_MODELS[self.model](self.viscosity, geometry, self.eps_film, self.eps_cap)

