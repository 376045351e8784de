"""The clearance joint as physics: geometry, contact law, friction law, contact history.

Pure Python; the Exudyn glue in :mod:`exuclear.exudyn_element` reads the body states,
calls :meth:`ClearanceJoint.loads` and maps the result onto generalized forces.
"""
from __future__ import annotations

from dataclasses import dataclass, field
from typing import NamedTuple

from .contact import DEFAULT_LAW, V_MIN_DEFAULT, ContactLaw, contact_law, is_elastic, pair_name, split_law_name
from .friction import NO_FRICTION, FrictionLaw, friction_law
from .geometry import BearingGeometry, ContactKinematics, JointLoads, joint_loads
from .materials import Material, composite_modulus


@dataclass
class ContactHistory:
    """Per-joint history: whether the last accepted state was in contact, and ``v0``.

    ``v0`` (docs/physics.md section 2.3) is the penetration rate at the instant ``delta``
    crossed zero.  It is updated only by :meth:`accept`, once per accepted time step;
    force evaluations (Newton iterations, Jacobian perturbations, Runge-Kutta stages)
    call the side-effect-free :meth:`onset_velocity`.

    Onset interpolation: in the step where contact begins, ``delta`` goes from
    ``d0 <= 0`` (last accepted state) to ``d1 > 0`` (trial state).  ``delta_dot`` is
    interpolated linearly in ``delta`` to ``delta = 0``:
    ``v0 = dd0 + (dd1 - dd0) * d0 / (d0 - d1)`` (docs/physics.md eqs. (18)-(19)).  This is exact when the contact
    starts at an accepted state (``d0 = 0``, the journal-bearing scene) and has an
    error of order (step)^2 * acceleration otherwise, instead of order
    step * acceleration for taking ``dd1`` of the first penetrated state.
    """

    in_contact: bool = False
    v0: float = 0.0
    delta: float = float("-inf")
    delta_dot: float = 0.0
    time: float = 0.0
    #: Contact onset instants since the last reset [s], interpolated like ``v0``.
    onset_times: list[float] = field(default_factory=list)

    @property
    def onsets(self) -> int:
        """Contacts begun since the last reset (impacts)."""
        return len(self.onset_times)

    def onset_velocity(self, delta: float, delta_dot: float) -> float:
        """``v0`` for a trial state (``delta > 0``) of the coming step; no side effects."""
        if self.in_contact:
            return self.v0
        d0 = self.delta
        if d0 == float("-inf"):  # no accepted state yet: the joint starts in contact
            return delta_dot
        return self.delta_dot + (delta_dot - self.delta_dot) * d0 / (d0 - delta)

    def accept(self, delta: float, delta_dot: float, time: float = 0.0) -> None:
        """Record an accepted state at ``time`` [s]; idempotent when repeated with the same state."""
        if delta > 0.0:
            if not self.in_contact:
                self.v0 = self.onset_velocity(delta, delta_dot)
                self.in_contact = True
                d0 = self.delta
                share = d0 / (d0 - delta) if d0 != float("-inf") else 0.0
                self.onset_times.append(self.time + share * (time - self.time))
        else:
            self.in_contact = False
        self.delta, self.delta_dot, self.time = delta, delta_dot, time

    def reset(self) -> None:
        self.in_contact, self.v0, self.delta, self.delta_dot, self.time = False, 0.0, float("-inf"), 0.0, 0.0
        self.onset_times = []


class JointResponse(NamedTuple):
    """Contact force magnitudes and the loads on both bodies at one instant."""

    f_n: float
    f_t: float
    v0: float
    loads: JointLoads


_NO_LOADS = JointLoads(0.0, 0.0, 0.0, 0.0)


