"""Where a clearance joint's parameters and outputs sit in its Exudyn items.

Every joint type shares one parameter matrix: the fields of row 0 to 3 (the radii of the
contact pair, the law, friction, the step control) serve every type; rows 4 and 5 hold the
revolute joint's own (slices, length, axial clearance, film, wear), which a spherical joint
leaves at 0 and a translational joint uses only for its slider's length (its guide length and
box width are in the ``damping`` matrix, :data:`SECOND_LAYOUT`).  ``joint_type`` says which
contacts the kernels build from them.

Parameters.  Exudyn hands a connector's ``stiffness`` matrix (6 x 6) to its user
functions on every call, so the joint's physics lives there, readable by the compiled
and the Python kernel alike (``mbs.GetObject(joint.objectNumber)["stiffness"]``).
:data:`LAYOUT` names every field: its row, first column, number of entries and meaning.
Both languages read it by name: Python through :func:`read` and :func:`parameters`, the
compiled kernel through its copy of the table (``Field`` and ``LAYOUT`` in
``exuclear/_kernel/layout.hpp``, exported as ``exuclear._ckernel.LAYOUT``), which
a test keeps equal to this one.

The connector's ``damping`` matrix, handed to the user functions too, holds the handle's
mark and what a joint type needs beyond :data:`LAYOUT` (:data:`SECOND_LAYOUT`: a
translational joint's guide length and box width), read by name in the same way.

Outputs.  The joint's ``NodeGenericData`` holds, after every accepted step, the
quantities of :data:`DATA_COLUMNS` (SI units); a ``SensorNode`` on it with
``OutputVariableType.Coordinates`` records them.  A spatial joint's node holds
:func:`spatial_data_columns` instead: the journal's tilt and axial position, then the
planar columns (without the time) once per slice, then, with an axial clearance, once per
end face.  A spherical joint's node holds :data:`BALL_DATA_COLUMNS`.
"""
from __future__ import annotations

from collections.abc import Sequence
from typing import Any, NamedTuple

import numpy as np

from ..contact import ContactLaw
from ..contact.pair import ContactGeometry
from ..friction import Coulomb, FrictionLaw, ModifiedCoulomb, NoFriction
from ..joint import ClearanceJoint
from ..settings import RATE_LIMIT_DEFAULT
from ..spatial import ShoulderGeometry
from ..wear.law import Wear

MAIN, PROBE, TORQUE = 0, 1, 2
#: Joint type (``ContactGeometry.joint_type``) -> code in the parameter matrix (layout.hpp ``JointType``).
JOINT_TYPE_CODES = {"revolute": 0, "spherical": 1, "prismatic": 2, "pin-slot": 3}
#: Size of the parameter matrix (Exudyn's connector ``stiffness``: 6 x 6).
MATRIX_SIZE = 6


class Field(NamedTuple):
    """One field of the parameter matrix: entries ``[row][column : column + size]``."""

    name: str
    row: int
    column: int
    size: int
    meaning: str


