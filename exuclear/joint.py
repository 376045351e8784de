"""The clearance joint as physics: geometry, contact law and friction law.

Pure Python; the kernels of :mod:`exuclear.engine` evaluate :meth:`ClearanceJoint.response`
on the contact kinematics Exudyn's connector provides, with the contact history of
:mod:`exuclear.history`.
"""
from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass
from typing import Any, NamedTuple

from .contact import DEFAULT_LAW, V_MIN_DEFAULT, ContactLaw, contact_law, damping_model, law_and_restitution
from .checks import check_positive
from .contact.pair import ContactGeometry
from .contact.stiffness import EXPONENT_METAL, STIFFNESS_MODELS, GivenStiffness, StiffnessModel, stiffness_model
from .film import FilmLaw, Lubrication
from .friction import NO_FRICTION, FrictionLaw, friction_law
from .geometry import BearingGeometry, ContactKinematics, JointLoads, joint_loads
from .history import ContactState
from .materials import Material, composite_modulus
from .prismatic import GuideGeometry
from .slot import SlotGeometry
from .spherical import SphereGeometry
from .wear.law import Wear


class ContactResponse(NamedTuple):
    """One contact's force magnitudes at one instant: ``f_n`` the normal force [N], ``f_t``
    the friction force ``mu(slip) f_n`` [N], ``v0`` the onset velocity [m/s] it used."""

    f_n: float
    f_t: float
    v0: float


def contact_response(normal_force: Callable[[float, float, float], float], friction: FrictionLaw, delta: float,
                     delta_dot: float, slip: float, history: ContactState, share: float = 1.0) -> ContactResponse:
    """Onset velocity, normal force and friction of one contact (docs/physics.md eqs. (9),
    (17)-(20)), for the planar joint, a slice of the spatial joint (``share`` = its part
    ``w / L`` of the law, eq. (41)) and an end face (``normal_force`` of eq. (53)) alike.

    ``normal_force(delta, delta_dot, v0)`` is the contact's law, ``friction`` its friction
    law evaluated at ``slip`` [m/s]; ``history`` the last accepted state of this contact.
    No force without penetration.  The compiled kernel's ``response``.
    """
    if delta <= 0.0:
        return ContactResponse(0.0, 0.0, history.v0 if history.in_contact else 0.0)
    v0 = history.onset_velocity(delta, delta_dot)
    f_n = share * normal_force(delta, delta_dot, v0)
    f_t = friction.coefficient(slip) * f_n if friction.active else 0.0
    return ContactResponse(f_n, f_t, v0)


class JointResponse(NamedTuple):
    """Contact force magnitudes and the loads on both bodies at one instant."""

    f_n: float
    f_t: float
    v0: float
    loads: JointLoads


_NO_LOADS = JointLoads(0.0, 0.0, 0.0, 0.0)

#: Journal and bearing material where none is given (the paper's).
DEFAULT_MATERIAL = "steel"
#: The spherical joint's law where none is given: Hertz's ball in a socket with Lankarani and
#: Nikravesh's damping, the pair of the ball-joint literature (Flores et al. 2006).
DEFAULT_SPHERICAL_LAW = "hertz+lankarani-nikravesh"


