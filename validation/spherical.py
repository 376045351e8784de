"""The spherical clearance joint (a ball in a socket) against analytic results, the ideal
joint, Exudyn's own hollow-sphere contact and two of Exudyn's examples (issue 49).

Source problems: a free steel ball (R_B = 9.9 mm) in a steel socket (R_S = 10 mm, c = 0.1 mm)
fixed to the ground (docs/physics.md section 13):

- resting under gravity: its sink against Hertz's static ``(m g / K)^(2/3)``, ``K`` of eq. (13)
  with the ball's and the socket's radii;
- an oblique impact (the ball started off the socket's centre at 0.5 c, flying at 0.5 m/s so
  that it meets the wall 30 degrees off the normal), frictionless: the restitution along the
  normal against each damping law's own (:func:`exuclear.contact.restitution.restitution_of_damping`,
  exact for a free mass), and the change of velocity across the normal (none) and of the
  spin (none);
- the same impact with Coulomb friction (mu = 0.05, sliding throughout): the tangential
  velocity and the spin after it against the impulse balance ``m dv_t = -mu P_n s``,
  ``J dw = R_B n x (-mu P_n s)`` with the normal impulse ``P_n`` the run gives;
- a spherical pendulum (a steel bar hanging from the ball joint, swinging in 3D) against the
  same pendulum on the ideal ``mbs.CreateSphericalJoint``, as the clearance goes to 0;
- Exudyn's ``ObjectContactSphereSphere(isHollowSphere1=True)`` on the oblique impact with the
  same law (Hertz, Carvalho-Martins damping; Exudyn's impactModel 2) under DOPRI5 and
  generalized-alpha;
- the zoo's spherical-joint models (``validation/exudyn_examples``: ``spherical_joint_chain``,
  ``generic_joint_chain``) with their own settings through a plain ``mbs.SolveDynamic``:
  right or told, and their cost against the ideal model (a timing: run nothing else meanwhile).

    python -m validation.spherical [--no-zoo]
"""
from __future__ import annotations

import argparse
import math
import warnings
from dataclasses import dataclass

import exudyn as exu
import exudyn.utilities as eu
import numpy as np
from exudyn.itemInterface import MarkerBodyRigid, NodeGenericData, ObjectContactSphereSphere

import exuclear
from exuclear.contact import DAMPING_MODELS
from exuclear.contact.restitution import restitution_of_damping
from exuclear.joint import make_spherical_joint
from validation._tables import markdown_table

BALL_RADIUS, SOCKET_RADIUS = 9.9e-3, 10e-3  # [m]
CLEARANCE = SOCKET_RADIUS - BALL_RADIUS
DENSITY, GRAVITY = 7850.0, 9.81  # steel [kg/m^3], [m/s^2]
MASS = DENSITY * 4.0 / 3.0 * math.pi * BALL_RADIUS**3
#: The oblique impact: start 0.5 c off the centre along z, fly along -y at this speed [m/s];
#: the ball meets the wall where sin(angle to the normal) = 0.5, 30 degrees off it.
IMPACT_SPEED, IMPACT_OFFSET = 0.5, 0.5
#: Restitution the impacts ask of each damping law (within every law's range).
IMPACT_CR = 0.8
#: Coulomb's coefficient of the friction impact: 3.5 mu (1 + e) v_n < v_t, so that the ball
#: slides throughout (a solid ball's slip changes by -3.5 mu P_n / m, docs/physics.md section 13.4).
IMPACT_MU = 0.05
#: The impact's integration: DOPRI5, tight tolerances and a largest step far below the
#: contact time (~35 us): the restitution it measures is the law's, not the integrator's.
IMPACT_SETTINGS = exuclear.SolverSettings(end_time=3.5e-4, method="dopri5", step=1e-6, rtol=1e-10, atol=1e-14,
                                          output_step=1e-7)