#: The parameter matrix, field by field (the compiled kernel's ``LAYOUT`` in the same order).
LAYOUT = (
    Field("joint_id", 0, 0, 1, "the joint's entry in the compiled kernel's table (-1: the Python kernel)"),
    Field("role", 0, 1, 1, "which connector: 0 the joint, 1 the bearing-spin probe, 2 the bearing torque"),
    Field("joint_type", 0, 2, 1, "the joint type's code (JOINT_TYPE_CODES): which contacts the kernels build"),
    Field("inner_radius", 0, 3, 1, "R_J [m] of the journal, R_B of the ball, a slider's H/2 (ContactGeometry.inner_radius)"),
    Field("outer_radius", 0, 4, 1, "R_B [m] of the bearing, R_S of the socket, a guide's H/2 + c (ContactGeometry.outer_radius)"),
    Field("max_penetration", 0, 5, 1, "penetration [m] beyond which a run stops"),
    Field("impact_step", 1, 0, 1, "step [s] that redoes a step in which a contact begins (0: off)"),
    Field("stiffness_code", 1, 1, 1, "the stiffness model's kernel_code (-1: a law for the Python kernel only)"),
    Field("damping_factor", 1, 2, 1, "D of eq. (9) (dimensionless)"),
    Field("v_min", 1, 3, 1, "floor of the onset velocity in eq. (9) [m/s]"),
    Field("friction_code", 1, 4, 1, "0 none, 1 Coulomb, 2 modified Coulomb (-1: the Python kernel only)"),
    Field("stiffness_constants", 2, 0, 5, "the stiffness model's kernel_parameters() (at most 5, the line-contact "
                                          "models'; the row's last entry holds wear_code)"),
    Field("friction_constants", 3, 0, 4, "Coulomb (mu, v_eps); modified Coulomb (mu_s, mu_d, v_s, v_d)"),
    Field("slices", 4, 0, 1, "number of slices N of the spatial joint (0: the planar joint)"),
    Field("length", 4, 1, 1, "bearing length L [m]; a translational joint's slider length, a pin-in-slot joint's slot length"),
    Field("axis_journal", 4, 2, 3, "the journal axis in the journal marker's frame (eq. (34))"),
    Field("axial_clearance", 5, 0, 1, "total axial play g [m] of the end faces (0: none; section 9.6)"),
    Field("friction_radius", 5, 1, 1, "R_e [m] of the end faces, eq. (51)"),
    Field("face_stiffness", 5, 2, 1, "K_f [N/m] of the end faces, eq. (52)"),
    Field("film_model", 3, 4, 1, "the film model's code (FILM_CODES; 0: a dry joint; section 10)"),
    Field("viscosity", 3, 5, 1, "eta [Pa s] of the film"),
    Field("eps_film", 5, 4, 1, "eccentricity ratio below which the film acts alone, eq. (70)"),
    Field("eps_cap", 5, 5, 1, "eccentricity ratio the film's argument tends to at the wall, eq. (70)"),
    Field("rate_limit", 1, 5, 1, "KAPPA of the joint's own step control: the change of the penetration rate a "
                                 "step may hold, as a fraction of the onset velocity (0: off)"),
    Field("bearing_motion", 4, 5, 1, "1: the loads use the bearing's own spin, from the probe connector; 0: they "
                                     "do not need it (uses_bearing_motion), the probe and torque connectors are off "
                                     "and the kernels take the spin as 0"),
    Field("wear_code", 2, 5, 1, "a joint's wear (section 11; a spatial joint's per slice, 11.7): surface code + 4 pressure code + 8 nodes "
                                "(wear_code; 0: no wear)"),
    Field("wear_coefficient", 5, 3, 1, "k_D [1/Pa] of the wear's Archard law, eq. (79)"),
)
FIELDS = {f.name: f for f in LAYOUT}

#: The connector's ``damping`` matrix (6 x 6), which Exudyn hands to the user functions beside
#: ``stiffness`` (the connector's own law is the user function, so Exudyn reads neither): the
#: handle's mark and the fields a joint type needs where :data:`LAYOUT` has no free entry, field
#: by field (the compiled kernel's ``SECOND_LAYOUT`` in the same order; the Python kernel reads
#: them of the joint's geometry).  0 in a field is its default.
SECOND_LAYOUT = (
    Field("token", 0, 0, 1, "the handle's mark of its connector (is_live); no kernel reads it"),
    Field("guide_length", 0, 1, 1, "a translational joint's guide length [m] (0: the walls do not end)"),
    Field("slider_half_width", 0, 2, 1, "the spatial translational joint's slider half-width B/2 [m] (0: the "
                                        "planar joint)"),
    Field("channel_half_width", 0, 3, 1, "its channel's half-depth B/2 + c_z [m], the far and near walls' distance "
                                         "from the centre line"),
)
SECOND_FIELDS = {f.name: f for f in SECOND_LAYOUT}
#: Where the handle marks its connector (``is_live``).
TOKEN_ENTRY = (SECOND_FIELDS["token"].row, SECOND_FIELDS["token"].column)