@dataclass(frozen=True)
class ClearanceJoint:
    """A clearance joint: geometry, normal contact law and friction law.

    The law's geometry is the joint's type: a :class:`BearingGeometry` for the revolute joint
    (:func:`make_joint`), a :class:`~exuclear.spherical.SphereGeometry` for the spherical one
    (:func:`make_spherical_joint`, which takes no film and no wear).

    Parameters
    ----------
    law : ContactLaw
        Normal contact law; it carries the joint's geometry.
    friction : FrictionLaw
        Friction law; default frictionless.
    film : FilmLaw, optional
        The oil film of a lubricated joint (:mod:`exuclear.film`), bound to the same
        geometry; None (the default) for the dry joint.  The film acts at every
        eccentricity, the contact law where the journal penetrates the wall, the two
        added (docs/physics.md section 10.5).
    wear : Wear, optional
        The wear of the joint's surfaces (:class:`exuclear.Wear`, docs/physics.md section
        11); None (the default): the surfaces keep their shape.  A lubricated joint wears
        where metal touches.
    """

    law: ContactLaw
    friction: FrictionLaw = NO_FRICTION
    film: FilmLaw | None = None
    wear: Wear | None = None

    def __post_init__(self) -> None:
        if not isinstance(self.law, ContactLaw):
            raise ValueError(f"`law` must be a ContactLaw, got {type(self.law).__name__}")
        if not isinstance(self.friction, FrictionLaw):
            raise ValueError(f"`friction` must be a FrictionLaw, got {type(self.friction).__name__}")
        if self.film is not None:
            if not isinstance(self.film, FilmLaw):
                raise ValueError(f"`film` must be a FilmLaw or None, got {type(self.film).__name__}")
            if self.film.geometry != self.law.geometry:
                raise ValueError(f"`film` was built for {self.film.geometry}, which differs from the law's "
                                 f"{self.law.geometry}")
        if self.wear is not None and not isinstance(self.wear, Wear):
            raise ValueError(f"`wear` must be an exuclear.Wear or None (no wear), got {type(self.wear).__name__}")
        if self.wear is not None and not isinstance(self.law.geometry, BearingGeometry):
            raise ValueError(f"`wear` is modelled for the revolute joint's journal and bearing (docs/physics.md "
                             f"section 11), not for the {self.law.geometry.joint_type} joint: give wear=None")

    @property
    def geometry(self) -> ContactGeometry:
        """The contact pair's geometry, which sets the joint type (a :class:`BearingGeometry`
        for the revolute joint, :class:`~exuclear.spherical.SphereGeometry` the spherical,
        :class:`~exuclear.prismatic.GuideGeometry` the translational,
        :class:`~exuclear.slot.SlotGeometry` the pin in a slot)."""
        return self.law.geometry

    def response(self, kin: ContactKinematics, history: ContactState) -> JointResponse:
        """Forces of the dry contact for the contact state ``kin`` given the last accepted
        ``history`` (docs/physics.md eqs. (9), (20), (24)-(26)); a lubricated joint's film
        adds :meth:`exuclear.film.FilmLaw.blended_load` (its kernels' ``Film``)."""
        f_n, f_t, v0 = contact_response(self.law.normal_force, self.friction, kin.delta, kin.delta_dot, kin.v_t,
                                        history)
        loads = joint_loads(self.law.geometry, kin, f_n, f_t) if kin.delta > 0.0 else _NO_LOADS
        return JointResponse(f_n, f_t, v0, loads)


def make_joint(
    *,
    journal_radius: float,
    bearing_radius: float,
    length: float,
    law: str | ContactLaw | None = None,
    cr: float | None = None,
    journal_material: str | Material | None = None,
    bearing_material: str | Material | None = None,
    E_star: float | None = None,
    friction: str | FrictionLaw = "none",
    v_min: float | None = None,
    stiffness: str | None = None,
    damping: str | None = None,
    lubrication: Lubrication | None = None,
    wear: Wear | None = None,
) -> ClearanceJoint:
    """Build a :class:`ClearanceJoint` from dimensions, materials and law names.

    Parameters
    ----------
    journal_radius, bearing_radius, length : float
        ``R_J < R_B`` and the bearing length ``L`` [m].
    law : str or ContactLaw, optional
        A law's name as :func:`exuclear.contact_law` takes it: a named law of
        :data:`exuclear.contact.CONTACT_LAWS` (default ``"wang-liu"``) or a pair
        ``"STIFFNESS+DAMPING"``; or a law built by :func:`exuclear.contact_law` (then
        ``cr``, the materials, ``E_star`` and ``v_min`` are the law's own: giving any of
        them raises ``ValueError``, and the law's geometry must match the radii and length).
    cr : float
        Coefficient of restitution in (0, 1]; required for every law with damping, 1 (the
        default there) for the elastic ones (``"hertz"``, damping ``"none"``).
    journal_material, bearing_material : str or Material, optional
        Names of :data:`exuclear.MATERIALS` or :class:`Material` objects; default steel.
    E_star : float, optional
        Composite modulus [Pa]; overrides the materials when given.
    friction : str or FrictionLaw
        ``"none"``, ``"coulomb:MU"``, ``"paper"`` or a :class:`FrictionLaw`.
    v_min : float, optional
        Floor of the onset velocity in the damping term [m/s]; default
        :data:`exuclear.contact.V_MIN_DEFAULT`.
    stiffness, damping : str, optional
        The law as a pair instead of ``law``: a name of
        :data:`exuclear.contact.STIFFNESS_MODELS` and one of
        :data:`exuclear.contact.DAMPING_MODELS`; a missing one is that of the default
        law (``liu``, ``zhiying-qishao``).
    lubrication : Lubrication, optional
        The oil of a lubricated joint (:class:`exuclear.Lubrication`: viscosity and film
        model); None (the default): the dry joint.  The film law is bound to this joint's
        geometry (``c = bearing_radius - journal_radius``, ``B = length``).
    wear : Wear, optional
        The wear of the surfaces (:class:`exuclear.Wear`); None (the default): none.
    """
    geometry = BearingGeometry(journal_radius, bearing_radius, length)
    film = _film(lubrication, geometry)
    law = _law(geometry, law, cr, ("journal_material", journal_material), ("bearing_material", bearing_material),
               E_star, v_min, stiffness, damping, DEFAULT_LAW)
    return ClearanceJoint(law, friction_law(friction), film, wear)


