"""A clearance joint's recorded outputs: columns from its data node's sensor
(:meth:`~exuclear.engine.handle.ClearanceJointHandle.outputs`)."""
from __future__ import annotations

from collections.abc import Sequence
from typing import Any

import numpy as np

from ..history import ContactState
from ._python_kernel import data_values, spatial_data_values
from .layout import DATA_COLUMNS, SLICE_COLUMNS, SPATIAL_JOINT_COLUMNS

#: Columns of :meth:`ClearanceJointHandle.outputs` after ``time`` (SI units).
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


def initial_data(slices: int, states: Sequence[ContactState], axis: Any, axial: float) -> list[float]:
    """The data node's entries at a run's initial state: the per-contact ``states`` and the
    journal's initial ``axis`` and ``axial`` displacement."""
    if not slices:
        return data_values(states[0])
    return spatial_data_values(states[0].time, axis, axial, states)


def assemble(data: np.ndarray, slices: int, faces: int, loads: Sequence[np.ndarray] = ()) -> dict[str, np.ndarray]:
    """The outputs from the sensor's rows ``data`` (sensor time, then the data node's entries):
    ``time`` and :data:`OUTPUT_COLUMNS` (planar joint, ``slices`` 0), or
    :data:`SPATIAL_OUTPUT_COLUMNS`, per-slice and per-face arrays and
    :data:`SPATIAL_JOINT_OUTPUTS` (``force`` and ``moment`` from the rows of the ``loads``
    sensors, ForceLocal and TorqueLocal, where they were recorded at the same times)."""
    if not slices:
        column = {c: data[:, k + 1] for k, c in enumerate(DATA_COLUMNS)}
        return {"time": data[:, 0], **{c: column[c] for c in OUTPUT_COLUMNS}}
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
        block = data[:, end:].reshape(data.shape[0], faces, n_slice)
        for c in OUTPUT_COLUMNS:
            out[FACE_OUTPUT_PREFIX + c] = block[:, :, SLICE_COLUMNS.index(c)]
    return out
