"""The laws one contact evaluates: the normal force and friction of
:func:`exuclear.joint.contact_response` (:mod:`exuclear.contact`, eq. (9) and eqs.
(10)-(17); :mod:`exuclear.friction`, eqs. (20)-(23)), an end face's flat punch
(:func:`exuclear.spatial.face_normal_force`, eq. (52)) and the impact duration
(:func:`exuclear.timescales.impact_duration`).  The compiled kernel's ``laws.hpp``.

The contacts call :func:`contact_response` through this module (``laws.contact_response``),
the one place where the kernel evaluates a contact law."""
from __future__ import annotations

from ...joint import ContactResponse, contact_response
from ...spatial import face_normal_force
from ...timescales import impact_duration

__all__ = ["ContactResponse", "contact_response", "face_normal_force", "impact_duration"]