def make_spherical_joint(
    *,
    ball_radius: float,
    socket_radius: float,
    law: str | ContactLaw | None = None,
    cr: float | None = None,
    ball_material: str | Material | None = None,
    socket_material: str | Material | None = None,
    E_star: float | None = None,
    friction: str | FrictionLaw = "none",
    v_min: float | None = None,
    stiffness: str | None = None,
    damping: str | None = None,
) -> ClearanceJoint:
    """Build the physics of a spherical clearance joint: a ball of radius ``ball_radius`` in
    a socket of radius ``socket_radius`` > ``ball_radius`` [m] (:class:`exuclear.spherical.SphereGeometry`).

    The other arguments are :func:`make_joint`'s, with the ball's and the socket's
    materials; the default law is :data:`DEFAULT_SPHERICAL_LAW` (Hertz's sphere in a
    sphere, docs/physics.md eq. (13) with the ball's and the socket's radii).  The
    line-contact stiffness models (``liu``, ``johnson``, ...) need a contact length, which
    a ball does not have: they raise ``ValueError``.
    """
    geometry = SphereGeometry(ball_radius, socket_radius)
    law = _law(geometry, law, cr, ("ball_material", ball_material), ("socket_material", socket_material), E_star,
               v_min, stiffness, damping, DEFAULT_SPHERICAL_LAW)
    return ClearanceJoint(law, friction_law(friction))


def make_pin_slot_joint(
    *,
    pin_radius: float,
    slot_width: float,
    slot_length: float,
    length: float,
    law: str | ContactLaw | None = None,
    cr: float | None = None,
    pin_material: str | Material | None = None,
    slot_material: str | Material | None = None,
    E_star: float | None = None,
    friction: str | FrictionLaw = "none",
    v_min: float | None = None,
    stiffness: str | None = None,
    damping: str | None = None,
) -> ClearanceJoint:
    """Build the physics of a pin-in-slot clearance joint: a pin of radius ``pin_radius`` in a
    slot of width ``slot_width`` > 2 ``pin_radius`` whose end centres lie ``slot_length`` >= 0
    apart, the pin ``length`` long in contact [m] (:class:`exuclear.slot.SlotGeometry`).

    The law is the revolute joint's of a journal of radius ``pin_radius`` in a bearing of
    radius ``slot_width / 2`` (:func:`make_joint`'s arguments, with the pin's and the slot's
    materials): at ``slot_length = 0`` the joint is that revolute joint.  It takes no film
    and no wear.
    """
    check_positive("pin_radius", pin_radius)
    check_positive("slot_width", slot_width)
    check_positive("length", length)
    if not slot_width > 2.0 * pin_radius:
        raise ValueError(f"`slot_width` must be larger than the pin's diameter 2 `pin_radius` (clearance W/2 - R_P > 0), "
                         f"got W = {slot_width}, R_P = {pin_radius}")
    geometry = SlotGeometry(pin_radius, 0.5 * slot_width, length, slot_length)
    law = _law(geometry, law, cr, ("pin_material", pin_material), ("slot_material", slot_material), E_star, v_min,
               stiffness, damping, DEFAULT_LAW)
    return ClearanceJoint(law, friction_law(friction))


