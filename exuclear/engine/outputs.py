"""A clearance joint's recorded outputs: columns from its data node's sensor
(:meth:`~exuclear.engine.handle.ClearanceJointHandle.outputs`)."""
from __future__ import annotations

from collections.abc import Sequence
from typing import Any

import numpy as np

from ..film import FilmLaw
from ..history import ContactState
from ._python_kernel import data_values, pair_data_values, spatial_data_values
from .layout import BALL_DATA_COLUMNS, FILM_DATA_COLUMNS, SLICE_COLUMNS, SPATIAL_JOINT_COLUMNS, data_columns

#: Columns of :meth:`ClearanceJointHandle.outputs` after ``time`` (SI units).  A planar joint
#: without friction or film runs without its bearing-spin probe (nothing in its loads needs
#: the spin, docs/physics.md section 4.1): its ``slip_velocity`` leaves out the bearing's term
#: ``(R_B - R_J) omega_B`` of eq. (8).
OUTPUT_COLUMNS = ("penetration", "penetration_rate", "ecc_x", "ecc_y", "normal_force", "tangential_force",
                  "slip_velocity", "v0", "in_contact")
#: A spatial joint's outputs: the journal's tilt (axis components x, y in the bearing's
#: joint frame) and axial displacement [m], then :data:`OUTPUT_COLUMNS` per slice
#: (arrays of shape (times, slices); ``slip_velocity`` is the slip speed, ``tangential_force``
#: the friction force's magnitude).
SPATIAL_OUTPUT_COLUMNS = ("tilt_x", "tilt_y", "axial_displacement")
#: A spatial joint's joint-level outputs besides those: ``ecc_mid_x``, ``ecc_mid_y`` the
#: journal centre's eccentricity in the bearing's mid-plane [m] (the mean of the slices':
#: the journal axis is straight and the slice planes symmetric about the mid-plane), and
#: ``force``, ``moment`` (shape (times, 3)) the resultant load of all slices and end
#: faces as the connector applies it (its ``ForceLocal`` and ``TorqueLocal``: on the
#: bearing, in the joint frame, :attr:`ClearanceJointHandle.frame`) [N, N m].
SPATIAL_JOINT_OUTPUTS = ("ecc_mid_x", "ecc_mid_y", "force", "moment")
#: With an axial clearance (docs/physics.md section 9.6), the end faces' outputs: ``"face_"``
#: and each of :data:`OUTPUT_COLUMNS`, arrays of shape (times, 2), face 0 at z = -L/2
#: (``slip_velocity`` the signed circumferential slip at the friction radius,
#: ``tangential_force`` the signed friction force there).
FACE_OUTPUT_PREFIX = "face_"
#: A lubricated joint's outputs beyond :data:`OUTPUT_COLUMNS` (docs/physics.md section 10):
#: the film force on the journal ``film_fx``, ``film_fy`` [N] (bearing's joint frame) and its
#: magnitude ``film_force``, the journal's viscous moment ``film_torque`` [N m], the
#: eccentricity ratio ``eccentricity_ratio`` = |e| / c, the attitude angle ``attitude_angle``
#: [rad] between the load the film carries (``-F``) and ``e``, the minimum film thickness
#: ``min_film_thickness`` = c (1 - eps) [m] (negative in metal contact), and the regime
#: ``regime``: 0 the film alone (eps <= eps_film), 1 the film near the wall (its blended
#: eccentricity, eq. (70)), 2 metal contact (penetration > 0, the dry law and the film).
FILM_OUTPUT_COLUMNS = ("film_fx", "film_fy", "film_force", "film_torque", "eccentricity_ratio", "attitude_angle",
                       "min_film_thickness", "regime")
