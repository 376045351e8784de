"""A worn joint's profiles over a run (:class:`WearState`): which profiles an evaluation uses,
the worn contact's kinematics, and the wear of each accepted step.  The compiled kernel's
``wear.hpp``.

The planar joint has one :class:`WearState`; the spatial joint one per slice (docs/physics.md
section 11.7), each on the slice's length ``L / N`` with its share of the law's force, in the
slice's plane.

As the contact history (package docstring), the profiles are kept at the start
(``previous``) and at the end (``current``) of the last accepted step: an evaluation of a
new step uses ``current``, one of a step computed again ``previous``, and a run's first
evaluation the initial profiles (:class:`exuclear.Wear`'s ``bearing`` and ``journal``).
"""
from __future__ import annotations

import math

import numpy as np

from ...geometry import BearingGeometry, ContactKinematics, kinematics_along
from ...spatial import SliceKinematics, slice_kinematics_along
from ...vectors import V3
from ...wear.law import Wear
from ...wear.surface import (
    SurfaceField,
    grid,
    hertz_half_width,
    pressure_shape,
    surface_field,
    wear_step,
    worn_contact,
)

#: An accepted step's stability number ``k_D K ds`` (docs/physics.md eq. (81)) above which
#: the profile's update overshoots (its error changes sign each step; above 2 it grows).
STABILITY_LIMIT = 1.0
#: A worn contact is conformal (its normal turns fast as the journal moves sideways, so the
#: joint asks for a Jacobian per step, docs/physics.md section 11.1) where the profiles are
#: deeper than this share of the contact's penetration.  Shallower, the overlap is the
#: unworn contact's narrow arc and an older Jacobian holds (docs/validation/wear.md has the
#: steps it saves on the worn-in journal).
CONFORMAL_DEPTH = 0.1
#: The relative change of the penetration for the law's exponent ``d ln F / d ln delta``.
EXPONENT_STEP = 1e-3


class Profiles:
    """The two depth profiles [m], the slip each bearing node has seen in contact [m] and
    its sum of stability numbers (for :func:`exuclear.predict_wear`'s bound)."""

    def __init__(self, bearing: np.ndarray, journal: np.ndarray, slip: np.ndarray, stability: np.ndarray) -> None:
        self.bearing, self.journal, self.slip, self.stability = bearing, journal, slip, stability
        self.deepest = max(float(np.max(bearing, initial=0.0)), float(np.max(journal, initial=0.0)))
        self.worn = self.deepest > 0.0

    def plus(self, bearing: np.ndarray, journal: np.ndarray, slip: np.ndarray, stability: np.ndarray) -> Profiles:
        return Profiles(self.bearing + bearing, self.journal + journal, self.slip + slip, self.stability + stability)