@dataclass(frozen=True)
class ClearanceJoint:
    """A revolute clearance joint: geometry, normal contact law and friction law.

    Parameters
    ----------
    law : ContactLaw
        Normal contact law; it carries the :class:`BearingGeometry`.
    friction : FrictionLaw
        Friction law; default frictionless.
    """

    law: ContactLaw
    friction: FrictionLaw = NO_FRICTION

    def __post_init__(self) -> None:
        if not isinstance(self.law, ContactLaw):
            raise ValueError(f"`law` must be a ContactLaw, got {type(self.law).__name__}")
        if not isinstance(self.friction, FrictionLaw):
            raise ValueError(f"`friction` must be a FrictionLaw, got {type(self.friction).__name__}")

    @property
    def geometry(self) -> BearingGeometry:
        return self.law.geometry

    def response(self, kin: ContactKinematics, history: ContactHistory) -> JointResponse:
        """Forces for the contact state ``kin`` given the last accepted ``history``."""
        if kin.delta <= 0.0:
            return JointResponse(0.0, 0.0, history.v0 if history.in_contact else 0.0, _NO_LOADS)
        v0 = history.onset_velocity(kin.delta, kin.delta_dot)
        f_n = self.law.normal_force(kin.delta, kin.delta_dot, v0)
        f_t = self.friction.coefficient(kin.v_t) * f_n if self.friction.active else 0.0
        return JointResponse(f_n, f_t, v0, joint_loads(self.law.geometry, kin, f_n, f_t))


def make_joint(
    *,
    journal_radius: float,
    bearing_radius: float,
    length: float,
    law: str | ContactLaw | None = None,
    cr: float | None = None,
    journal_material: str | Material = "steel",
    bearing_material: str | Material = "steel",
    E_star: float | None = None,
    friction: str | FrictionLaw = "none",
    v_min: float = V_MIN_DEFAULT,
    stiffness: str | None = None,
    damping: str | None = None,
) -> ClearanceJoint:
    """Build a :class:`ClearanceJoint` from dimensions, materials and law names.

    Parameters
    ----------
    journal_radius, bearing_radius, length : float
        ``R_J < R_B`` and the bearing length ``L`` [m].
    law : str or ContactLaw, optional
        A name of :data:`exuclear.CONTACT_LAWS` (default ``"wang-liu"``), a pair
        ``"STIFFNESS+DAMPING"`` (:mod:`exuclear.contact`), or a ready law (then ``cr``,
        materials, ``E_star`` and ``v_min`` must not be given and the law's own geometry
        must match the radii and length).
    cr : float
        Coefficient of restitution in (0, 1]; required for every law with damping, 1 (the
        default there) for the elastic ones (``"hertz"``, damping ``"none"``).
    journal_material, bearing_material : str or Material
        Names of :data:`exuclear.MATERIALS` or :class:`Material` objects.
    E_star : float, optional
        Composite modulus [Pa]; overrides the materials when given.
    friction : str or FrictionLaw
        ``"none"``, ``"coulomb:MU"``, ``"paper"`` or a :class:`FrictionLaw`.
    v_min : float
        Floor of the onset velocity in the damping term [m/s].
    stiffness, damping : str, optional
        The law as a pair instead of ``law``: a name of
        :data:`exuclear.contact.STIFFNESS_MODELS` and one of
        :data:`exuclear.contact.DAMPING_MODELS`; a missing one is that of the default
        law (``liu``, ``zhiying-qishao``).
    """
    geometry = BearingGeometry(journal_radius, bearing_radius, length)
    if isinstance(law, ContactLaw):
        if stiffness is not None or damping is not None:
            raise ValueError("give either `law` or `stiffness`/`damping`, not both")
        if law.geometry != geometry:
            raise ValueError(f"`law` was built for {law.geometry}, which differs from {geometry}")
        return ClearanceJoint(law, friction_law(friction))
    if stiffness is not None or damping is not None:
        if law is not None:
            raise ValueError("give either `law` or `stiffness`/`damping`, not both")
        law = pair_name(stiffness, damping)
    elif law is None:
        law = DEFAULT_LAW
    split_law_name(law)  # unknown names fail here, listing the known ones
    if cr is None:
        if not is_elastic(law):
            raise ValueError(f"`cr` (coefficient of restitution in (0, 1]) is required for the {law!r} law")
        cr = 1.0
    if E_star is None:
        E_star = composite_modulus(journal_material, bearing_material)
    return ClearanceJoint(contact_law(law, geometry, E_star, cr, v_min), friction_law(friction))
