"""Bad input, everywhere: what the API and the command lines answer to it.

Source: issue 6, part 3, and the input rules of ``shared/STYLE.md`` ("check inputs at
the public boundary and fail loudly: ValueError naming the argument and the rule";
command lines print one line ``error: ...`` and exit with status 2, no traceback; likely
unit mistakes warn).  Every input of :data:`BAD_INPUTS` is tried here, on the API in
this process and on the command lines through their ``main`` functions (as
``python -m ...`` would run them, an uncaught exception being a traceback), and the
replies are written as the table of ``docs/bad_input.md``::

    python -m validation.bad_input [--write docs/bad_input.md]

``tests/test_hard_cases.py`` tries every input again and checks that the table still
says what the library answers, and that every reply is the one the rules ask for
(rows marked as gaps are expected to fall short, strictly).
"""
from __future__ import annotations

import argparse
import contextlib
import importlib
import io
import math
import os
import shlex
import sys
import traceback
import warnings
from collections.abc import Sequence
from dataclasses import dataclass
from typing import NamedTuple

import exudyn as exu
import exudyn.utilities as eu
import numpy as np
from exudyn.itemInterface import (
    MarkerBodyPosition,
    MarkerBodyRigid,
    NodeGenericODE2,
    NodeRigidBody2D,
    ObjectBeamGeometricallyExact2D,
    ObjectGround,
    ObjectKinematicTree,
    ObjectRigidBody2D,
)

import exuclear
from exuclear.models.journal_bearing import JournalBearingParams
from exuclear.models.slider_crank import SliderCrankParams

DOC = os.path.join("docs", "bad_input.md")

#: The paper's journal and bearing (docs/physics.md section 6.1), as the API rows write them.
PAPER = {"journal_radius": 9.9e-3, "bearing_radius": 10e-3, "length": 15e-3}
#: A path whose parent is a regular file, so nothing can be written there on any machine.
UNWRITABLE = os.path.join(os.path.abspath(__file__), "out")


def system() -> tuple[exu.MainSystem, int, int]:
    """A fresh system with a ground and one rigid body: ``(mbs, body, ground)``."""
    mbs = exu.SystemContainer().AddSystem()
    ground = mbs.AddObject(ObjectGround())
    node = mbs.AddNode(NodeRigidBody2D(referenceCoordinates=[0.0, 0.0, 0.0]))
    body = mbs.AddObject(ObjectRigidBody2D(nodeNumber=node, mass=1.0, inertia=1e-3))
    return mbs, body, ground


def ball_system() -> exu.MainSystem:
    """A fresh system for a ball joint: the ground (object 0), a 3D rigid body (object 1) and
    a point mass (object 2)."""
    mbs = exu.SystemContainer().AddSystem()
    mbs.CreateGround()
    mbs.CreateRigidBody(inertia=eu.InertiaSphere(0.03, 9.9e-3), referencePosition=[0.0, 0.0, 0.0])
    mbs.CreateMassPoint(mass=0.03, referencePosition=[0.0, 0.0, 0.0])
    return mbs


def markers() -> tuple[exu.MainSystem, list]:
    """A fresh :func:`system` with a position (not rigid) marker on the ground and a rigid
    one on the body: ``(mbs, [position marker, rigid marker])``."""
    mbs, body, ground = system()
    return mbs, [mbs.AddMarker(MarkerBodyPosition(bodyNumber=ground)), mbs.AddMarker(MarkerBodyRigid(bodyNumber=body))]


def on_marker() -> dict:
    """A fresh :func:`system` as ``CreateClearanceJoint``'s arguments ``mbs`` and
    ``itemNumbers`` = [ground, a rigid marker on the body]."""
    mbs, body, ground = system()
    return {"mbs": mbs, "itemNumbers": [ground, mbs.AddMarker(MarkerBodyRigid(bodyNumber=body))]}