#: The pendulum: a steel bar (length, width [m]) hanging from the joint, spun about x and z.
BAR_LENGTH, BAR_WIDTH, BAR_SPIN = 0.3, 0.02, (5.0, 0.0, 3.0)
PENDULUM_TIME = 0.3  # [s]
#: The clearances of the pendulum's convergence [m].
PENDULUM_CLEARANCES = (1e-4, 1e-5, 1e-6)
#: The zoo's models with a spherical clearance joint (validation/exudyn_examples).
ZOO_MODELS = ("spherical_joint_chain", "generic_joint_chain")


def socket_scene(p0, v0, w0=(0.0, 0.0, 0.0), gravity=(0.0, 0.0, 0.0), backend=None,
                 node_type=exu.NodeType.RotationRotationVector, **joint_options):
    """A free ball in a socket on the ground: (system, ball body, joint handle), not assembled;
    the ball's rotation node ``node_type`` (a Lie-group node by default: explicit solvers run)."""
    mbs = exu.SystemContainer().AddSystem()
    ground = mbs.CreateGround()
    ball = mbs.CreateRigidBody(inertia=eu.InertiaSphere(MASS, BALL_RADIUS), referencePosition=[0.0, 0.0, 0.0],
                               initialDisplacement=list(p0), initialVelocity=list(v0),
                               initialAngularVelocity=list(w0), gravity=list(gravity), nodeType=node_type)
    options = {"law": "hertz+lankarani-nikravesh", "cr": IMPACT_CR, **joint_options}
    joint = exuclear.CreateSphericalClearanceJoint(mbs, itemNumbers=[ground, ball], position=[0.0, 0.0, 0.0],
                                                   ball_radius=BALL_RADIUS, socket_radius=SOCKET_RADIUS,
                                                   backend=backend, **options)
    return mbs, ball, joint


def _velocities(mbs, ball):
    ov = exu.OutputVariableType
    return (np.asarray(mbs.GetObjectOutputBody(ball, ov.Velocity, [0, 0, 0])),
            np.asarray(mbs.GetObjectOutputBody(ball, ov.AngularVelocity, [0, 0, 0])))


# -- resting sink ------------------------------------------------------------------------------
def resting_sink(backend=None, end_time=0.02):
    """(sink [m], Hertz's static sink [m]) of the ball resting in its socket under gravity."""
    mbs, ball, joint = socket_scene((0.0, -CLEARANCE, 0.0), (0.0, 0.0, 0.0), gravity=(0.0, -GRAVITY, 0.0),
                                    backend=backend, cr=0.5)
    mbs.Assemble()
    _run(mbs, exuclear.SolverSettings(end_time=end_time, method="generalized-alpha", step="auto"))
    k = joint.joint.law.stiffness_model.k0                                              # eq. (13)
    return float(joint.state().delta), (MASS * GRAVITY / k) ** (2.0 / 3.0)


def _run(mbs, settings):
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", exuclear.AccuracyWarning)
        result = exuclear.simulate(mbs, settings)
    if not result.success:
        raise RuntimeError(result.message)
    return result


# -- the oblique impact ------------------------------------------------------------------------
@dataclass(frozen=True)
class Impact:
    """One oblique impact: the restitution along the normal at the deepest penetration, the
    change of velocity across it and of the spin (relative to the normal change), the
    tangential velocity and spin after it, and what the impulse balance predicts for them."""

    restitution: float
    across: float
    spin_change: float
    v_t_after: np.ndarray
    w_after: np.ndarray
    v_t_expected: np.ndarray
    w_expected: np.ndarray


def impact_start():
    """Start and velocity of the ball in the oblique impact."""
    return (0.0, 0.0, IMPACT_OFFSET * CLEARANCE), (0.0, -IMPACT_SPEED, 0.0)


