"""The clearance joint's fields of the scenes' parameter dataclasses, described once.

Every scene has a clearance joint, and its parameter dataclass holds that joint's values
as fields of the same meaning, rule and command-line option in each scene.  A run of them
is one :func:`joint_fields` in the class body, a lone one a :func:`joint_field`::

    @scene_params
    class FourBarParams:
        ...
        gravity: float = field(metadata=param("gravity along -Y [m/s^2]", nonnegative))
        _joint_fields = joint_fields("bearing_radius", "clearance", "bearing_length", "law", "cr",
                                     help={"bearing_radius": "bearing radius R_B at B [m]"})
        crank_angle0: float = field(default=0.0, metadata=param(...))
        v_min: float = joint_field("v_min")

:func:`scene_params` makes the class a frozen dataclass with each run's fields in its place
(``bearing_radius`` ... ``cr``, then ``crank_angle0``, then ``v_min``); their types, defaults
and :func:`~exuclear.models._params.param` metadata come from :data:`JOINT_FIELDS`.
:func:`scene_joint` builds the joint (:func:`exuclear.make_joint`) from whichever of these
fields a scene has.  A scene keeps its own field names and order; its help text replaces the
shared one only where it says something of that scene (which bearing).
"""
from __future__ import annotations

import inspect
from dataclasses import MISSING, Field, dataclass, field, fields
from typing import Any, NamedTuple, TypeVar

import exuclear
from exuclear.contact import V_MIN_DEFAULT
from exuclear.engine import BACKENDS, DEFAULT_BACKEND
from exuclear.materials import MATERIALS
from exuclear.wear import PRESSURES, SURFACES

from ._lubricant import FILM_MODEL_DEFAULT, FILM_MODEL_NAMES, lubrication
from ._params import Check, one_of, optional, param, positive


class JointField(NamedTuple):
    """The description of one joint field.

    ``type`` is the field's annotation; ``argument`` the :func:`exuclear.make_joint` argument
    its value goes to (None: one the joint is not built from directly); ``default`` its
    default (``MISSING``: none, the scene's named constructor gives the value); the others
    are :func:`~exuclear.models._params.param`'s.
    """

    type: str
    help: str
    check: Check | None = None
    argument: str | None = None
    option: str | None = None
    cli: bool = True
    choices: tuple[str, ...] | None = None
    default: Any = MISSING


#: The bearing length's two names: a scene's field has one, its command line takes the other
#: as a second option (``--length`` and ``--bearing-length`` both set it).
LENGTH_NAMES = ("length", "bearing_length")

#: The joint fields by name (the bearing length under ``"length"``, see :data:`LENGTH_NAMES`).
JOINT_FIELDS: dict[str, JointField] = {
    "journal_radius": JointField("float", "journal radius R_J [m]", positive, "journal_radius"),
    "bearing_radius": JointField("float", "bearing radius R_B [m]", positive, "bearing_radius"),
    # a scene that gives the clearance has the journal radius R_B - c (scene_joint)
    "clearance": JointField("float", "radial clearance [m]", positive),
    "length": JointField("float", "bearing length L [m]", positive, "length"),
    # --law, --stiffness, --damping and --cr are the scenes' own options (_cli.add_law_options)
    "law": JointField("str", "contact law", argument="law", cli=False),
    "cr": JointField("float", "coefficient of restitution", argument="cr", cli=False),
    "journal_material": JointField("str", f"journal material: {', '.join(MATERIALS)}",
                                   argument="journal_material", option="journal"),
    "bearing_material": JointField("str", "bearing material", argument="bearing_material", option="bearing"),
    "friction": JointField("str", "friction law: none | coulomb:MU | paper", argument="friction"),
    "v_min": JointField("float", "floor of v0 in the damping term [m/s]", argument="v_min", default=V_MIN_DEFAULT),
    # how the joint is added (exuclear.AddClearanceJoint), not what it is: no make_joint argument
    "backend": JointField("str", "the joint's kernel: compiled (C++) or python", one_of(sorted(BACKENDS)),
                          choices=tuple(BACKENDS), default=DEFAULT_BACKEND),
    "max_penetration": JointField(
        "float | None", "penetration [m] beyond which the run stops (default: the larger of half the clearance "
        "and 0.1 % of the journal radius)", optional(positive), default=None),
    # the oil: make_joint's `lubrication`, from the two together (scene_joint)
    "viscosity": JointField("float | None", "dynamic viscosity of the oil in the clearance joint [Pa s] (default: "
                            "none, a dry joint)", optional(positive), default=None),
    "film_model": JointField("str", "the oil film's model (docs/physics.md section 10), with --viscosity",
                             one_of(FILM_MODEL_NAMES), choices=FILM_MODEL_NAMES, default=FILM_MODEL_DEFAULT),
    # the wear: make_joint's `wear`, from the three together (scene_joint)
    "wear_coefficient": JointField("float | None", "wear coefficient k_D = k / H of Archard's law [1/Pa] (default: "
                                   "none, no wear; docs/physics.md section 11)", optional(positive), default=None),
    "wear_surface": JointField("str", "which surfaces wear, with --wear-coefficient", one_of(SURFACES),
                               choices=SURFACES, default="bearing"),
    "wear_pressure": JointField("str", "the pressure over the contact arc for the wear, with --wear-coefficient",
                                one_of(PRESSURES), choices=PRESSURES, default="winkler"),
}