def beam() -> exu.MainSystem:
    """A fresh system: object 0 the ground, object 1 an ``ObjectBeamGeometricallyExact2D``."""
    mbs = exu.SystemContainer().AddSystem()
    mbs.AddObject(ObjectGround())
    nodes = [mbs.AddNode(NodeRigidBody2D(referenceCoordinates=[x, 0.0, 0.0])) for x in (0.0, 0.1)]
    mbs.AddObject(ObjectBeamGeometricallyExact2D(nodeNumbers=nodes, length=0.1, massPerLength=1.0,
                                                 crossSectionInertia=1e-6, bendingStiffness=1.0, axialStiffness=1e3,
                                                 shearStiffness=1e3))
    return mbs


def kinematic_tree() -> exu.MainSystem:
    """A fresh system: object 0 an ``ObjectKinematicTree`` of two revolute links."""
    mbs = exu.SystemContainer().AddSystem()
    node = mbs.AddNode(NodeGenericODE2(referenceCoordinates=[0.0, 0.0], initialCoordinates=[0.0, 0.0],
                                       initialCoordinates_t=[0.0, 0.0], numberOfODE2Coordinates=2))
    mbs.AddObject(ObjectKinematicTree(
        nodeNumber=node, linkParents=[-1, 0], jointTypes=[exu.JointType.RevoluteZ] * 2,
        jointTransformations=exu.Matrix3DList([np.eye(3)] * 2),
        jointOffsets=exu.Vector3DList([[0.0, 0.0, 0.0], [0.1, 0.0, 0.0]]),
        linkInertiasCOM=exu.Matrix3DList([np.eye(3) * 1e-3] * 2), linkCOMs=exu.Vector3DList([[0.0, 0.0, 0.0]] * 2),
        linkMasses=[1.0, 1.0]))
    return mbs


def build_journal(params: JournalBearingParams) -> object:
    """:func:`exuclear.models.journal_bearing.build`, imported late."""
    from exuclear.models.journal_bearing import build

    return build(params)


#: Names the API rows may use.
NAMESPACE = {"exuclear": exuclear, "PAPER": PAPER, "SliderCrankParams": SliderCrankParams,
             "JournalBearingParams": JournalBearingParams, "system": system, "markers": markers,
             "build_journal": build_journal, "on_marker": on_marker, "beam": beam, "kinematic_tree": kinematic_tree,
             "ball_system": ball_system,
             "nan": math.nan, "inf": math.inf}


@dataclass(frozen=True)
class BadInput:
    """One input tried.

    Attributes
    ----------
    surface : str
        ``"API"`` (``code`` is a Python expression over :data:`NAMESPACE`) or ``"CLI"``
        (``code`` is a command line ``python -m MODULE ARGS``).
    mistake : str
        The kind of mistake: wrong type, NaN or inf, missing value, unknown name,
        inconsistent input, likely unit mistake, unwritable output.
    code : str
        The input, as shown in the table.
    expect : str
        The reply the rules ask for: ``ValueError``, ``TypeError`` (Python's own check
        of a call's arguments), ``UnitWarning``, ``ValidityWarning`` (a law outside the
        range its source covers), ``accepted`` (valid input), ``exit 2``,
        ``exit 0 + warning`` or ``exit 2 + warning``.
    says : str
        Text the reply's message must contain (the name of the argument at fault), if any.
    gap : str
        Empty when the library answers as it should; else what it should do instead.
    """

    surface: str
    mistake: str
    code: str
    expect: str
    gap: str = ""
    says: str = ""

    def satisfied_by(self, reply: Reply) -> bool:
        """Whether ``reply`` is the one the rules ask for."""
        return reply.kind == self.expect and self.says in reply.message


class Reply(NamedTuple):
    """What an input got: its kind (as :attr:`BadInput.expect`) and the message text."""

    kind: str
    message: str


def settings_input(mistake: str, arguments: str, says: str = "") -> BadInput:
    """``exuclear.SolverSettings(end_time=0.1, <arguments>)``, which must raise ``ValueError``."""
    return BadInput("API", mistake, f"exuclear.SolverSettings(end_time=0.1, {arguments})", "ValueError", says=says)


_SC = "python -m exuclear.models.slider_crank"
_JB = "python -m exuclear.models.journal_bearing"