def make_prismatic_joint(
    *,
    slider_length: float,
    slider_height: float,
    clearance: float,
    stiffness: float | str,
    slider_width: float | None = None,
    clearance_width: float | None = None,
    guide_length: float | None = None,
    exponent: float | None = None,
    corner_radius: float | None = None,
    corner_length: float | None = None,
    slider_material: str | Material | None = None,
    guide_material: str | Material | None = None,
    E_star: float | None = None,
    damping: str = "lankarani-nikravesh",
    cr: float | None = None,
    friction: str | FrictionLaw = "none",
    v_min: float | None = None,
) -> ClearanceJoint:
    """Build the physics of a translational clearance joint: a slider ``slider_length`` by
    ``slider_height`` [m] in a guide ``slider_height + 2 clearance`` wide
    (:class:`exuclear.prismatic.GuideGeometry`), four corners against two walls; with
    ``slider_width`` [m] the spatial joint, a box in a channel ``slider_width + 2
    clearance_width`` deep (``clearance_width`` default ``clearance``), eight corners against
    four walls.  ``guide_length`` [m]: the walls end ``guide_length / 2`` either side of the
    guide's centre point, beyond which a corner is free (default: they do not end).

    A sharp corner has no radius of curvature: its law is ``F_e = K delta^n`` with ``K =
    stiffness`` [N/m^n] and ``n = exponent`` (default 1.5).  A rounded corner may take one
    of :data:`CORNER_STIFFNESS_MODELS` by name instead, ``E*`` from ``E_star`` or the
    slider's and the guide's materials (default steel):

    - ``"hertz"`` with ``corner_radius`` [m], a corner rounded to a ball (point contact):
      Hertz's sphere on a flat, ``K = 4/3 E* sqrt(corner_radius)``, ``n = 1.5``
      (docs/physics.md eq. (13) with the flat's radius infinite);
    - ``"dubowsky-freudenstein"`` with ``corner_radius`` and ``corner_length`` [m], a corner
      edge rounded to a cylinder along the slider's depth (line contact): the
      Dubowsky-Freudenstein law in its flat limit, ``delta = F / (pi L E*) [ln(pi L^3 E* /
      (F r)) + 1]`` with ``L = corner_length``, ``r = corner_radius``
      (:class:`exuclear.contact.stiffness.DubowskyFreudenstein`).

    The damping model ``damping`` (:data:`exuclear.contact.DAMPING_MODELS`) has restitution
    ``cr`` (required unless ``damping="none"``), ``v_min`` [m/s] as in :func:`make_joint`;
    ``friction`` acts along the wall.
    """
    geometry = GuideGeometry(slider_length, slider_height, clearance, corner_radius, corner_length, guide_length,
                             slider_width, clearance_width)
    if cr is None:
        if str(damping).lower() != "none":
            raise ValueError(f"`cr` is required with damping={damping!r}: the corners' coefficient of restitution, "
                             "0 < cr <= 1 (or damping='none' for elastic corners)")
        cr = 1.0
    model = _corner_stiffness(geometry, stiffness, exponent, slider_material, guide_material, E_star)
    law = ContactLaw(model, damping_model(damping, cr), V_MIN_DEFAULT if v_min is None else v_min)
    return ClearanceJoint(law, friction_law(friction))


#: The named stiffness models a slider's rounded corner takes on its flat wall: Hertz's
#: sphere on a flat (a corner rounded to a ball) and the one line-contact law with a flat
#: limit (an edge rounded to a cylinder); the library's other line laws need a conforming
#: outer radius (:class:`exuclear.contact.stiffness.DubowskyFreudenstein` says why).
CORNER_STIFFNESS_MODELS = ("hertz", "dubowsky-freudenstein")