def oblique_impact(damping="lankarani-nikravesh", mu=0.0, backend=None, cr=IMPACT_CR, node_type=None, settings=None):
    """The oblique impact under the law ``hertz+DAMPING`` (and Coulomb's ``mu``): :class:`Impact`;
    ``node_type`` and ``settings`` other than :func:`socket_scene`'s and :data:`IMPACT_SETTINGS`."""
    p0, v0 = impact_start()
    friction = f"coulomb:{mu}" if mu > 0.0 else "none"
    nodes = {} if node_type is None else {"node_type": node_type}
    mbs, ball, joint = socket_scene(p0, v0, backend=backend, law=f"hertz+{damping}", cr=cr, friction=friction, **nodes)
    mbs.Assemble()
    _run(mbs, IMPACT_SETTINGS if settings is None else settings)
    out = joint.outputs()
    k = int(np.argmax(out["penetration"]))
    n = np.array([out["ecc_x"][k], out["ecc_y"][k], out["ecc_z"][k]])
    n /= np.linalg.norm(n)
    v_in, w_in = np.array(v0), np.zeros(3)
    v_out, w_out = _velocities(mbs, ball)
    dv = v_out - v_in
    dv_n = dv @ n
    p_n = -MASS * dv_n  # the normal impulse the run gave (on the ball, along -n)
    v_t_in = v_in - (v_in @ n) * n
    s = v_t_in / np.linalg.norm(v_t_in)  # the slip's direction: the ball starts without spin
    inertia = 0.4 * MASS * BALL_RADIUS**2  # a solid ball
    return Impact(restitution=-(v_out @ n) / (v_in @ n), across=float(np.linalg.norm(dv - dv_n * n) / abs(dv_n)),
                  spin_change=float(np.linalg.norm(w_out - w_in) * BALL_RADIUS / abs(dv_n)),
                  v_t_after=v_out - (v_out @ n) * n, w_after=w_out,
                  v_t_expected=v_t_in - mu * p_n / MASS * s,
                  w_expected=np.cross(BALL_RADIUS * n, -mu * p_n * s) / inertia)


def law_restitution(damping, cr=IMPACT_CR):
    """The restitution the law ``hertz+DAMPING`` gives a free mass (its damping factor's)."""
    law = make_spherical_joint(ball_radius=BALL_RADIUS, socket_radius=SOCKET_RADIUS, law=f"hertz+{damping}",
                               cr=cr).law
    return restitution_of_damping(law.damping_factor)


# -- the spherical pendulum --------------------------------------------------------------------
def pendulum(clearance=None, end_time=PENDULUM_TIME):
    """The bar's free end over time (times, 3) [m]: on the ideal joint (``clearance`` None) or
    the clearance joint (the ball started against the socket's lower wall), generalized-alpha
    at exuclear's automatic steps."""
    mbs = exu.SystemContainer().AddSystem()
    ground = mbs.CreateGround()
    inertia = eu.InertiaCuboid(DENSITY, [BAR_WIDTH, BAR_LENGTH, BAR_WIDTH])
    centre = np.array([0.0, -0.5 * BAR_LENGTH, 0.0])
    spin = np.array(BAR_SPIN)
    bar = mbs.CreateRigidBody(inertia=inertia, referencePosition=list(centre), gravity=[0.0, -GRAVITY, 0.0],
                              initialDisplacement=[0.0, -(clearance or 0.0), 0.0],
                              initialVelocity=list(np.cross(spin, centre)), initialAngularVelocity=list(spin))
    if clearance is None:
        mbs.CreateSphericalJoint(itemNumbers=[ground, bar], position=[0.0, 0.0, 0.0])
    else:
        exuclear.CreateSphericalClearanceJoint(mbs, itemNumbers=[ground, bar], position=[0.0, 0.0, 0.0],
                                               ball_radius=SOCKET_RADIUS - clearance, socket_radius=SOCKET_RADIUS,
                                               law="hertz+lankarani-nikravesh", cr=0.9)
    tip = mbs.AddSensor(exu.itemInterface.SensorBody(bodyNumber=bar, localPosition=[0.0, -0.5 * BAR_LENGTH, 0.0],
                                                     storeInternal=True, writeToFile=False,
                                                     outputVariableType=exu.OutputVariableType.Position))
    mbs.Assemble()
    _run(mbs, exuclear.SolverSettings(end_time=end_time, method="generalized-alpha", step="auto",
                                      output_step=end_time / 300))
    return np.asarray(mbs.GetSensorStoredData(tip))