BAD_INPUTS: tuple[BadInput, ...] = (
    # -- API: wrong types
    BadInput("API", "wrong type", 'exuclear.make_joint(**PAPER, cr="0.9")', "ValueError"),
    BadInput("API", "wrong type", "exuclear.make_joint(**PAPER, cr=[0.9])", "ValueError"),
    BadInput("API", "wrong type", "exuclear.make_joint(**PAPER, cr=True)", "ValueError"),
    BadInput("API", "wrong type", "exuclear.make_joint(**PAPER, cr=0.9, friction=0.1)", "ValueError"),
    BadInput("API", "wrong type", 'exuclear.Material("207e9", 0.3)', "ValueError"),
    BadInput("API", "wrong type", 'exuclear.SolverSettings(end_time="0.1")', "ValueError"),
    BadInput("API", "wrong type", "exuclear.SolverSettings(end_time=0.1, method=5)", "ValueError"),
    BadInput("API", "wrong type", 'exuclear.SolverSettings(end_time=0.1, verbose="yes")', "ValueError"),
    BadInput("API", "wrong type", 'exuclear.SolverSettings(end_time=0.1, step="fast")', "ValueError", says="'auto'"),
    BadInput("API", "wrong type", 'exuclear.simulate("mbs", exuclear.SolverSettings(end_time=0.1))', "ValueError"),
    BadInput("API", "wrong type", 'exuclear.simulate(system()[0], {"end_time": 0.1})', "ValueError"),
    BadInput("API", "wrong type", 'SliderCrankParams.paper(crank_speed="500")', "ValueError"),
    BadInput("API", "wrong type", 'SliderCrankParams.paper(ideal="no")', "ValueError"),
    # -- API: NaN and inf
    BadInput("API", "NaN or inf", "exuclear.make_joint(journal_radius=9.9e-3, bearing_radius=10e-3, length=nan, "
                                  "cr=0.9)", "ValueError"),
    BadInput("API", "NaN or inf", "exuclear.Material(nan, 0.3)", "ValueError"),
    BadInput("API", "NaN or inf", "exuclear.SolverSettings(end_time=inf)", "ValueError"),
    BadInput("API", "NaN or inf", "SliderCrankParams.paper(gravity=nan)", "ValueError"),
    BadInput("API", "NaN or inf", "build_journal(JournalBearingParams.paper(mass=nan))", "ValueError"),
    # -- API: missing values
    BadInput("API", "missing value", "exuclear.make_joint(**PAPER)", "ValueError"),
    BadInput("API", "missing value", "exuclear.make_joint(bearing_radius=10e-3, length=15e-3, cr=0.9)", "TypeError"),
    BadInput("API", "missing value", "exuclear.SolverSettings()", "TypeError"),
    # -- API: unknown names
    BadInput("API", "unknown name", 'exuclear.make_joint(**PAPER, law="hertzian", cr=0.9)', "ValueError"),
    BadInput("API", "unknown name", 'exuclear.make_joint(**PAPER, cr=0.9, journal_material="brass")', "ValueError"),
    BadInput("API", "unknown name", 'exuclear.make_joint(**PAPER, cr=0.9, friction="viscous")', "ValueError"),
    BadInput("API", "unknown name", 'exuclear.SolverSettings(end_time=0.1, method="rk45")', "ValueError"),
    BadInput("API", "unknown name", 'SliderCrankParams.paper(formulation="tree")', "ValueError"),
    # -- API: the joint as an Exudyn item (CreateClearanceJoint / AddClearanceJoint)
    BadInput("API", "inconsistent input", "exuclear.CreateClearanceJoint(system()[0], itemNumbers=[0, 1], "
                                          "axis=[0, 0, 0], **PAPER, cr=0.9)", "ValueError", says="`axis`"),
    BadInput("API", "inconsistent input", "exuclear.CreateClearanceJoint(system()[0], itemNumbers=[0, 7], **PAPER, "
                                          "cr=0.9)", "ValueError", says="not an object"),
    BadInput("API", "inconsistent input", "exuclear.CreateClearanceJoint(system()[0], itemNumbers=[1, 1], **PAPER, "
                                          "cr=0.9)", "ValueError", says="same body"),
    BadInput("API", "inconsistent input", "exuclear.CreateClearanceJoint(system()[0], itemNumbers=[0, 1], "
                                          "position=[0, 0], **PAPER, cr=0.9)", "ValueError", says="`position`"),
    BadInput("API", "inconsistent input", "exuclear.AddClearanceJoint(*markers(), **PAPER, cr=0.9)", "ValueError",
             says="rigid markers"),
    BadInput("API", "unknown name", 'exuclear.CreateClearanceJoint(system()[0], itemNumbers=[0, 1], **PAPER, '
                                    'cr=0.9, bearingRotates="yes")', "ValueError", says="`bearingRotates`"),
    BadInput("API", "inconsistent input", "exuclear.CreateClearanceJoint(beam(), itemNumbers=[0, 1], **PAPER, cr=0.9)",
             "ValueError", says="MarkerNodeRigid"),
    BadInput("API", "inconsistent input", "exuclear.CreateClearanceJoint(kinematic_tree(), itemNumbers=[0, 0], "
                                          "**PAPER, cr=0.9)", "ValueError", says="MarkerKinematicTreeRigid"),
    BadInput("API", "inconsistent input", "exuclear.CreateClearanceJoint(**on_marker(), position=[0, 0, 0], **PAPER, "
                                          "cr=0.9)", "ValueError", says="`position`"),
    BadInput("API", "inconsistent input", "exuclear.CreateClearanceJoint(system()[0], itemNumbers=[0, 1], "
                                          "bodyNumbers=[0, 1], **PAPER, cr=0.9)", "ValueError", says="`itemNumbers`"),
    BadInput("API", "wrong type", "exuclear.CreateClearanceJoint(system()[0], itemNumbers=[0, 1], axisRadius=-0.1, "
                                  "**PAPER, cr=0.9)", "ValueError", says="`axisRadius`"),
    # -- API: inconsistent input
    BadInput("API", "inconsistent input", "exuclear.make_joint(journal_radius=10e-3, bearing_radius=10e-3, "
                                          "length=15e-3, cr=0.9)", "ValueError"),
    BadInput("API", "inconsistent input", 'exuclear.make_joint(**PAPER, law="hertz", cr=0.5)', "ValueError"),
    BadInput("API", "inconsistent input", 'exuclear.make_joint(**PAPER, law=exuclear.contact_law("wang-liu", '
                                          'exuclear.BearingGeometry(**PAPER), 2.27e11, 0.9), cr=0.5)', "ValueError",
             says="`cr`"),
    BadInput("API", "inconsistent input", "exuclear.friction.ModifiedCoulomb(mu_s=0.3, mu_d=0.25, v_s=1e-2, v_d=1e-4)",
             "ValueError"),
    BadInput("API", "inconsistent input", "exuclear.SolverSettings(end_time=0.1, step=1.0)", "ValueError"),
    BadInput("API", "inconsistent input", "exuclear.SolverSettings(end_time=0.1, step=1e-5, min_step=1e-4)",
             "ValueError", says="`min_step`"),
    BadInput("API", "inconsistent input", 'exuclear.simulate(system()[0], exuclear.SolverSettings(end_time=0.1, '
                                          'method="generalized-alpha", step="auto", impact_step=1e-3))', "ValueError",
             says="`impact_step`"),
    BadInput("API", "inconsistent input", 'exuclear.engine.simulation_settings(exuclear.SolverSettings(end_time=0.1, '
                                          'method="generalized-alpha", step="auto"))', "ValueError",
             says="chosen from the model"),
    # settings that belong to the other family of methods, or out of their range
    *(settings_input(mistake, arguments, says) for mistake, arguments, says in (
        ("inconsistent input", 'method="generalized-alpha", newton_contractivity=0.0', "`newton_contractivity`"),
        ("inconsistent input", 'method="dopri5", newton_contractivity=0.1', "`newton_contractivity`"),
        ("unknown name", 'method="generalized-alpha", linear_solver="lu"', "`linear_solver`"),
        ("inconsistent input", 'method="dopri5", spectral_radius=0.5', "`spectral_radius`"),
        ("inconsistent input", 'method="dopri5", impact_step=1e-6', ""),
        ("inconsistent input", 'method="dopri5", rate_limit=0.02', "`rate_limit`"),
        ("inconsistent input", 'method="generalized-alpha", rate_limit=-0.1', "`rate_limit`"))),
    BadInput("API", "inconsistent input", 'setattr(exuclear.CreateClearanceJoint(**on_marker(), **PAPER, cr=0.9), '
                                          '"rate_limit", -1)',
             "ValueError", says="`rate_limit`"),
    BadInput("API", "inconsistent input", "SliderCrankParams.paper(rod_length=0.04)", "ValueError"),
    BadInput("API", "inconsistent input", "SliderCrankParams.paper(clearance=0.02)", "ValueError", says="`clearance`"),
    BadInput("API", "inconsistent input", 'SliderCrankParams.paper(clearance_joints=("O", "A", "B"))', "accepted"),
    BadInput("API", "inconsistent input", 'SliderCrankParams.paper(clearance_joints=("B", "B"))', "ValueError",
             says="`clearance_joints`"),
    BadInput("API", "inconsistent input", "SliderCrankParams.paper(crank_speed=0.0)", "ValueError", says="`crank_speed`"),
    BadInput("API", "inconsistent input", "SliderCrankParams.paper(crank_speed=-52.36)", "accepted"),
    BadInput("API", "inconsistent input", "SliderCrankParams.paper(max_penetration=0.0)", "ValueError",
             says="`max_penetration`"),
    BadInput("API", "inconsistent input", "build_journal(JournalBearingParams.paper(start_gap=1e-3))", "ValueError"),
    # -- API: the lubricated joint (issue 23)
    BadInput("API", "wrong type", 'exuclear.make_joint(**PAPER, cr=0.9, lubrication="oil")', "ValueError",
             says="`lubrication`"),
    BadInput("API", "wrong type", 'exuclear.Lubrication(viscosity="0.05")', "ValueError", says="`viscosity`"),
    BadInput("API", "NaN or inf", "exuclear.Lubrication(viscosity=nan)", "ValueError", says="`viscosity`"),
    BadInput("API", "unknown name", 'exuclear.Lubrication(viscosity=0.05, model="petroff")', "ValueError",
             says="`model`"),
    BadInput("API", "inconsistent input", "exuclear.Lubrication(viscosity=0.05, eps_film=0.95, eps_cap=0.9)",
             "ValueError", says="`eps_cap`"),
    BadInput("API", "inconsistent input", 'exuclear.make_joint(journal_radius=9.9e-3, bearing_radius=10e-3, '
                                          'length=0.03, cr=0.9, lubrication=exuclear.Lubrication(0.05, "finite"))',
             "ValueError", says="B/D"),
    # -- API: the spherical joint (a ball in a socket)
    BadInput("API", "inconsistent input", "exuclear.CreateSphericalClearanceJoint(ball_system(), itemNumbers=[0, 1], "
                                          "ball_radius=10e-3, socket_radius=10e-3, cr=0.9)", "ValueError",
             says="`ball_radius` must be smaller than `socket_radius`"),
    BadInput("API", "missing value", "exuclear.CreateSphericalClearanceJoint(ball_system(), itemNumbers=[0, 1], "
                                     "socket_radius=10e-3, cr=0.9)", "ValueError", says="`ball_radius` is required"),
    BadInput("API", "unknown name", "exuclear.CreateSphericalClearanceJoint(ball_system(), itemNumbers=[0, 1], "
                                    'ball_radius=9.9e-3, socket_radius=10e-3, law="hertzian", cr=0.9)', "ValueError"),
    BadInput("API", "inconsistent input", "exuclear.CreateSphericalClearanceJoint(ball_system(), itemNumbers=[0, 1], "
                                          'ball_radius=9.9e-3, socket_radius=10e-3, law="wang-liu", cr=0.9)',
             "ValueError", says="spherical joint's contact is a point"),
    BadInput("API", "inconsistent input", "exuclear.CreateSphericalClearanceJoint(ball_system(), itemNumbers=[0, 2], "
                                          "ball_radius=9.9e-3, socket_radius=10e-3, cr=0.9)", "ValueError",
             says="`itemNumbers[1]`"),
    BadInput("API", "likely unit mistake", "exuclear.CreateSphericalClearanceJoint(ball_system(), itemNumbers=[0, 1], "
                                           "ball_radius=9.9, socket_radius=10, cr=0.9)", "UnitWarning"),
    # -- API: likely unit mistakes
    BadInput("API", "likely unit mistake", "exuclear.Lubrication(viscosity=50)", "UnitWarning"),
    BadInput("API", "likely unit mistake", "exuclear.Material(3e6, 0.4)", "UnitWarning"),
    BadInput("API", "likely unit mistake", "exuclear.BearingGeometry(5e-3, 10e-3, 15e-3)", "UnitWarning"),
    BadInput("API", "likely unit mistake", "SliderCrankParams.paper(crank_speed=2e4)", "UnitWarning"),
    BadInput("API", "likely unit mistake", "exuclear.BearingGeometry(9.9, 10.0, 15.0)", "UnitWarning"),
    BadInput("API", "likely unit mistake", "exuclear.BearingGeometry(9.9e-3, 10e-3, 15.0)", "UnitWarning"),
    # -- API: unusual values
    BadInput("API", "unusual value", 'exuclear.friction_law("coulomb:1.5")', "ValidityWarning", says="`mu`"),
    BadInput("API", "inconsistent input", 'exuclear.friction_law("coulomb:-0.1")', "ValueError", says="`mu`"),
    BadInput("API", "unusual value", "exuclear.friction.ModifiedCoulomb(mu_s=30, mu_d=25, v_s=1e-4, v_d=1e-2)",
             "ValidityWarning", says="`mu_s`"),
    # -- CLI: slider-crank
    BadInput("CLI", "wrong type", f"{_SC} --cr abc", "exit 2"),
    BadInput("CLI", "NaN or inf", f"{_SC} --cr nan", "exit 2"),
    BadInput("CLI", "NaN or inf", f"{_SC} --rpm inf", "exit 2"),
    BadInput("CLI", "missing value", f"{_SC} --cr", "exit 2"),
    BadInput("CLI", "unknown name", f"{_SC} --law foo", "exit 2"),
    BadInput("CLI", "unknown name", f"{_SC} --journal brass", "exit 2"),
    BadInput("CLI", "unknown name", f"{_SC} --friction viscous", "exit 2"),
    BadInput("CLI", "unknown name", f"{_SC} --method rk45", "exit 2"),
    BadInput("CLI", "unknown name", f"{_SC} --backend numba", "exit 2"),
    BadInput("CLI", "inconsistent input", f"{_SC} --clearance-joints XB", "exit 2"),
    BadInput("CLI", "inconsistent input", f"{_SC} --clearance-joints BB", "exit 2", says="each joint once"),
    BadInput("CLI", "inconsistent input", f"{_SC} --rpm 0", "exit 2", says="`rpm`"),
    BadInput("CLI", "inconsistent input", f"{_SC} --dt-out 0", "exit 2", says="`--dt-out`"),
    BadInput("CLI", "inconsistent input", f"{_SC} --max-penetration=-1e-6", "exit 2", says="`max_penetration`"),
    BadInput("CLI", "missing value", f'{_SC} --csv ""', "exit 2", says="`--csv`"),
    BadInput("CLI", "missing value", f'{_SC} --plot ""', "exit 2", says="`--plot`"),
    BadInput("CLI", "unknown name", f"{_SC} --no-such-option", "exit 2"),
    BadInput("CLI", "inconsistent input", f"{_SC} --formulation minimal --clearance-joints OAB", "exit 2"),
    BadInput("CLI", "inconsistent input", f"{_SC} --ideal --formulation minimal", "exit 2"),
    BadInput("CLI", "inconsistent input", f"{_SC} --formulation redundant --method dopri5", "exit 2", says="constraints"),
    BadInput("CLI", "inconsistent input", f"{_SC} --step 1", "exit 2"),
    BadInput("CLI", "inconsistent input", f"{_SC} --revolutions -1", "exit 2"),
    BadInput("CLI", "inconsistent input", f"{_SC} --gravity -9.81", "exit 2"),
    BadInput("CLI", "inconsistent input", f"{_SC} --clearance -1e-4", "exit 2",
             says="`clearance` must be positive, got -0.0001"),
    BadInput("CLI", "unusual value", f"{_SC} --friction coulomb:1.5 --revolutions 0.01", "exit 0 + warning",
             says="friction coefficient `mu` = 1.5"),
    BadInput("CLI", "likely unit mistake", f"{_SC} --rpm 2e5 --revolutions 0.001", "exit 0 + warning",
             says="above 1e5 rpm"),
    BadInput("CLI", "inconsistent input", f"{_SC} --viscosity=-1e-3", "exit 2", says="`viscosity` must be positive"),
    BadInput("CLI", "inconsistent input", f"{_SC} --film-model finite", "exit 2", says="needs a `viscosity`"),
    BadInput("CLI", "unknown name", f"{_SC} --viscosity 0.01 --film-model ocvirk", "exit 2"),
    BadInput("CLI", "likely unit mistake", f"{_SC} --viscosity 40 --revolutions 0.01", "exit 0 + warning",
             says="mPa s"),
    BadInput("CLI", "unwritable output", f"{_SC} --revolutions 0.01 --csv {UNWRITABLE}.csv", "exit 2"),
    BadInput("CLI", "unwritable output", f"{_SC} --revolutions 0.01 --plot {UNWRITABLE}", "exit 2"),
    # -- CLI: journal-bearing
    BadInput("CLI", "wrong type", f"{_JB} --mass 4e-2kg", "exit 2"),
    BadInput("CLI", "NaN or inf", f"{_JB} --length nan", "exit 2"),
    BadInput("CLI", "inconsistent input", f"{_JB} --mass 0", "exit 2"),
    BadInput("CLI", "inconsistent input", f"{_JB} --velocity 0", "exit 2"),
    BadInput("CLI", "inconsistent input", f"{_JB} --v-min 0", "exit 2"),
    BadInput("CLI", "inconsistent input", f"{_JB} --journal-radius 0.011", "exit 2"),
    BadInput("CLI", "inconsistent input", f"{_JB} --law hertz --cr 0.5", "exit 2"),
    BadInput("CLI", "inconsistent input", f"{_JB} --end-time 0", "exit 2", says="`end_time`"),
    BadInput("CLI", "inconsistent input", f"{_JB} --dt-out=-1e-6", "exit 2", says="`--dt-out`"),
    BadInput("CLI", "inconsistent input", f"{_JB} --viscosity 0", "exit 2", says="`viscosity` must be positive"),
    BadInput("CLI", "inconsistent input", f"{_JB} --viscosity 0.01 --plot out", "exit 2", says="`--plot`"),
    BadInput("CLI", "missing value", f'{_JB} --csv ""', "exit 2", says="`--csv`"),
    BadInput("CLI", "unknown name", f"{_JB} --bearing gold", "exit 2"),
    BadInput("CLI", "likely unit mistake", f"{_JB} --journal-radius 0.005", "exit 0 + warning"),
    BadInput("CLI", "likely unit mistake", f"{_JB} --journal-radius 9.9 --bearing-radius 10 --length 15",
             "exit 0 + warning"),
    BadInput("CLI", "unwritable output", f"{_JB} --plot {UNWRITABLE}", "exit 2"),
)