def _corner_stiffness(geometry: GuideGeometry, stiffness: float | str, exponent: float | None,
                      slider_material: Any, guide_material: Any, E_star: float | None) -> StiffnessModel:
    """A corner's stiffness model from :func:`make_prismatic_joint`'s arguments: a number ``K``
    as given, or one of :data:`CORNER_STIFFNESS_MODELS` for the rounded corner of ``geometry``."""
    rounded = [name for name in ("corner_radius", "corner_length") if getattr(geometry, name) is not None]
    materials = [name for name, value in (("slider_material", slider_material), ("guide_material", guide_material),
                                          ("E_star", E_star)) if value is not None]
    known = "'hertz' (with `corner_radius`) or 'dubowsky-freudenstein' (with `corner_radius` and `corner_length`)"
    if not isinstance(stiffness, str):
        if rounded or materials:
            given = ", ".join(f"`{name}`" for name in rounded + materials)
            raise ValueError(f"a numeric `stiffness` is the corner's K itself: leave out {given}, or give a rounded "
                             f"corner's stiffness model, {known}")
        return GivenStiffness(geometry, 1.0, stiffness, EXPONENT_METAL if exponent is None else exponent)
    name = stiffness.lower()
    if name not in CORNER_STIFFNESS_MODELS:
        why = (" (its formula needs the outer radius of a conforming pair, which a flat wall does not have)"
               if name in STIFFNESS_MODELS else "")
        raise ValueError(f"`stiffness` must be a number K [N/m^n] or a stiffness model of a corner on a flat wall, "
                         f"{known}; got {stiffness!r}{why}")
    if geometry.corner_radius is None:
        raise ValueError(f"stiffness={stiffness!r} needs `corner_radius` [m], the radius of the slider's rounded corners")
    if exponent is not None:
        raise ValueError(f"`exponent` is fixed by the {stiffness!r} stiffness; leave it out")
    if E_star is None:
        E_star = composite_modulus(DEFAULT_MATERIAL if slider_material is None else slider_material,
                                   DEFAULT_MATERIAL if guide_material is None else guide_material)
    E_star = check_positive("E_star", E_star)
    if name == "hertz":
        if geometry.corner_length is not None:
            raise ValueError("stiffness='hertz' is a corner rounded to a ball, a point contact: leave out "
                             "`corner_length`, or give stiffness='dubowsky-freudenstein' for an edge rounded along it")
        return GivenStiffness(geometry, 1.0, 4.0 / 3.0 * E_star * geometry.corner_radius ** 0.5, EXPONENT_METAL)
    if geometry.corner_length is None:
        raise ValueError(f"stiffness={stiffness!r} is a line contact along the rounded corner edge: give "
                         "`corner_length` [m], the edge's length (the slider's depth across the plane)")
    return stiffness_model(name, geometry, E_star)


def _law(geometry: ContactGeometry, law: str | ContactLaw | None, cr: float | None, inner: tuple[str, Any],
         outer: tuple[str, Any], E_star: float | None, v_min: float | None, stiffness: str | None,
         damping: str | None, default_law: str) -> ContactLaw:
    """The contact law a builder's arguments ask for, in ``geometry``; ``inner``, ``outer``:
    the two bodies' material arguments (name, value)."""
    if isinstance(law, ContactLaw):
        if stiffness is not None or damping is not None:
            raise ValueError("give either `law` or `stiffness`/`damping`, not both")
        given = [name for name, value in (("cr", cr), inner, outer, ("E_star", E_star), ("v_min", v_min))
                 if value is not None]
        if given:
            raise ValueError(f"a ready `law` carries its own cr, materials (E_star) and v_min; leave out "
                             f"{', '.join(f'`{name}`' for name in given)} or give the law by name")
        if law.geometry != geometry:
            raise ValueError(f"`law` was built for {law.geometry}, which differs from {geometry}")
        return law
    law, cr = law_and_restitution(law, stiffness, damping, cr, default_law=default_law, default_cr=None)
    if E_star is None:
        E_star = composite_modulus(DEFAULT_MATERIAL if inner[1] is None else inner[1],
                                   DEFAULT_MATERIAL if outer[1] is None else outer[1])
    return contact_law(law, geometry, E_star, cr, V_MIN_DEFAULT if v_min is None else v_min)


def _film(lubrication: Lubrication | None, geometry: BearingGeometry) -> FilmLaw | None:
    """The film law of ``lubrication`` in ``geometry``, or None for a dry joint."""
    if lubrication is None:
        return None
    if not isinstance(lubrication, Lubrication):
        raise ValueError(f"`lubrication` must be an exuclear.Lubrication (viscosity, model) or None (dry), got "
                         f"{type(lubrication).__name__}")
    return lubrication.law(geometry)