def pendulum_errors(clearances=PENDULUM_CLEARANCES, end_time=PENDULUM_TIME):
    """The largest distance [m] of the clearance pendulum's free end from the ideal one's, per clearance."""
    ideal = pendulum(None, end_time)
    errors = []
    for c in clearances:
        path = pendulum(c, end_time)
        ref = np.column_stack([np.interp(path[:, 0], ideal[:, 0], ideal[:, k]) for k in (1, 2, 3)])
        errors.append(float(np.max(np.linalg.norm(path[:, 1:4] - ref, axis=1))))
    return errors


# -- Exudyn's own hollow-sphere contact ------------------------------------------------------------
def peer_impact(solver):
    """The frictionless oblique impact on Exudyn's ``ObjectContactSphereSphere(isHollowSphere1=True)``
    with Hertz and Carvalho-Martins damping (its impactModel 2): (restitution along the normal
    or NaN, what stopped it or "")."""
    p0, v0 = impact_start()
    law = make_spherical_joint(ball_radius=BALL_RADIUS, socket_radius=SOCKET_RADIUS, law="hertz+carvalho-martins",
                               cr=IMPACT_CR).law
    mbs = exu.SystemContainer().AddSystem()
    ground = mbs.CreateGround()
    ball = mbs.CreateRigidBody(inertia=eu.InertiaSphere(MASS, BALL_RADIUS), referencePosition=list(p0),
                               initialVelocity=list(v0), nodeType=exu.NodeType.RotationRotationVector)
    gap = CLEARANCE - np.linalg.norm(p0)
    data = mbs.AddNode(NodeGenericData(initialCoordinates=[gap, 0.0, 0.0, 0.0], numberOfDataCoordinates=4))
    mbs.AddObject(ObjectContactSphereSphere(
        markerNumbers=[mbs.AddMarker(MarkerBodyRigid(bodyNumber=ball)), mbs.AddMarker(MarkerBodyRigid(bodyNumber=ground))],
        nodeNumber=data, spheresRadii=[BALL_RADIUS, SOCKET_RADIUS], isHollowSphere1=True,
        contactStiffness=law.stiffness_model.k0, contactStiffnessExponent=law.exponent,
        restitutionCoefficient=law.cr, impactModel=2, minimumImpactVelocity=law.v_min))
    mbs.Assemble()
    ss = exu.SimulationSettings()
    ss.timeIntegration.endTime = IMPACT_SETTINGS.end_time
    ss.timeIntegration.numberOfSteps = int(round(IMPACT_SETTINGS.end_time / IMPACT_SETTINGS.step))
    ss.timeIntegration.verboseMode = 0
    ss.solution.file.write = False
    ss.timeIntegration.absoluteTolerance, ss.timeIntegration.relativeTolerance = 1e-14, 1e-10
    ss.timeIntegration.discontinuous.useRecommendedStepSize = False  # validation/peer_contact.py says why
    try:
        ok = mbs.SolveDynamic(ss, solverType=solver)
    except Exception as err:  # Exudyn's own error types
        return math.nan, str(err).strip().splitlines()[-1][:120]
    if not ok or mbs.systemData.GetTime() < IMPACT_SETTINGS.end_time * (1.0 - 1e-9):
        return math.nan, f"stopped at t = {mbs.systemData.GetTime():.3g} s"
    v_out, _w = _velocities(mbs, ball)
    hit = np.array(p0) + np.array(v0) * (math.sqrt(CLEARANCE**2 - np.linalg.norm(p0) ** 2) / IMPACT_SPEED)
    n = hit / np.linalg.norm(hit)  # the normal where the free flight meets the wall
    return float(-(v_out @ n) / (np.array(v0) @ n)), ""