#: The spherical joint's outputs: :data:`OUTPUT_COLUMNS` of its ball (``slip_velocity`` the
#: slip speed, ``tangential_force`` the friction force's magnitude), the ball's ``ecc_z``
#: [m], and ``force``, ``moment`` (shape (times, 3)), the connector's load on the socket in
#: the joint frame (its ``ForceLocal`` and ``TorqueLocal``) [N, N m].
BALL_OUTPUT_COLUMNS = (*OUTPUT_COLUMNS, "ecc_z", "force", "moment")
#: The translational joint's outputs: :data:`OUTPUT_COLUMNS`, each of shape (times, 8), one
#: column per corner-wall pair in :data:`exuclear.prismatic.PAIRS`' order (``ecc_x``,
#: ``ecc_y`` the corner in the guide's joint frame, ``slip_velocity`` its signed slip along
#: the wall), and ``force``, ``moment`` (shape (times, 3)), the connector's load on the guide.
#: The spatial joint's: (times, 32), :data:`exuclear.prismatic.BOX_PAIRS`' order (``ecc_y`` the
#: corner's coordinate across its wall, y or z; ``slip_velocity`` its slip speed over the wall).
PAIR_OUTPUT_COLUMNS = (*OUTPUT_COLUMNS, "force", "moment")
#: Codes of the ``regime`` output.
REGIME_FILM, REGIME_BLEND, REGIME_CONTACT = 0, 1, 2


def initial_data(slices: int, states: Sequence[ContactState], axis: Any, axial: float,
                 lubricated: bool = False, joint_type: str = "revolute") -> list[float]:
    """The data node's entries at a run's initial state: the per-contact ``states`` and the
    journal's initial ``axis`` and ``axial`` displacement (the ball's ``ecc_z``)."""
    if joint_type == "spherical":
        return [*data_values(states[0]), axial]
    if joint_type == "prismatic":
        return pair_data_values(states[0].time, states)
    if not slices:
        return data_values(states[0], lubricated)
    return spatial_data_values(states[0].time, axis, axial, states, slices if lubricated else 0)


def assemble(data: np.ndarray, slices: int, faces: int, film: FilmLaw | None = None,
             loads: Sequence[np.ndarray] = ()) -> dict[str, np.ndarray]:
    """The outputs from the sensor's rows ``data`` (sensor time, then the data node's entries):
    ``time`` and :data:`OUTPUT_COLUMNS` (planar joint, ``slices`` 0; with a ``film``, also
    :data:`FILM_OUTPUT_COLUMNS`), or :data:`SPATIAL_OUTPUT_COLUMNS`, per-slice and per-face
    arrays and :data:`SPATIAL_JOINT_OUTPUTS` (``force`` and ``moment`` from the rows of the
    ``loads`` sensors, ForceLocal and TorqueLocal, where they were recorded at the same
    times; with a ``film``, :data:`FILM_OUTPUT_COLUMNS` per slice: the slice's share of the
    film force and moment)."""
    if not slices:
        column = {c: data[:, k + 1] for k, c in enumerate(data_columns(film is not None))}
        out = {"time": data[:, 0], **{c: column[c] for c in OUTPUT_COLUMNS}}
        if film is not None:
            out.update(film_outputs(column, film))
        return out
    n_joint, n_slice = len(SPATIAL_JOINT_COLUMNS), len(SLICE_COLUMNS)
    # after the sensor's time: the data node's own time, then SPATIAL_OUTPUT_COLUMNS
    out = {"time": data[:, 0], **{c: data[:, 2 + k] for k, c in enumerate(SPATIAL_OUTPUT_COLUMNS)}}
    end = 1 + n_joint + slices * n_slice
    block = data[:, 1 + n_joint:end].reshape(data.shape[0], slices, n_slice)
    for c in OUTPUT_COLUMNS:
        out[c] = block[:, :, SLICE_COLUMNS.index(c)]
    out["ecc_mid_x"], out["ecc_mid_y"] = out["ecc_x"].mean(axis=1), out["ecc_y"].mean(axis=1)
    for name, rows in zip(("force", "moment"), loads):
        if rows.ndim == 2 and rows.shape[0] == data.shape[0] and np.array_equal(rows[:, 0], data[:, 0]):
            out[name] = rows[:, 1:4]
    if faces:
        block = data[:, end:end + faces * n_slice].reshape(data.shape[0], faces, n_slice)
        for c in OUTPUT_COLUMNS:
            out[FACE_OUTPUT_PREFIX + c] = block[:, :, SLICE_COLUMNS.index(c)]
    if film is not None:  # per slice: arrays of shape (times, slices)
        start = end + faces * n_slice
        block = data[:, start:start + slices * len(FILM_DATA_COLUMNS)].reshape(data.shape[0], slices,
                                                                                len(FILM_DATA_COLUMNS))
        column = {c: block[:, :, k] for k, c in enumerate(FILM_DATA_COLUMNS)}
        column.update({c: out[c] for c in ("ecc_x", "ecc_y", "penetration")})
        out.update(film_outputs(column, film))
    return out