class WearState:
    """The wear of a planar joint, or of one slice of a spatial joint (module docstring).

    ``geometry``: the joint's, with the slice's length ``L / N`` for a slice; ``row``: the
    slice's index, which row of a slices x nodes starting profile (:class:`exuclear.Wear`'s
    ``bearing``, ``journal``) it starts from (a one-row profile: every slice's).
    """

    def __init__(self, wear: Wear, geometry: BearingGeometry, law: object, row: int = 0) -> None:
        self.wear, self.geometry, self.law = wear, geometry, law
        self.grid = grid(wear.nodes)
        n = wear.nodes
        zero = np.zeros(n)
        self.initial = Profiles(np.array(wear.profile_row("bearing", row) if wear.bearing is not None else zero),
                                np.array(wear.profile_row("journal", row) if wear.journal is not None else zero),
                                zero, zero)
        self.reset()

    def reset(self) -> None:
        self.previous = self.current = self.initial
        self.last_stability = 0.0  # the last accepted step's k_D K ds

    def field(self, profiles: Profiles, ex: float, ey: float, psi: float) -> SurfaceField:
        g = self.geometry
        journal = profiles.journal if self.wear.wears_journal else None
        return surface_field(self.grid, g.journal_radius, g.bearing_radius, g.length, ex, ey, psi, profiles.bearing,
                             journal)

    def kinematics(self, profiles: Profiles, kin: ContactKinematics, psi: float, dvx: float, dvy: float,
                   omega_i: float, omega_j: float) -> ContactKinematics:
        """The contact of the worn surfaces (eqs. (75), (76)) in place of the circles' ``kin``;
        the circles' own where nothing has worn yet (bit for bit the unworn joint)."""
        if not profiles.worn:
            return kin
        g, journal = self.geometry, profiles.journal if self.wear.wears_journal else None
        c = worn_contact(self.field(profiles, kin.ex, kin.ey, psi), self.grid, g.journal_radius, g.bearing_radius,
                         kin.ex, kin.ey, psi, profiles.bearing, journal)
        return kinematics_along(self.geometry, kin.ex, kin.ey, c.delta + self.geometry.clearance, c.nx, c.ny, dvx, dvy,
                                omega_i, omega_j)

    def slice_kinematics(self, profiles: Profiles, kin: SliceKinematics, psi: float, p: V3, u: V3, dv: V3, dw: V3,
                         w_j: V3) -> SliceKinematics:
        """A spatial slice's contact of the worn surfaces in its plane (eqs. (75), (76) at its
        eccentricity, eq. (35)), the rest of its kinematics along that normal (eqs.
        (36)-(40)); the unworn slice's own ``kin`` where nothing has worn yet."""
        if not profiles.worn:
            return kin
        g, journal = self.geometry, profiles.journal if self.wear.wears_journal else None
        c = worn_contact(self.field(profiles, kin.ex, kin.ey, psi), self.grid, g.journal_radius, g.bearing_radius,
                         kin.ex, kin.ey, psi, profiles.bearing, journal)
        return slice_kinematics_along(g.journal_radius, g.bearing_radius, kin.s, kin.ex, kin.ey,
                                      c.delta + g.clearance, c.nx, c.ny, p, u, dv, dw, w_j)

    def exponent(self, delta: float) -> float:
        """The law's ``d ln F / d ln delta`` at ``delta`` (no rate), for the Winkler modulus."""
        hi = self.law.normal_force(delta * (1.0 + EXPONENT_STEP), 0.0, 1.0)
        lo = self.law.normal_force(delta * (1.0 - EXPONENT_STEP), 0.0, 1.0)
        return math.log(hi / lo) / math.log((1.0 + EXPONENT_STEP) / (1.0 - EXPONENT_STEP))

    def accept(self, base: Profiles, kin: ContactKinematics | SliceKinematics, psi: float, f_n: float,
               slip: float) -> Profiles:
        """The profiles after an accepted step that ends in the state ``kin`` with the normal
        force ``f_n`` (a slice's: its share), from the profiles ``base`` at its start; ``slip``
        [m] the step's slip at the contact (``|v_t| h``; a slice's ``|v_s| h``, eq. (42))."""
        self.last_stability = 0.0
        if f_n <= 0.0 or slip <= 0.0:
            return base
        g, w = self.geometry, self.wear
        f = self.field(base, kin.ex, kin.ey, psi)
        winkler = w.pressure == "winkler"
        half_width = 0.0 if winkler else hertz_half_width(f_n, g.journal_radius, g.bearing_radius, g.length,
                                                          self.law.E_star)
        q = pressure_shape(f, self.grid, w.pressure, (kin.nx, kin.ny), half_width, g.bearing_radius)
        factor = self.exponent(kin.delta) if winkler and kin.delta > 0.0 else 0.0
        step = wear_step(f, self.grid, q, f_n, slip, w.coefficient, w.wears_bearing, w.wears_journal, psi, kin.ex,
                         kin.ey, g.journal_radius, factor)
        self.last_stability = step.stability
        loaded = step.loaded.astype(float)
        return base.plus(step.bearing, step.journal, slip * loaded, step.stability * loaded)

    def unstable(self, slip: float, h: float, where: str = "") -> str:
        """Why the last accepted step (``slip`` [m] in ``h`` [s]) was too long for the profile's
        update, or ``""``; ``where`` names the slice (``" of slice k"``; the planar joint: ``""``)."""
        stability = self.last_stability
        if stability <= STABILITY_LIMIT:
            return ""
        longest = h * STABILITY_LIMIT / stability
        return (f"the wear update is unstable: k_D K ds = {stability:.3g} > {STABILITY_LIMIT:g} in one step{where} (slip "
                f"{slip:.3g} m in {h:.3g} s; docs/physics.md eq. (81)); give a step of at most {longest:.3g} s "
                "(simulationSettings.timeIntegration.maxStepSize) or a smaller wear coefficient")