def read(matrix: Any, name: str, fields: dict[str, Field] = FIELDS) -> Any:
    """A field of a parameter matrix: a float, or a tuple for a field of several entries
    (``fields``: :data:`SECOND_FIELDS` for the ``damping`` matrix)."""
    f = fields[name]
    row = matrix[f.row]
    if f.size == 1:
        return row[f.column]
    return tuple(row[f.column + i] for i in range(f.size))


def write(matrix: np.ndarray, name: str, value: float | Sequence[float], fields: dict[str, Field] = FIELDS) -> None:
    """Set a field of a parameter matrix; a field of several entries takes up to ``size`` values."""
    f = fields[name]
    if f.size == 1:
        matrix[f.row, f.column] = value
        return
    values = tuple(value)
    if len(values) > f.size:
        raise ValueError(f"parameter field {name!r} holds {f.size} values, got {len(values)}")
    matrix[f.row, f.column:f.column + len(values)] = values


#: The data node's entries, in order (both kernels' ``data_values``).
DATA_COLUMNS = ("time", "penetration", "penetration_rate", "ecc_x", "ecc_y", "normal_force", "tangential_force",
                "slip_velocity", "v0", "in_contact", "onsets", "onset_time", "peak_force", "max_penetration")

#: A lubricated planar joint's data node: :data:`DATA_COLUMNS`, then these (the film force
#: on the journal [N] in the bearing's joint frame and the journal's viscous moment [N m],
#: eqs. (68)-(69), at the accepted state); a dry joint's node keeps :data:`DATA_COLUMNS` only.
FILM_DATA_COLUMNS = ("film_fx", "film_fy", "film_torque")

#: The spherical joint's data node: :data:`DATA_COLUMNS` of its ball, then the ball's
#: eccentricity along z (the joint frame's), as its ``ecc_x``, ``ecc_y``.
BALL_DATA_COLUMNS = DATA_COLUMNS + ("ecc_z",)

#: The spatial joint's own entries, before the slices' (``spatial_data_values``).
SPATIAL_JOINT_COLUMNS = ("time", "tilt_x", "tilt_y", "axial_displacement")
#: Each slice's entries in the spatial data node, in order.
SLICE_COLUMNS = DATA_COLUMNS[1:]


#: The translational joint's data node: the time, then :data:`SLICE_COLUMNS` of each
#: corner-wall pair in :data:`exuclear.prismatic.PAIRS`' order (``ecc_x``, ``ecc_y``: the corner).
def pair_data_columns(pairs: int) -> tuple[str, ...]:
    """Names of the translational joint's data-node entries: ``"time"``, then ``SLICE_COLUMNS``
    of pair 0, 1, ... as ``"normal_force[3]"``."""
    return ("time", *(f"{c}[{k}]" for k in range(pairs) for c in SLICE_COLUMNS))


def spatial_data_columns(slices: int, faces: int = 0, lubricated: bool = False) -> tuple[str, ...]:
    """Names of a spatial joint's data-node entries: ``SPATIAL_JOINT_COLUMNS``, then
    ``SLICE_COLUMNS`` of slice 0, 1, ... as ``"normal_force[3]"``, then those of the
    ``faces`` end faces (0 or 2; face 0 at z = -L/2) as ``"normal_force[face0]"``, then,
    where the joint is ``lubricated``, each slice's :data:`FILM_DATA_COLUMNS` (``"film_fx[3]"``)."""
    return (SPATIAL_JOINT_COLUMNS + tuple(f"{c}[{k}]" for k in range(slices) for c in SLICE_COLUMNS)
            + tuple(f"{c}[face{k}]" for k in range(faces) for c in SLICE_COLUMNS)
            + (tuple(f"{c}[{k}]" for k in range(slices) for c in FILM_DATA_COLUMNS) if lubricated else ()))


#: Stiffness codes the compiled kernel evaluates (exuclear/_kernel/laws.hpp ``elastic_force``).
KERNEL_STIFFNESS_CODES = frozenset(range(7))


def law_code(law: ContactLaw) -> tuple[int, tuple[float, ...]]:
    """The kernel's stiffness code and constants of a contact law; ``ValueError`` for a
    stiffness model the compiled kernel does not know (a law written in Python)."""
    code = int(getattr(law, "kernel_code", -1))
    if code not in KERNEL_STIFFNESS_CODES:
        raise ValueError(f"the stiffness model of law {law.name!r} has no compiled form; use backend='python'")
    return code, tuple(float(v) for v in law.kernel_parameters())