def assemble_ball(data: np.ndarray, loads: Sequence[np.ndarray] = ()) -> dict[str, np.ndarray]:
    """The spherical joint's outputs (:data:`BALL_OUTPUT_COLUMNS`) from the sensor's rows
    ``data`` and those of its ``loads`` sensors (ForceLocal, TorqueLocal)."""
    column = {c: data[:, k + 1] for k, c in enumerate(BALL_DATA_COLUMNS)}
    out = {"time": data[:, 0], **{c: column[c] for c in (*OUTPUT_COLUMNS, "ecc_z")}}
    for name, rows in zip(("force", "moment"), loads):
        if rows.ndim == 2 and rows.shape[0] == data.shape[0] and np.array_equal(rows[:, 0], data[:, 0]):
            out[name] = rows[:, 1:4]
    return out


def assemble_pairs(data: np.ndarray, pairs: int, loads: Sequence[np.ndarray] = ()) -> dict[str, np.ndarray]:
    """The translational joint's outputs (:data:`PAIR_OUTPUT_COLUMNS`) from the sensor's rows
    ``data`` (sensor time, the data node's time, then ``pairs`` blocks of ``SLICE_COLUMNS``)
    and those of its ``loads`` sensors (ForceLocal, TorqueLocal)."""
    n_pair = len(SLICE_COLUMNS)
    block = data[:, 2:2 + pairs * n_pair].reshape(data.shape[0], pairs, n_pair)
    out = {"time": data[:, 0], **{c: block[:, :, SLICE_COLUMNS.index(c)] for c in OUTPUT_COLUMNS}}
    for name, rows in zip(("force", "moment"), loads):
        if rows.ndim == 2 and rows.shape[0] == data.shape[0] and np.array_equal(rows[:, 0], data[:, 0]):
            out[name] = rows[:, 1:4]
    return out


def film_outputs(column: dict[str, np.ndarray], film: FilmLaw) -> dict[str, np.ndarray]:
    """:data:`FILM_OUTPUT_COLUMNS` from the data node's columns (by name) of a lubricated joint."""
    ex, ey, fx, fy = column["ecc_x"], column["ecc_y"], column["film_fx"], column["film_fy"]
    c = film.geometry.clearance
    eps = np.hypot(ex, ey) / c                                                # eq. (55)
    regime = np.where(column["penetration"] > 0.0, REGIME_CONTACT,
                      np.where(eps > film.eps_film, REGIME_BLEND, REGIME_FILM)).astype(float)
    return {"film_fx": fx, "film_fy": fy, "film_force": np.hypot(fx, fy), "film_torque": column["film_torque"],
            "eccentricity_ratio": eps,
            "attitude_angle": np.arctan2(np.abs(ex * fy - ey * fx), -(ex * fx + ey * fy)),  # film.attitude_angle
            "min_film_thickness": c * (1.0 - eps), "regime": regime}