# -- the report -----------------------------------------------------------------------------------------
def checks(zoo=True):
    """The rows of the report: (check, measured, reference, verdict)."""
    rows = []
    sink, static = resting_sink()
    rows.append(("resting sink [m]", f"{sink:.5g}", f"(m g / K)^(2/3) = {static:.5g}", _rel(sink, static, 1e-3)))
    for damping in sorted(set(DAMPING_MODELS) - {"none"}):
        r = oblique_impact(damping)
        e = law_restitution(damping)
        rows.append((f"restitution along n, {damping}", f"{r.restitution:.5f}", f"{e:.5f}",
                     _rel(r.restitution, e, 1e-2)))
        rows.append((f"across n / along n, spin change, {damping}", f"{r.across:.2e}, {r.spin_change:.1e}", "0",
                     "ok" if r.across < 1e-2 and r.spin_change < 1e-12 else "off"))
    f = oblique_impact(mu=IMPACT_MU)
    rows.append((f"tangential velocity after [m/s], mu {IMPACT_MU}", _vec(f.v_t_after), _vec(f.v_t_expected),
                 _rel(np.linalg.norm(f.v_t_after - f.v_t_expected), np.linalg.norm(f.v_t_expected), 1e-2, diff=True)))
    rows.append((f"spin after [rad/s], mu {IMPACT_MU}", _vec(f.w_after), _vec(f.w_expected),
                 _rel(np.linalg.norm(f.w_after - f.w_expected), np.linalg.norm(f.w_expected), 2e-2, diff=True)))
    errors = pendulum_errors()
    for c, err in zip(PENDULUM_CLEARANCES, errors):
        rows.append((f"pendulum end vs ideal, c = {c:g} m", f"{err:.3g} m = {err / c:.3g} c", "-> 0 with c", ""))
    for name, solver in (("DOPRI5", exu.DynamicSolverType.DOPRI5),
                         ("generalized-alpha", exu.DynamicSolverType.GeneralizedAlpha)):
        e, why = peer_impact(solver)
        ours = oblique_impact("carvalho-martins").restitution
        rows.append((f"Exudyn ObjectContactSphereSphere, {name}", f"{e:.5f}" if not why else why,
                     f"exuclear {ours:.5f}, law {law_restitution('carvalho-martins'):.5f}",
                     _rel(e, ours, 1e-2) if not why else "stops"))
    if zoo:
        rows += zoo_rows()
    return rows


def zoo_rows():
    """The zoo's spherical-joint models with their own settings (plain mbs.SolveDynamic)."""
    from validation.exudyn_examples import load_models, run_model

    rows = []
    load_models()
    for name in ZOO_MODELS:
        run = run_model(name, quick=True, convergence=False)
        rows.append((f"zoo {name}, own settings", f"reached {run.get('own_reached')}, penetration "
                     f"{run.get('own_pen_c', math.nan):.3g} c; {run.get('own_warnings') or 'no notes'}",
                     f"cost / ideal {run.get('own_ratio', math.nan):.3g} (a timing)", run.get("verdict", "")))
    return rows


def _rel(value, reference, tol, diff=False):
    err = value / reference if diff else abs(value - reference) / abs(reference)
    return f"ok ({err:.1e})" if err <= tol else f"off ({err:.1e})"


def _vec(v):
    return "(" + ", ".join(f"{x:.4g}" for x in v) + ")"


def main(argv=None):
    ap = argparse.ArgumentParser(prog="python -m validation.spherical", description=__doc__.splitlines()[0])
    ap.add_argument("--no-zoo", action="store_true", help="leave out the zoo models (their timings)")
    args = ap.parse_args(argv)
    print(markdown_table(("check", "measured", "reference", "verdict"), checks(zoo=not args.no_zoo)))


if __name__ == "__main__":
    main()