def friction_code(friction: FrictionLaw) -> tuple[int, tuple[float, ...]]:
    """The kernel's friction code and constants; ``ValueError`` for a law it does not know."""
    kind = type(friction)
    if kind is NoFriction:
        return 0, ()
    if kind is Coulomb:
        return 1, (friction.mu, friction.v_eps)
    if kind is ModifiedCoulomb:
        return 2, (friction.mu_s, friction.mu_d, friction.v_s, friction.v_d)
    raise ValueError(f"friction law {kind.__name__} has no compiled form; use backend='python'")


class RunStart(NamedTuple):
    """What a joint's kernel asks its handle once per run start (the handle's run-start
    callback returns it; ``start_run`` of both kernels reads it by field name): the first
    fields of :data:`STEP_CONTROL`, whose defaults and meanings are there."""

    can_shorten: bool
    min_step: float
    label: str
    rate: bool
    group_size: int
    rate_scale: float
    growth_cap: float
    contact_cap: float
    jacobian_step: float
    separation_step: float
    impact_mass: float
    refusal: str
    end_time: float


class ControlField(NamedTuple):
    """One field of a joint's step control through a run: its name, its value at a run's start
    (before the run-start record) and what it holds."""

    name: str
    default: Any
    meaning: str


_INF, _NAN = float("inf"), float("nan")


def _told(count: str, first: str, what: str) -> tuple[ControlField, ...]:
    """A kind of step the joint accepted although a rule asked for a shorter one (the handle's
    notes): how many, and the end and length of the first of them (``first_time``, ``first_step``)."""
    return (ControlField(count, 0, what), ControlField(f"{first}_time", 0.0, "the end [s] of the first of them"),
            ControlField(f"{first}_step", 0.0, "its length [s]"))


#: What the joint's own step control holds through a run, field by field: both kernels'
#: ``StepControl`` (the Python kernel's is made from this table; the compiled kernel's
#: ``RUN_START_FIELDS`` and ``STEP_COUNT_FIELDS`` in ``joint_state.hpp``, exported as
#: ``exuclear._ckernel.STEP_CONTROL_FIELDS``, which a test keeps equal to this one).  The
#: first fields are :class:`RunStart`'s, set at each run's start; the rest are what the run did,
#: which the handle reads after it.
STEP_CONTROL = (
    ControlField("can_shorten", True, "the solver redoes a rejected step shorter"),
    ControlField("min_step", 0.0, "the solver's minimum step [s]"),
    ControlField("label", "", "the joint's name, for messages"),
    ControlField("rate", True, "the joint's rate criterion applies (False: an explicit solver's error control sets "
                               "the step)"),
    ControlField("group_size", 1, "the clearance joints of the joint's system (the kernel's step group)"),
    ControlField("rate_scale", 1.0, "the factor on rate_limit for this run (below 1 in a convergence check's "
                                    "tighter run)"),
    ControlField("growth_cap", _INF, "the longest step free flight may grow to [s] (steering.GROWTH_CONTACT_PERIODS)"),
    ControlField("contact_cap", _INF, "the longest step a contact held through it may take [s] "
                                      "(steering.HELD_CONTACT_PERIODS; inf: none)"),
    ControlField("jacobian_step", _INF, "the step above which the joint asks for a Jacobian per step [s] "
                                        "(steering.steer_newton; inf: never)"),
    ControlField("separation_step", _INF, "a contact that ends in a longer step is not resolved [s] (inf: not counted)"),
    ControlField("impact_mass", _NAN, "the effective mass of the joint's impacts [kg] (nan: unknown)"),
    ControlField("refusal", "", "why the run cannot start, e.g. a journal outside its bearing (engine.placement; "
                                "'': it can)"),
    ControlField("end_time", _INF, "the run's end time [s]: the accepted step that reaches it tells the handle, "
                                   "which then warns of the whole run (inf: unknown)"),
    # what the run did
    ControlField("runs", 0, "runs started since the joint was created"),
    ControlField("jacobian_on", False, "whether the joint asks for a Jacobian per step now"),
    ControlField("separations", 0, "contacts that ended in the run"),
    ControlField("long_separations", 0, "... in a step longer than separation_step: maybe numerical chatter"),
    ControlField("last_ended", 0, "contacts the last accepted step ended (taken back if it is redone)"),
    ControlField("last_long", 0, "... of them in a step longer than separation_step"),
    ControlField("rejected", 0, "steps the joint rejected and had redone shorter"),
    *_told("unresolved", "unresolved", "contact steps accepted although the rate criterion asked for a shorter one"),
    ControlField("unresolved_advice", _INF, "the smallest step [s] the rate criterion asked for in them"),
    *_told("held_long", "held", "steps accepted through a held contact although longer than contact_cap"),
    *_told("over_limit", "over", "steps accepted with a penetration beyond the joint's limit"),
    ControlField("deepest", 0.0, "the deepest penetration [m] beyond the limit"),
    # the step control's own memory
    ControlField("last_time", -_INF, "the end [s] of the last rejected step (to see it come back unshortened)"),
    ControlField("last_step", 0.0, "its length [s]"),
    ControlField("retry_start", -_INF, "the start [s] of the step out of contact that began the contact the penetration retries are about"),
    ControlField("retries", 0, "the penetration retries of that step so far"),
    ControlField("finished", False, "whether the step that reaches end_time has told the handle"),
)

