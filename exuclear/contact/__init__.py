"""Normal contact force laws for a journal in a bearing: a stiffness model and a damping model.

Every law here has the form of docs/physics.md eq. (9),

    F_N = F_e(delta) * (1 + D * delta_dot / v0_eff),   F_N >= 0,

zero for ``delta <= 0``, with ``v0_eff = max(v0, v_min)``.  Two families supply the two
factors, and a :class:`ContactLaw` is one member of each.  The package holds one role per
module:

- :mod:`.stiffness`: a :class:`StiffnessModel` gives the elastic force ``F_e(delta)`` of a
  cylinder in a conforming hole (:data:`STIFFNESS_MODELS`), written ``K_eff(delta) * delta^n``
  where the model is a power law;
- :mod:`.damping`: a :class:`DampingModel` gives the constant hysteresis factor ``D`` from
  the coefficient of restitution ``cr`` (:data:`DAMPING_MODELS`);
- :mod:`.restitution`: the exact relation between ``D`` and the effective restitution of
  one impact, which some damping models invert;
- :mod:`.law`: eq. (9) itself (:func:`damped_normal_force`), the :class:`ContactLaw` pair,
  the five named laws and the parsing of law names.

The five named laws are fixed pairs (:data:`CONTACT_LAWS`, :data:`ALIASES`):
``wang-liu`` = ``liu+zhiying-qishao``, ``lankarani-nikravesh`` = ``hertz+lankarani-nikravesh``,
``hertz`` = ``hertz+none``, ``hunt-crossley`` = ``hertz+hunt-crossley``,
``flores`` = ``hertz+flores``.  Any other pair is named ``"STIFFNESS+DAMPING"``, e.g.
``"pereira+gonthier"``.

The compiled kernel evaluates the same formulas; each stiffness model names its formula by
:attr:`StiffnessModel.kernel_code` and hands the constants it needs over in
:meth:`StiffnessModel.kernel_parameters`.

Units: SI.  Sign convention: ``delta > 0`` is penetration, ``delta_dot > 0`` is approach
(compression), ``v0 > 0`` the approach speed at contact onset.
"""
from ..exceptions import ValidityWarning
from .damping import (
    DAMPING_MODELS,
    CarvalhoMartinsDamping,
    DampingModel,
    FloresDamping,
    GonthierDamping,
    HerbertMcWhannellDamping,
    HuGuoDamping,
    HuntCrossleyDamping,
    LankaraniNikraveshDamping,
    LeeWangDamping,
    NoDamping,
    ZhiyingQishaoDamping,
    damping_model,
)
from .law import (
    ALIASES,
    CONTACT_LAWS,
    DEFAULT_LAW,
    PAIR_SEPARATOR,
    V_MIN_DEFAULT,
    ContactLaw,
    Flores,
    Hertz,
    HuntCrossley,
    LankaraniNikravesh,
    WangLiu,
    compose_law,
    contact_law,
    damped_normal_force,
    is_elastic,
    law_and_restitution,
    pair_name,
    split_law_name,
)
from .restitution import RESTITUTION_RTOL, damping_for_restitution, restitution_of_damping
from .stiffness import (
    ESDU78035,
    EXPONENT_METAL,
    IMPLICIT_MAX_ITER,
    IMPLICIT_RTOL,
    STIFFNESS_MODELS,
    DubowskyFreudenstein,
    Johnson,
    Liu,
    Pereira,
    PointContact,
    Radzimovsky,
    StiffnessModel,
    stiffness_model,
)

__all__ = [
    # the normal force and the law
    "V_MIN_DEFAULT", "damped_normal_force", "ContactLaw", "compose_law", "contact_law",
    # named laws and law names
    "WangLiu", "LankaraniNikravesh", "Hertz", "HuntCrossley", "Flores", "CONTACT_LAWS", "ALIASES", "DEFAULT_LAW",
    "PAIR_SEPARATOR", "pair_name", "split_law_name", "is_elastic", "law_and_restitution",
    # stiffness models
    "EXPONENT_METAL", "IMPLICIT_RTOL", "IMPLICIT_MAX_ITER", "StiffnessModel", "PointContact", "Liu", "Pereira",
    "Johnson", "Radzimovsky", "ESDU78035", "DubowskyFreudenstein", "STIFFNESS_MODELS", "stiffness_model",
    # damping models and the restitution relation
    "DampingModel", "NoDamping", "LankaraniNikraveshDamping", "HuntCrossleyDamping", "FloresDamping",
    "GonthierDamping", "HuGuoDamping", "CarvalhoMartinsDamping", "ZhiyingQishaoDamping", "LeeWangDamping",
    "HerbertMcWhannellDamping", "DAMPING_MODELS", "damping_model", "RESTITUTION_RTOL", "restitution_of_damping",
    "damping_for_restitution",
    # warnings
    "ValidityWarning",
]