def _api(code: str) -> Reply:
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        try:
            eval(code, dict(NAMESPACE))  # the table's own expressions, written above
        except (ValueError, TypeError) as err:
            return Reply(type(err).__name__, str(err))
        except Exception as err:  # anything else is a gap of the library, shown as such
            return Reply(type(err).__name__, str(err))
    for category in (exuclear.UnitWarning, exuclear.ValidityWarning):
        said = [str(w.message) for w in caught if issubclass(w.category, category)]
        if said:
            return Reply(category.__name__, said[0])
    return Reply("accepted", "")


def _cli_lines(stderr: str) -> list[str]:
    """The lines a user reads: ``warning: ...``, ``error: ...`` and argparse's ``...: error: ...``."""
    return [line for line in stderr.splitlines() if line.startswith(("warning:", "error:")) or ": error:" in line]


def _cli(code: str) -> Reply:
    words = shlex.split(code)
    module = importlib.import_module(words[2])
    err, out = io.StringIO(), io.StringIO()
    with warnings.catch_warnings(), contextlib.redirect_stderr(err), contextlib.redirect_stdout(out):
        warnings.simplefilter("always")
        try:
            status = module.main(words[3:])
        except SystemExit as stop:  # argparse
            status = stop.code
        except Exception as crash:  # what `python -m` would print as a traceback
            last = traceback.format_exception_only(type(crash), crash)[-1].strip()
            return Reply("traceback", last)
    lines = _cli_lines(err.getvalue())
    warned = any(line.startswith("warning:") for line in lines)
    return Reply(f"exit {status}" + (" + warning" if warned else ""), " / ".join(lines))


