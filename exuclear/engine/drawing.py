"""How a clearance joint is drawn: journal and bearing by a graphics function, which only
Exudyn's renderer calls (``show=True``)."""
from __future__ import annotations

from typing import Any

import exudyn as exu
import numpy as np

from ..checks import check_positive

#: Colours of the drawing (RGBA).
JOURNAL_COLOR, BEARING_COLOR = [0.3, 0.3, 0.8, 1.0], [0.7, 0.7, 0.7, 1.0]
#: Outer radius of the drawn bearing ring, relative to the bearing radius.
BEARING_RING = 1.4


def drawing_function(handle: Any, configuration: Any = exu.ConfigurationType.Visualization) -> Any:
    """Graphics function of the joint ``handle``: the journal as a cylinder of radius R_J and
    the bearing as a ring from R_B, both of the bearing length, along the bearing axis, at
    the markers' current poses.  Exudyn calls it only to render."""
    # what it draws, read now: the function is kept by the system, and must not keep the
    # handle (which keeps the system: a cycle through Exudyn's C++ that is never freed)
    geometry, axis_local = handle.joint.geometry, handle._axis_local
    m_bearing, m_journal = handle.markerNumbers
    # CreateClearanceJoint's axisRadius, axisLength, color: the journal drawn at axisRadius,
    # the bearing to the same scale (the play stays in proportion), over axisLength
    sizes = getattr(handle, "_drawing", {})
    scale = sizes["radius"] / geometry.journal_radius if "radius" in sizes else 1.0
    length, journal_color = sizes.get("length", geometry.length), sizes.get("color", JOURNAL_COLOR)

    def draw(mbs: exu.MainSystem, item: int) -> list:
        rot = np.asarray(mbs.GetMarkerOutput(m_bearing, exu.OutputVariableType.RotationMatrix,
                                             configuration=configuration)).reshape(3, 3)
        axis = rot @ axis_local
        shift = 0.5 * length * axis
        out = []
        for marker, radius, inner, color in ((m_journal, scale * geometry.journal_radius, None, journal_color),
                                             (m_bearing, scale * BEARING_RING * geometry.bearing_radius,
                                              scale * geometry.bearing_radius, BEARING_COLOR)):
            centre = np.asarray(mbs.GetMarkerOutput(marker, exu.OutputVariableType.Position,
                                                    configuration=configuration))
            out.append(exu.graphics.Cylinder(pAxis=(centre - shift).tolist(), vAxis=(2.0 * shift).tolist(),
                                             radius=radius, radiusInner=inner, color=color))
        return out

    return draw


#: Colour of the drawn socket: see-through, so that the ball inside it shows.
SOCKET_COLOR = [0.7, 0.7, 0.7, 0.3]


def ball_drawing_function(handle: Any, configuration: Any = exu.ConfigurationType.Visualization) -> Any:
    """Graphics function of the spherical joint ``handle``: the ball as a sphere of radius R_B
    and the socket as a see-through sphere of radius R_S, at the markers' current positions
    (``jointRadius`` scales both, ``color`` the ball's)."""
    geometry = handle.joint.geometry  # read now: the function must not keep the handle (see drawing_function)
    m_socket, m_ball = handle.markerNumbers
    sizes = getattr(handle, "_drawing", {})
    scale = sizes["radius"] / geometry.ball_radius if "radius" in sizes else 1.0
    ball_color = sizes.get("color", JOURNAL_COLOR)

    def draw(mbs: exu.MainSystem, item: int) -> list:
        out = []
        for marker, radius, color in ((m_ball, scale * geometry.ball_radius, ball_color),
                                      (m_socket, scale * geometry.socket_radius, SOCKET_COLOR)):
            centre = mbs.GetMarkerOutput(marker, exu.OutputVariableType.Position, configuration=configuration)
            out.append(exu.graphics.Sphere(point=list(centre), radius=radius, color=color, nTiles=16))
        return out

    return draw


#: Length of the drawn guide walls, relative to the slider's length; their thickness, to its height.
GUIDE_WALL_LENGTH, GUIDE_WALL_THICKNESS = 3.0, 0.1


def slider_drawing_function(handle: Any, configuration: Any = exu.ConfigurationType.Visualization) -> Any:
    """Graphics function of the translational joint ``handle``: the slider as a box of its
    length and height (and width; the planar slider as deep as high) at the slider marker's
    pose, and the guide's walls about the guide marker, two at ``+-(H/2 + c)`` (and the
    spatial joint's two at ``+-(B/2 + c_z)``), ``guide_length`` long (else
    :data:`GUIDE_WALL_LENGTH` slider lengths)."""
    geometry = handle.joint.geometry  # read now: the function must not keep the handle (see drawing_function)
    m_guide, m_slider = handle.markerNumbers
    length, height = geometry.slider_length, geometry.slider_height
    width = geometry.slider_width if geometry.spatial else height
    wall = GUIDE_WALL_THICKNESS * height
    span = geometry.guide_length or GUIDE_WALL_LENGTH * length
    offset = geometry.outer_radius + 0.5 * wall  # a wall's centre line from the guide's
    walls = [([0.0, side * offset, 0.0], [span, wall, width]) for side in (-1.0, 1.0)]
    if geometry.spatial:
        offset_z = geometry.channel_half_width + 0.5 * wall
        walls += [([0.0, 0.0, side * offset_z], [span, 2.0 * geometry.outer_radius, wall]) for side in (-1.0, 1.0)]

    def draw(mbs: exu.MainSystem, item: int) -> list:
        out = []
        for marker, boxes, color in ((m_slider, (([0.0, 0.0, 0.0], [length, height, width]),), JOURNAL_COLOR),
                                     (m_guide, walls, BEARING_COLOR)):
            centre = np.asarray(mbs.GetMarkerOutput(marker, exu.OutputVariableType.Position, configuration=configuration))
            rot = np.asarray(mbs.GetMarkerOutput(marker, exu.OutputVariableType.RotationMatrix,
                                                 configuration=configuration)).reshape(3, 3)
            for local, size in boxes:
                box = exu.graphics.Brick(centerPoint=local, size=size, color=color)
                out.append(exu.graphics.Move(box, centre.tolist(), rot.tolist()))
        return out

    return draw


def drawing_sizes(radius: Any, length: Any, color: Any, radius_name: str = "axisRadius") -> dict:
    """``axisRadius``, ``axisLength`` and ``color`` of :func:`~exuclear.engine.connector.CreateClearanceJoint`
    (``jointRadius`` and ``color`` of :func:`~exuclear.engine.spherical.CreateSphericalClearanceJoint`), checked."""
    out: dict[str, Any] = {}
    if radius is not None:
        out["radius"] = check_positive(radius_name, radius)
    if length is not None:
        out["length"] = check_positive("axisLength", length)
    if color is not None:
        try:
            rgba = [float(v) for v in color]
        except (TypeError, ValueError):
            rgba = []
        if len(rgba) != 4 or not all(0.0 <= v <= 1.0 for v in rgba):
            raise ValueError(f"`color` must be 4 numbers in [0, 1] (RGBA), got {color!r}")
        out["color"] = rgba
    return out
