"""A contact law: one stiffness model and one damping model in docs/physics.md eq. (9).

:class:`ContactLaw` is the pair; :func:`compose_law` builds any pair by its members'
names, :func:`contact_law` by a law's name.  The five named laws (:data:`CONTACT_LAWS`,
:data:`ALIASES`) are pairs with fixed members; the other pairs are named
``"STIFFNESS+DAMPING"`` (:func:`split_law_name`, :func:`pair_name`).
:func:`law_and_restitution` reads a command line's law options.
"""
from __future__ import annotations

from dataclasses import dataclass, field
from typing import ClassVar

from ..checks import check_choice, check_open_closed, check_positive, check_real
from .damping import (
    DAMPING_MODELS,
    DampingModel,
    FloresDamping,
    HuntCrossleyDamping,
    LankaraniNikraveshDamping,
    NoDamping,
    ZhiyingQishaoDamping,
    damping_model,
)
from .pair import ContactGeometry
from .stiffness import EXPONENT_METAL, STIFFNESS_MODELS, Liu, PointContact, StiffnessModel, stiffness_model

#: Default floor of the onset velocity in the damping term [m/s] (docs/physics.md eq. (17)):
#: grazing contact has v0 -> 0 and D * delta_dot / v0 would blow up.
V_MIN_DEFAULT = 1e-3


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
    def geometry(self) -> ContactGeometry:
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


def compose_law(stiffness: str, damping: str, geometry: ContactGeometry, E_star: float, cr: float = 1.0,
                v_min: float = V_MIN_DEFAULT, exponent: float | None = None) -> ContactLaw:
    """The contact law of the stiffness model ``stiffness`` and the damping model ``damping``.

    ``cr`` must be 1 with ``damping="none"``; ``exponent`` applies to the ``hertz`` and
    ``liu`` stiffness models only (default 1.5).
    """
    return ContactLaw(stiffness_model(stiffness, geometry, E_star, exponent), damping_model(damping, cr), v_min)


# -- the five named laws: pairs with fixed members ---------------------------------------
class _NamedLaw(ContactLaw):
    """A named pair; built from ``(geometry, E_star, cr, v_min, exponent)``."""

    name: ClassVar[str] = ""
    _stiffness: ClassVar[type[StiffnessModel]] = PointContact
    _damping: ClassVar[type[DampingModel]] = NoDamping

    def __init__(self, geometry: ContactGeometry, E_star: float, cr: float = 1.0, v_min: float = V_MIN_DEFAULT,
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

    def __init__(self, geometry: ContactGeometry, E_star: float, cr: float = 1.0, v_min: float = V_MIN_DEFAULT,
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


def pair_name(stiffness: str | None = None, damping: str | None = None, default_law: str = DEFAULT_LAW) -> str:
    """``"STIFFNESS+DAMPING"``; a missing member is that of ``default_law`` (by default
    :data:`DEFAULT_LAW`: ``liu``, ``zhiying-qishao``)."""
    default_s, default_d = split_law_name(default_law)
    return f"{stiffness or default_s}{PAIR_SEPARATOR}{damping or default_d}"


def split_law_name(name: str) -> tuple[str, str]:
    """``(stiffness, damping)`` of a law name: a named law or ``"STIFFNESS+DAMPING"``.

    ``ValueError`` listing the known names for an unknown one.
    """
    if isinstance(name, str) and PAIR_SEPARATOR in name:
        stiffness, _, damping = name.partition(PAIR_SEPARATOR)
        return (check_choice("stiffness", stiffness, STIFFNESS_MODELS, ignore_case=True),
                check_choice("damping", damping, DAMPING_MODELS, ignore_case=True))
    return ALIASES[check_choice("law", name, CONTACT_LAWS, ignore_case=True)]


def is_elastic(name: str) -> bool:
    """True if the law named ``name`` has no damping (it then takes only ``cr = 1``);
    False for dissipative and for unknown names (which fail where the law is built)."""
    try:
        return not DAMPING_MODELS[split_law_name(name)[1]].dissipative
    except ValueError:
        return False


def contact_law(
    name: str,
    geometry: ContactGeometry,
    E_star: float,
    cr: float = 1.0,
    v_min: float = V_MIN_DEFAULT,
    exponent: float | None = None,
) -> ContactLaw:
    """Build a contact law by its name: one of :data:`CONTACT_LAWS` or ``"STIFFNESS+DAMPING"``
    with names of :data:`STIFFNESS_MODELS` and :data:`DAMPING_MODELS`."""
    if isinstance(name, str) and PAIR_SEPARATOR in name:
        return compose_law(*split_law_name(name), geometry, E_star, cr, v_min, exponent)
    cls = CONTACT_LAWS[check_choice("law", name, CONTACT_LAWS, ignore_case=True)]
    return cls(geometry, check_real("E_star", E_star), cr, v_min, EXPONENT_METAL if exponent is None else exponent)


def law_and_restitution(law: str | None = None, stiffness: str | None = None, damping: str | None = None,
                        cr: float | None = None, default_law: str = DEFAULT_LAW,
                        default_cr: float | None = 0.9) -> tuple[str, float]:
    """The law name and ``cr`` that a command line's options or :func:`exuclear.make_joint`'s
    arguments ask for.

    ``law`` or the pair ``stiffness``/``damping`` (not both; a missing member of the pair
    is that of the default law); ``cr`` defaults to ``default_cr`` for a law with damping
    (``default_cr=None``: ``cr`` is then required, ``ValueError``) and to 1 for an elastic
    one, so that ``--law hertz`` alone is accepted.  Unknown names raise ``ValueError``
    listing the known ones.
    """
    if stiffness is not None or damping is not None:
        if law is not None:
            raise ValueError("give either `law` or `stiffness`/`damping`, not both")
        law = pair_name(stiffness, damping, default_law)
    elif law is None:
        law = default_law
    split_law_name(law)  # unknown names fail here, listing the known ones
    if cr is None:
        if is_elastic(law):
            cr = 1.0
        elif default_cr is None:
            raise ValueError(f"`cr` (coefficient of restitution in (0, 1]) is required for the {law!r} law")
        else:
            cr = default_cr
    return law, cr