def _described(name: str) -> JointField:
    """The description of the joint field ``name``; ``KeyError`` listing the known names."""
    key = "length" if name in LENGTH_NAMES else name
    if key not in JOINT_FIELDS:
        raise KeyError(f"no joint field {name!r}; known: {', '.join([*JOINT_FIELDS, *LENGTH_NAMES[1:]])}")
    return JOINT_FIELDS[key]


def joint_field(name: str, *, help: str | None = None, second_option: bool = True) -> Field:
    """The dataclass field of the joint value ``name`` (a key of :data:`JOINT_FIELDS`, or
    ``"bearing_length"``): its default, and its :func:`~exuclear.models._params.param`
    metadata with the make_joint argument under ``"joint"``.

    ``help`` replaces the shared help text where the scene's says more (which bearing);
    ``second_option`` False leaves out the second option name (a scene whose command line
    never had it).
    """
    described = _described(name)
    option = described.option
    if name in LENGTH_NAMES:
        option = next(other for other in LENGTH_NAMES if other != name)
    metadata = param(described.help if help is None else help, described.check,
                     option=option if second_option else None, cli=described.cli, choices=described.choices)
    return field(default=described.default, metadata={**metadata, "joint": described.argument})


class JointFields(NamedTuple):
    """A run of joint fields in a scene's class body (:func:`joint_fields`), put in its place by
    :func:`scene_params`."""

    names: tuple[str, ...]
    help: dict[str, str]
    second_option: bool

    def fields(self) -> list[tuple[str, str, Field]]:
        """Each field's name, annotation and :func:`joint_field`, in order."""
        return [(name, _described(name).type, joint_field(name, help=self.help.get(name),
                                                          second_option=self.second_option))
                for name in self.names]


def joint_fields(*names: str, help: dict[str, str] | None = None, second_option: bool = True) -> JointFields:
    """The joint fields ``names``, in this order, where this stands in a :func:`scene_params`
    class body; ``help`` by name and ``second_option`` as in :func:`joint_field`."""
    for name in names:
        _described(name)  # an unknown name is refused where the class is written
    unknown = [name for name in (help or {}) if name not in names]
    if unknown:
        raise KeyError(f"help for {unknown}, which are not among the fields {names}")
    return JointFields(names, dict(help or {}), second_option)


T = TypeVar("T", bound=type)


def scene_params(cls: T) -> T:
    """The frozen dataclass of the scene parameters ``cls``: its own fields, and the fields of
    each :func:`joint_fields` in its body where that stands (the name it is given there is
    not kept).

    Every field of the body needs a value (``field(...)``): the order of the body's names
    is what places the joint fields among them.
    """
    own = dict(inspect.get_annotations(cls))
    annotations: dict[str, str] = {}
    for name, value in list(vars(cls).items()):
        if isinstance(value, JointFields):
            delattr(cls, name)
            for field_name, annotation, joint in value.fields():
                annotations[field_name] = annotation
                setattr(cls, field_name, joint)
        elif name in own:
            annotations[name] = own.pop(name)
    if own:
        raise TypeError(f"{cls.__name__}: give the fields {', '.join(own)} a value, field(...), so that their "
                        "place among the joint fields is known")
    cls.__annotations__ = annotations
    return dataclass(frozen=True)(cls)


def scene_joint(params: object) -> exuclear.ClearanceJoint:
    """The clearance joint (:func:`exuclear.make_joint`) of a scene's parameters ``params``,
    from its joint fields; what a scene has no field for is make_joint's default (steel, no
    friction, a dry joint).

    A scene that gives the ``clearance`` and no journal radius has ``R_J = R_B - c``; its
    clearance must then be smaller than the bearing radius (``ValueError``).  A scene with a
    ``viscosity`` has a lubricated joint where that is given (:func:`lubrication`).
    """
    names = {f.name for f in fields(params)}
    arguments = {f.metadata["joint"]: getattr(params, f.name) for f in fields(params) if f.metadata.get("joint")}
    if "clearance" in names and "journal_radius" not in arguments:
        clearance, bearing_radius = params.clearance, params.bearing_radius
        if clearance >= bearing_radius:
            raise ValueError(f"`clearance` must be smaller than `bearing_radius` (the journal radius is their "
                             f"difference), got clearance = {clearance}, bearing_radius = {bearing_radius}")
        arguments["journal_radius"] = bearing_radius - clearance
    if "viscosity" in names:
        arguments["lubrication"] = lubrication(params.viscosity, params.film_model)
    if "wear_coefficient" in names and params.wear_coefficient is not None:
        arguments["wear"] = exuclear.Wear(coefficient=params.wear_coefficient, surface=params.wear_surface,
                                          pressure=params.wear_pressure)
    return exuclear.make_joint(**arguments)