#: What a kernel assumes where its handle gives no run-start record (a kernel used without a handle).
RUN_START_DEFAULT = RunStart(*(f.default for f in STEP_CONTROL[:len(RunStart._fields)]))


#: Film model name -> code in the parameter matrix (0: no film; exuclear/_kernel/layout.hpp ``FilmCode``).
FILM_CODES = {"short": 1, "long": 2, "finite": 3}

#: The surfaces that wear -> code in :func:`wear_code` (0: no wear; layout.hpp ``WearSurface``).
WEAR_SURFACE_CODES = {"bearing": 1, "journal": 2, "both": 3}
#: The pressure over the contact arc -> code in :func:`wear_code` (layout.hpp ``WearPressure``).
WEAR_PRESSURE_CODES = {"winkler": 0, "hertz": 1}


def wear_code(wear: Wear) -> float:
    """The wear's surface, pressure and nodes in the one entry ``wear_code`` of the matrix:
    ``surface + 4 pressure + 8 nodes`` (a whole number, exact in a double; the matrix has
    no three free entries for them).  ``decode`` of layout.hpp takes it apart."""
    return float(WEAR_SURFACE_CODES[wear.surface] + 4 * WEAR_PRESSURE_CODES[wear.pressure] + 8 * wear.nodes)


def data_columns(lubricated: bool) -> tuple[str, ...]:
    """A planar joint's data-node entries: :data:`DATA_COLUMNS`, and
    :data:`FILM_DATA_COLUMNS` where the joint is lubricated."""
    return DATA_COLUMNS + FILM_DATA_COLUMNS if lubricated else DATA_COLUMNS


def uses_bearing_motion(joint: ClearanceJoint, slices: int = 0) -> bool:
    """Whether the joint's loads depend on the bearing's own spin beyond the relative motion
    the connector sees (docs/physics.md section 4.1): friction (the slip of eq. (8) and the
    bearing's moment ``-R_B F_T``), a film (the spins of eqs. (55)-(56), the film's moments)
    or slices (the frame's rotation in the penetration rate, eq. (38)).  A planar, dry,
    frictionless joint needs it nowhere: its penetration rate is the relative velocity along
    ``n`` in any frame (eq. (7)) and its normal force passes through both centres, so its
    probe and torque connectors are switched off (they would only cost Jacobian columns);
    its recorded ``slip_velocity`` then leaves out the bearing's term ``omega_B (R_B - R_J)``.
    A spherical joint's ball (docs/physics.md section 13) likewise needs it for friction only:
    its normal rate has no spin in it and its normal force passes through both centres.
    A translational joint's corners need it always: the guide's spin moves its walls under
    the slider (:func:`exuclear.prismatic.corner_kinematics`).  A pin in a slot needs it
    where the slot has a length: its spin moves the segment's point under the pin
    (:mod:`exuclear.slot`)."""
    return (slices > 0 or joint.geometry.joint_type == "prismatic" or getattr(joint.geometry, "slot_length", 0.0) > 0.0
            or joint.film is not None or type(joint.friction) is not NoFriction)