def attempt(case: BadInput) -> Reply:
    """Try one input; the reply it gets."""
    return _api(case.code) if case.surface == "API" else _cli(case.code)


def _cell(text: str) -> str:
    return text.replace("|", "\\|").replace("\n", " ")


def _machine_free(text: str) -> str:
    """``text`` with this file's path (where :data:`UNWRITABLE` points) written ``<file>``."""
    return text.replace(os.path.dirname(UNWRITABLE), "<file>")


def table_row(case: BadInput, reply: Reply) -> str:
    """The Markdown line of one input."""
    if case.gap:
        status = f"**gap**: {case.gap}"
    else:
        status = "ok" if case.satisfied_by(reply) else f"**unexpected** (rule: {case.expect} {case.says})".strip()
    message = f"{reply.kind}: {reply.message}" if reply.message else reply.kind
    cells = (case.surface, case.mistake, f"`{_cell(_machine_free(case.code))}`", _cell(_machine_free(message)),
             _cell(status))
    return "| " + " | ".join(cells) + " |"


def document(replies: Sequence[tuple[BadInput, Reply]]) -> str:
    """The whole of ``docs/bad_input.md``."""
    gaps = sum(1 for case, _ in replies if case.gap)
    head = [
        "# Bad input: what each gets",
        "",
        "Every row was tried by `python -m validation.bad_input --write docs/bad_input.md`, which wrote this file;",
        "`tests/test_hard_cases.py` tries every row again and fails if a reply changes without this table.",
        "The rules (issue 6, STYLE.md): the API raises `ValueError` naming the argument and the rule (Python's",
        "own `TypeError` for a missing or unknown keyword); likely unit mistakes give an `exuclear.UnitWarning`,",
        "values a law's sources do not cover (a friction coefficient above 1) an `exuclear.ValidityWarning`;",
        "the command lines print one line `error: ...` (argparse's errors too, with a pointer to `--help`), exit",
        "with status 2 and show no traceback; warnings are one line `warning: ...`.",
        "",
        f"`PAPER` is `{PAPER}` (the paper's journal and bearing); `system()` is a fresh system with a ground and",
        "one rigid body, `(mbs, body, ground)`; `build_journal` is `exuclear.models.journal_bearing.build`.",
        "`<file>/out` is a path below a regular file (nothing can be written there). CLI replies list the",
        "warning and error lines of stderr.",
        "",
        f"{len(replies)} inputs, {gaps} of them gaps (a gap is a reply that falls short of the rule; its last column",
        "says what should happen, and where).",
        "",
        "| where | mistake | input | reply | status |",
        "|---|---|---|---|---|",
    ]
    return "\n".join(head + [table_row(c, r) for c, r in replies]) + "\n"


def _parser() -> argparse.ArgumentParser:
    ap = argparse.ArgumentParser(prog="python -m validation.bad_input", description=__doc__.split("\n")[0])
    ap.add_argument("--write", metavar="FILE", help=f"write the table to FILE (the repository's is {DOC})")
    return ap


def main(argv: list[str] | None = None) -> int:
    args = _parser().parse_args(argv)
    replies = [(case, attempt(case)) for case in BAD_INPUTS]
    text = document(replies)
    if args.write:
        with open(args.write, "w", encoding="utf-8") as f:
            f.write(text)
        print(f"wrote {args.write}")
    else:
        print(text)
    unexpected = [c for c, r in replies if c.satisfied_by(r) == bool(c.gap)]
    for case in unexpected:
        why = "as the rule asks, but the row is marked a gap" if case.gap else "not the one the rule asks"
        print(f"error: {case.code}: the reply is {why}", file=sys.stderr)
    return 1 if unexpected else 0


if __name__ == "__main__":
    sys.exit(main())
