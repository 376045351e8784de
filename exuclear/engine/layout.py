"""Where a clearance joint's parameters and outputs sit in its Exudyn items.

Parameters.  Exudyn hands a connector's ``stiffness`` matrix (6 x 6) to its user
functions on every call, so the joint's physics lives there, readable by the compiled
and the Python kernel alike (``mbs.GetObject(joint.objectNumber)["stiffness"]``):

====  ==========================================================================
row   entries
====  ==========================================================================
0     joint id (kernel table), role (0 joint, 1 bearing-spin probe, 2 bearing
      torque), R_J, R_B [m], penetration limit [m], impact step [s] (0: off)
1     stiffness code (``StiffnessModel.kernel_code``), 0, exponent n, damping factor D,
      v_min [m/s], c [m]
2     the stiffness model's constants (``kernel_parameters()``, up to 6)
3     friction code, then up to 4 friction constants
4     the handle's token (which handle owns the connector); the spatial joint's axial
      clearance (section 9.6): total play g [m] (0: none), shoulder radius R_S [m],
      friction radius R_e [m], face stiffness K_f [N/m]
5     spatial joint (docs/physics.md section 9): number of slices N (0: the planar
      joint), bearing length L [m], the journal axis in the journal marker's frame (3)
====  ==========================================================================

The codes are those of ``exuclear/_kernel/clearance_kernel.cpp``.

Outputs.  The joint's ``NodeGenericData`` holds, after every accepted step, the
quantities of :data:`DATA_COLUMNS` (SI units); a ``SensorNode`` on it with
``OutputVariableType.Coordinates`` records them.  A spatial joint's node holds
:func:`spatial_data_columns` instead: the journal's tilt and axial position, then the
planar columns (without the time) once per slice, then, with an axial clearance, once per
end face.
"""
from __future__ import annotations

import numpy as np

from ..contact import ContactLaw
from ..friction import Coulomb, FrictionLaw, ModifiedCoulomb, NoFriction
from ..joint import ClearanceJoint
from ..spatial import ShoulderGeometry

MAIN, PROBE, TORQUE = 0, 1, 2

#: The data node's entries, in order (the compiled kernel's ``write_data``).
DATA_COLUMNS = ("time", "penetration", "penetration_rate", "ecc_x", "ecc_y", "normal_force", "tangential_force",
                "slip_velocity", "v0", "in_contact", "onsets", "onset_time", "peak_force", "max_penetration")

#: The spatial joint's own entries, before the slices' (``spatial_data_values``).
SPATIAL_JOINT_COLUMNS = ("time", "tilt_x", "tilt_y", "axial_displacement")
#: Each slice's entries in the spatial data node, in order.
SLICE_COLUMNS = DATA_COLUMNS[1:]


def spatial_data_columns(slices: int, faces: int = 0) -> tuple[str, ...]:
    """Names of a spatial joint's data-node entries: ``SPATIAL_JOINT_COLUMNS``, then
    ``SLICE_COLUMNS`` of slice 0, 1, ... as ``"normal_force[3]"``, then those of the
    ``faces`` end faces (0 or 2; face 0 at z = -L/2) as ``"normal_force[face0]"``."""
    return (SPATIAL_JOINT_COLUMNS + tuple(f"{c}[{k}]" for k in range(slices) for c in SLICE_COLUMNS)
            + tuple(f"{c}[face{k}]" for k in range(faces) for c in SLICE_COLUMNS))




#: Stiffness codes the compiled kernel evaluates (clearance_kernel.cpp ``elastic_force``).
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


def parameters(joint: ClearanceJoint, joint_id: int, role: int, max_penetration: float,
               impact_step: float = 0.0, compiled: bool = True, slices: int = 0,
               axis_journal: tuple[float, float, float] = (0.0, 0.0, 1.0),
               shoulders: ShoulderGeometry | None = None) -> list[list[float]]:
    """The ``stiffness`` matrix that carries ``joint`` to the kernels (see the module docstring);
    ``compiled=False`` (the Python kernel) accepts laws without a compiled form; ``slices``
    > 0 makes it a spatial joint whose journal axis is ``axis_journal`` in the journal
    marker's frame, with the axial clearance ``shoulders`` (or None)."""
    law, g = joint.law, joint.geometry
    code, extra = law_code(law) if compiled else (-1, ())
    f_code, f_params = friction_code(joint.friction) if compiled else (-1, ())
    if len(extra) > 6 or len(f_params) > 4:
        raise ValueError("a law has more constants than the kernel's parameter layout holds")
    p = np.zeros((6, 6))
    p[0, :] = [joint_id, role, g.journal_radius, g.bearing_radius, max_penetration, impact_step]
    p[1, :] = [code, 0.0, law.exponent, law.damping_factor, law.v_min, g.clearance]
    p[2, :len(extra)] = extra
    p[3, 0] = f_code
    p[3, 1:1 + len(f_params)] = f_params
    if slices:
        p[5, :] = [slices, g.length, *axis_journal, 0.0]
    if shoulders is not None:
        p[4, 1:5] = [shoulders.axial_clearance, shoulders.shoulder_radius, shoulders.friction_radius,
                     shoulders.face_stiffness(law.E_star)]
    return p.tolist()