def length_field(geometry: ContactGeometry) -> float:
    """The parameter matrix's ``length``: the revolute joint's bearing length, a translational
    joint's slider length, a pin-in-slot joint's slot length (its pin's length enters only
    its law's constants), 0 for the spherical joint."""
    if geometry.joint_type == "prismatic":
        return geometry.slider_length
    if geometry.joint_type == "pin-slot":
        return geometry.slot_length
    return geometry.length or 0.0


def second_parameters(joint: ClearanceJoint, token: float) -> list[list[float]]:
    """The ``damping`` matrix of the joint's connector (:data:`SECOND_LAYOUT`): the handle's
    ``token``, and a translational joint's guide length and box width."""
    d = np.zeros((MATRIX_SIZE, MATRIX_SIZE))
    write(d, "token", token, SECOND_FIELDS)
    g = joint.geometry
    if g.joint_type == "prismatic":
        write(d, "guide_length", g.guide_length or 0.0, SECOND_FIELDS)
        write(d, "slider_half_width", g.half_width, SECOND_FIELDS)
        write(d, "channel_half_width", g.channel_half_width, SECOND_FIELDS)
    return d.tolist()


def parameters(joint: ClearanceJoint, joint_id: int, role: int, max_penetration: float,
               impact_step: float = 0.0, rate_limit: float = RATE_LIMIT_DEFAULT, compiled: bool = True, slices: int = 0,
               axis_journal: tuple[float, float, float] = (0.0, 0.0, 1.0),
               shoulders: ShoulderGeometry | None = None) -> list[list[float]]:
    """The ``stiffness`` matrix that carries ``joint`` to the kernels (:data:`LAYOUT`);
    ``compiled=False`` (the Python kernel) accepts laws without a compiled form; ``slices``
    > 0 makes it a spatial joint whose journal axis is ``axis_journal`` in the journal
    marker's frame, with the axial clearance ``shoulders`` (or None)."""
    law, g = joint.law, joint.geometry
    code, extra = law_code(law) if compiled else (-1, ())
    f_code, f_params = friction_code(joint.friction) if compiled else (-1, ())
    p = np.zeros((MATRIX_SIZE, MATRIX_SIZE))
    values = {"joint_id": joint_id, "role": role, "joint_type": JOINT_TYPE_CODES[g.joint_type],
              "inner_radius": g.inner_radius, "outer_radius": g.outer_radius, "max_penetration": max_penetration,
              "impact_step": impact_step,
              "rate_limit": rate_limit,
              "stiffness_code": code, "damping_factor": law.damping_factor, "v_min": law.v_min,
              "friction_code": f_code, "stiffness_constants": extra, "friction_constants": f_params,
              "slices": slices, "length": length_field(g), "axis_journal": axis_journal,
              "bearing_motion": float(uses_bearing_motion(joint, slices))}
    if joint.film is not None:
        values.update(film_model=FILM_CODES[joint.film.name], viscosity=joint.film.viscosity,
                      eps_film=joint.film.eps_film, eps_cap=joint.film.eps_cap)
    if joint.wear is not None:  # the planar joint's wear, or a spatial joint's per slice (section 11.7)
        values.update(wear_code=wear_code(joint.wear), wear_coefficient=joint.wear.coefficient)
    if shoulders is not None:
        values.update(axial_clearance=shoulders.axial_clearance, friction_radius=shoulders.friction_radius,
                      face_stiffness=shoulders.face_stiffness(law.E_star))
    try:
        for name, value in values.items():
            write(p, name, value)
    except ValueError:
        raise ValueError("a law has more constants than the kernel's parameter layout holds") from None
    return p.tolist()
