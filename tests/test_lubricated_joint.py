"""The lubricated joint through the Exudyn element (issue 23; docs/physics.md section 10.6).

A journal spinning at constant speed in a fixed bearing under a constant load settles
where the film carries the load: at the published eccentricity and attitude angle
(Butenschoen's table for the finite model, Ocvirk's closed form for the short one).  Then
the two kernels on a lubricated impact, the frame of the film's velocity (a spinning
bearing), the outputs and the refusals.

The steady-load scene (:func:`steady_run`): journal radius 20 mm, clearance 40 um
(psi = 2e-3), eta = 0.05 Pa s, omega = 100 rad/s; the load from the reference's Sommerfeld
number.  **Mass and speed below oil whip**: a light journal at low eps whirls once omega is
above about twice its first critical speed, i.e. once the dimensionless mass
``M = m c omega^2 / F`` passes a threshold of order 1 at moderate eps (rigid-rotor
stability analyses; the exact value was not rechecked here); the mass here is set from
``M = 0.01`` for every case, two orders below, so the steady state is stable and reached
in a few revolutions (the film's relaxation time is of order 1/omega; the run checks that
eps no longer moves over its second half).  The journal's moment of
inertia is 100 kg m^2 so that the film's Couette moment (0.25 N m at B/D = 1) slows it by
less than 1e-5 relative over a run: the spin is constant to that.
"""
from __future__ import annotations

import math
from collections.abc import Callable

import exudyn as exu
import numpy as np
import pytest
from exudyn.itemInterface import (
    CoordinateConstraint,
    LoadForceVector,
    MarkerBodyPosition,
    MarkerNodeCoordinate,
    NodePointGround,
    NodeRigidBody2D,
    ObjectGround,
    ObjectRigidBody2D,
    SensorNode,
)

import exuclear
from exuclear.engine import kernel
from exuclear.engine.layout import DATA_COLUMNS, FILM_DATA_COLUMNS
from exuclear.engine.outputs import FILM_OUTPUT_COLUMNS, OUTPUT_COLUMNS, REGIME_CONTACT
from exuclear.film import Lubrication, attitude_angle, sommerfeld_number
from exuclear.geometry import BearingGeometry

R = 0.02        # journal radius [m]
C = 40e-6       # radial clearance [m]: psi = 2e-3
ETA = 0.05      # [Pa s]
OMEGA = 100.0   # [rad/s]
MASS_PARAMETER = 0.01   # m c omega^2 / F, two orders below oil whip (module docstring)
INERTIA = 100.0  # [kg m^2]: the spin stays constant to 1e-5 (module docstring)
STEP = 1e-4     # [s]; the steady state does not depend on it (an implicit method's fixed point)
T_END = 0.5     # [s]: 8 revolutions, about 50 film relaxation times
# Butenschoen (1976), Table: B/D, eps, So, beta [deg]
BUTENSCHOEN = [(1.0, 0.5, 0.8903, 56.705), (1.0, 0.9, 8.4352, 26.482),
               (0.125, 0.5, 0.0231, 53.784), (0.125, 0.9, 0.6776, 21.089)]
needs_compiled = pytest.mark.skipif(kernel.COMPILED is None, reason="the compiled kernel is not built")


def unit_load(width_ratio: float) -> float:
    """``B D eta omega / psi^2`` [N]: the load of Sommerfeld number 1 (physics.md eq. (57))."""
    return 2.0 * R * width_ratio * 2.0 * R * ETA * OMEGA / (C / R) ** 2


def lubricated(model: str) -> dict:
    return {"lubrication": Lubrication(viscosity=ETA, model=model)}


def steady_run(model: str, width_ratio: float, load: float, backend: str = "compiled", eps0: float = 0.3,
               t_end: float = T_END, slices: int | None = None) -> dict:
    """A journal spinning at OMEGA in a fixed bearing under ``load`` along -y, released at
    ``eps0`` below the centre; the joint's outputs (``slices``: the spatial joint's)."""
    mbs = exu.SystemContainer().AddSystem()
    ground = mbs.AddObject(ObjectGround())
    node = mbs.AddNode(NodeRigidBody2D(referenceCoordinates=[0, 0, 0], initialCoordinates=[0, -eps0 * C, 0],
                                       initialVelocities=[0, 0, OMEGA]))
    pin = mbs.AddObject(ObjectRigidBody2D(nodeNumber=node, mass=MASS_PARAMETER * load / (C * OMEGA ** 2),
                                          inertia=INERTIA))
    mbs.AddLoad(LoadForceVector(markerNumber=mbs.AddMarker(MarkerBodyPosition(bodyNumber=pin)),
                                loadVector=[0, -load, 0]))
    joint = exuclear.CreateClearanceJoint(mbs, itemNumbers=[ground, pin], position=[0, 0, 0], axis=[0, 0, 1],
                                          journal_radius=R, bearing_radius=R + C, length=2.0 * R * width_ratio,
                                          cr=0.9, backend=backend, slices=slices, **lubricated(model))
    solve(mbs, t_end, STEP)
    return {**joint.outputs(), "frame": joint.frame}  # the frame of ecc_x, ecc_y (CreateRevoluteJoint's)


def solve(mbs: exu.MainSystem, t_end: float, step: float) -> None:
    mbs.Assemble()
    ss = exu.SimulationSettings()
    ss.timeIntegration.endTime = t_end
    ss.timeIntegration.numberOfSteps = int(round(t_end / step))
    ss.timeIntegration.generalizedAlpha.spectralRadius = 0.5  # damps the stiff film's fast modes
    ss.timeIntegration.verboseMode = 0
    ss.solution.file.write = False
    ss.solution.sensors.writePeriod = step
    mbs.SolveDynamic(ss, solverType=exu.DynamicSolverType.GeneralizedAlpha)


def model_steady_state(model: str, width_ratio: float, so: float) -> tuple[float, float]:
    """The film law's own ``(eps, beta [deg])`` carrying Sommerfeld number ``so`` at rest
    (bisection on ``So(eps)``, which rises monotonically), from exuclear.film directly."""
    g = BearingGeometry(R, R + C, 2.0 * R * width_ratio)
    law = Lubrication(viscosity=ETA, model=model).law(g)

    def so_of(eps: float) -> float:
        f = law.load(eps * C, 0.0, 0.0, 0.0, OMEGA, 0.0)
        return sommerfeld_number(math.hypot(f.fx, f.fy), g, ETA, OMEGA)

    lo, hi = 1e-3, 0.999
    for _ in range(60):
        mid = 0.5 * (lo + hi)
        lo, hi = (mid, hi) if so_of(mid) < so else (lo, mid)
    eps = 0.5 * (lo + hi)
    f = law.load(eps * C, 0.0, 0.0, 0.0, OMEGA, 0.0)
    return eps, math.degrees(attitude_angle(eps * C, 0.0, f.fx, f.fy))


def settled(out: dict) -> tuple[float, float]:
    eps, beta = out["eccentricity_ratio"], np.degrees(out["attitude_angle"])
    half = len(eps) // 2
    assert abs(eps[-1] - eps[half]) < 1e-4, "not settled: eps still moves over the run's second half"
    return float(eps[-1]), float(beta[-1])


# -- steady load: the published numbers ---------------------------------------------------------
@needs_compiled
@pytest.mark.parametrize("width_ratio, eps_table, so, beta_table", BUTENSCHOEN)
def test_finite_model_settles_at_butenschoens_table(width_ratio, eps_table, so, beta_table):
    # the load from the table's So; the finite model's fits reproduce the table to So 5 %,
    # beta 1.6 deg (tests/test_film.py), which moves the equilibrium by up to ~0.01 in eps:
    # within the brief's 0.02 and 2 deg.  Against the model's own steady state (the
    # element's job) the element is checked tighter: eps 1e-4, beta 0.05 deg (the run's
    # remaining settling, ~1e-5).  0.6 s: a rotating film's squeeze turns between its
    # approaching and leaving numbers (physics.md eq. (66a)), so the B/D = 1/8 journal rings
    # down from its start at eps 0.3 for 0.3 s before eps moves less than settled()'s 1e-4
    eps, beta = settled(steady_run("finite", width_ratio, so * unit_load(width_ratio), t_end=0.6))
    assert abs(eps - eps_table) < 0.02
    assert abs(beta - beta_table) < 2.0
    eps_model, beta_model = model_steady_state("finite", width_ratio, so)
    assert abs(eps - eps_model) < 1e-4
    assert abs(beta - beta_model) < 0.05


def ocvirk(width_ratio: float, eps: float) -> tuple[float, float]:
    """Ocvirk's closed form: So = (B/D)^2 / 2 eps sqrt(pi^2 (1 - eps^2) + 16 eps^2) / (1 - eps^2)^2
    (F = eta omega R L^3 / (4 c^2) ...), tan(beta) = pi sqrt(1 - eps^2) / (4 eps)."""
    so = width_ratio ** 2 / 2 * eps * math.sqrt(math.pi ** 2 * (1 - eps ** 2) + 16 * eps ** 2) / (1 - eps ** 2) ** 2
    return so, math.degrees(math.atan(math.pi * math.sqrt(1 - eps ** 2) / (4 * eps)))


@needs_compiled
@pytest.mark.parametrize("width_ratio, eps_target", [(0.25, 0.5), (0.25, 0.9), (0.125, 0.5), (0.125, 0.9)])
def test_short_model_settles_at_ocvirks_closed_form(width_ratio, eps_target):
    # the short model is Ocvirk's for rotation alone: only the run's settling separates
    # them (eps 1e-4, beta 0.05 deg), well inside the brief's 0.02 and 2 deg
    so, beta_target = ocvirk(width_ratio, eps_target)
    eps, beta = settled(steady_run("short", width_ratio, so * unit_load(width_ratio)))
    assert abs(eps - eps_target) < 1e-4
    assert abs(beta - beta_target) < 0.05


@needs_compiled
def test_long_model_settles_at_sommerfelds_closed_form():
    # the long model: F_r = 12 eta omega R^3 B eps^2 / (c^2 (2 + eps^2) (1 - eps^2)),
    # F_t = 6 pi eta omega R^3 B eps / (c^2 (2 + eps^2) sqrt(1 - eps^2)) (exuclear/film/laws.py LongBearing)
    eps_target, width_ratio = 0.6, 1.0
    k = ETA * OMEGA * R ** 3 * (2.0 * R * width_ratio) / C ** 2
    f_r = 12.0 * k * eps_target ** 2 / ((2.0 + eps_target ** 2) * (1.0 - eps_target ** 2))
    f_t = 6.0 * math.pi * k * eps_target / ((2.0 + eps_target ** 2) * math.sqrt(1.0 - eps_target ** 2))
    eps, beta = settled(steady_run("long", width_ratio, math.hypot(f_r, f_t)))
    assert abs(eps - eps_target) < 1e-4
    assert abs(beta - math.degrees(math.atan2(f_t, f_r))) < 0.05


# -- the user's path: a loaded journal comes to rest near the blend (issue 30) ------------------
#: The scene of issue 30: a journal spinning at 50 Hz in a fixed bearing, R 10 mm, c 10 um, eta
#: 0.01 Pa s, 0.05 kg; its moment of inertia 1000 kg m^2 holds the spin (the film's moment,
#: ~0.1 N m, slows it by 2e-5 rad/s over a run).  Started 0.5 c below the centre.
REST_R, REST_C, REST_ETA, REST_OMEGA = 0.01, 10e-6, 0.01, 2.0 * math.pi * 50.0
REST_MASS, REST_INERTIA, REST_STEP, REST_END = 0.05, 1e3, 1e-5, 0.2


def plain_rest_run(model: str, length: float, load: float | Callable[[float], float],
                   t_end: float = REST_END) -> tuple[float, dict]:
    """The user's path: ``mbs.CreateRigidBody`` (planar), ``exuclear.CreateClearanceJoint``
    and ``mbs.SolveDynamic`` with Exudyn's default settings (generalized-alpha) and steps of
    REST_STEP; ``load`` [N] along -y, a number or a function of time.  The time the solver
    reached and the joint's outputs."""
    from exudyn.utilities import RigidBodyInertia

    mbs = exu.SystemContainer().AddSystem()
    ground = mbs.CreateGround()
    body = mbs.CreateRigidBody(inertia=RigidBodyInertia(mass=REST_MASS, inertiaTensor=np.diag([REST_INERTIA] * 3)),
                               referencePosition=[0, 0, 0], initialDisplacement=[0, -0.5 * REST_C, 0],
                               initialAngularVelocity=[0, 0, REST_OMEGA], create2D=True, returnDict=True)
    if callable(load):
        mbs.CreateForce(itemNumber=body["bodyNumber"], loadVector=[0, -load(0.0), 0],
                        loadVectorUserFunction=lambda mbs_, t, vector: [0, -load(t), 0])
    else:
        mbs.CreateForce(itemNumber=body["bodyNumber"], loadVector=[0, -load, 0])
    joint = exuclear.CreateClearanceJoint(mbs, itemNumbers=[ground, body["bodyNumber"]], position=[0, 0, 0],
                                          journal_radius=REST_R, bearing_radius=REST_R + REST_C, length=length,
                                          cr=0.9, lubrication=Lubrication(viscosity=REST_ETA, model=model))
    mbs.Assemble()
    ss = exu.SimulationSettings()
    ss.timeIntegration.endTime = t_end
    ss.timeIntegration.numberOfSteps = int(round(t_end / REST_STEP))
    ss.timeIntegration.verboseMode = 0
    ss.solution.file.write = False
    try:
        mbs.SolveDynamic(ss)
    except RuntimeError:  # Exudyn's "SolveDynamic terminated": the time reached tells
        pass
    return mbs.systemData.GetTime(), joint.outputs()


def butenschoen_eccentricity(so: float, width_ratio: float) -> float:
    """The eccentricity ratio at which Butenschoen's rotation fit (eq. (64), 1976, as DIN 31652-2
    gives it; exuclear.film.FiniteBearing) carries Sommerfeld number ``so``, by bisection."""
    g = BearingGeometry(REST_R, REST_R + REST_C, 2.0 * REST_R * width_ratio)
    law = Lubrication(viscosity=REST_ETA, model="finite").law(g)
    lo, hi = 1e-3, 0.999
    for _ in range(60):
        mid = 0.5 * (lo + hi)
        lo, hi = (mid, hi) if law.rotation(mid)[0] < so else (lo, mid)
    return 0.5 * (lo + hi)


@needs_compiled
@pytest.mark.parametrize("so", [8.4352, 12.0])
def test_plain_solve_dynamic_rests_the_journal_at_butenschoens_eccentricity(so):
    # issue 30: B/D = 0.999 of the bearing's diameter (1.000 of the journal's), the load of
    # Butenschoen's So = 8.4352 (his table: eps 0.9 at B/D = 1; the fit, 0.896) and So = 12
    # (the fit: eps 0.924, inside the blend of eq. (70)).  The film's squeeze number switched
    # at eps_dot = 0 (281 times the damping on one side), Exudyn's Newton stalled at the rest
    # state and the run stopped at 0.0331 s (0.031 s at So 12).  Now it runs to its end with
    # the journal at the fit's eps (the blend moves it by < 0.001 here: eps_b = 0.923 at eps
    # 0.924), within the brief's 0.02 of the table and within 0.002 of the fit
    length = 0.999 * 2.0 * (REST_R + REST_C)
    width_ratio = length / (2.0 * REST_R)
    load = so * length * 2.0 * REST_R * REST_ETA * REST_OMEGA / (REST_C / REST_R) ** 2  # eq. (57)
    reached, out = plain_rest_run("finite", length, load)
    assert reached == pytest.approx(REST_END, abs=0.1 * REST_STEP)
    eps = float(out["eccentricity_ratio"][-1])
    if so == 8.4352:
        assert abs(eps - 0.9) < 0.02  # Butenschoen's table (tests/test_film.py BUTENSCHOEN)
    assert abs(eps - butenschoen_eccentricity(so, width_ratio)) < 0.002


REST_ECCENTRICITIES = (0.8, 0.85, 0.9, 0.92, 0.95, 0.97, 0.99)


def rest_load(model: str, width_ratio: float, eps: float) -> float:
    """The load [N] the film carries at rest at ``eps`` (its blended law, eq. (70))."""
    g = BearingGeometry(REST_R, REST_R + REST_C, 2.0 * REST_R * width_ratio)
    f = Lubrication(viscosity=REST_ETA, model=model).law(g).blended_load(eps * REST_C, 0.0, 0.0, 0.0, REST_OMEGA, 0.0)
    return math.hypot(f.fx, f.fy)


@needs_compiled
@pytest.mark.parametrize("model", ["short", "long", "finite"])
@pytest.mark.parametrize("width_ratio", [1 / 8, 1 / 2, 1.0])
@pytest.mark.parametrize("eps", REST_ECCENTRICITIES)
def test_newton_converges_for_a_journal_resting_from_eps_08_to_099(model, width_ratio, eps):
    # the plain path through film, blend (eps > 0.9) and its cap: under the load the blended film
    # carries at rest at eps the journal runs to the end and rests there (within 1e-4, the
    # settledness of the steady runs above; measured within 1e-5); under a load varying
    # sinusoidally between 0.6 and 1 times that (10 Hz, two periods) it runs to the end, its
    # largest eps over the second half (at the load's peak) within 0.005 of that eps (measured:
    # 0.0004 at most above, the orbit's overshoot as the load turns, 0.0024 at most below, the
    # squeeze film's lag and the outputs' sampling at Exudyn's default 0.01 s, ten a period)
    load = rest_load(model, width_ratio, eps)
    reached, out = plain_rest_run(model, 2.0 * REST_R * width_ratio, load)
    assert reached == pytest.approx(REST_END, abs=0.1 * REST_STEP)
    assert abs(out["eccentricity_ratio"][-1] - eps) < 1e-4
    reached, out = plain_rest_run(model, 2.0 * REST_R * width_ratio,
                                  lambda t: load * (0.8 + 0.2 * math.sin(2.0 * math.pi * 10.0 * t)))
    assert reached == pytest.approx(REST_END, abs=0.1 * REST_STEP)
    e = out["eccentricity_ratio"]
    assert abs(e[len(e) // 2:].max() - eps) < 0.005


# -- the frame: which velocity the film takes -------------------------------------------------
@needs_compiled
@pytest.mark.parametrize("backend", ["compiled", "python"])
def test_a_spinning_bearing_carries_the_load_as_a_spinning_journal_does(backend):
    # omega_eff = omega_J + omega_B - 2 dphi/dt: a bearing spinning at OMEGA round a journal
    # that does not spin carries the load at the same eps and attitude as the journal
    # spinning in a fixed bearing.  The connector hands over A0^T (v1 - v0), the inertial
    # rate in the bearing's (rotating) frame, with the bearing's spin from the probe
    # connector: taken for the rotating frame's rate, the film would see omega_eff = 3 OMEGA
    # in steady state (the eccentricity turns at -OMEGA in that frame) and settle elsewhere.
    width_ratio, eps_target = 0.25, 0.5
    so, beta_target = ocvirk(width_ratio, eps_target)
    load = so * unit_load(width_ratio)
    mbs = exu.SystemContainer().AddSystem()
    ground_node = mbs.AddNode(NodePointGround())
    fixed = mbs.AddMarker(MarkerNodeCoordinate(nodeNumber=ground_node, coordinate=0))
    bearing_node = mbs.AddNode(NodeRigidBody2D(referenceCoordinates=[0, 0, 0], initialVelocities=[0, 0, OMEGA]))
    bearing = mbs.AddObject(ObjectRigidBody2D(nodeNumber=bearing_node, mass=1.0, inertia=INERTIA))
    for axis in (0, 1):  # the bearing's centre held, its spin free
        mbs.AddObject(CoordinateConstraint(markerNumbers=[fixed, mbs.AddMarker(
            MarkerNodeCoordinate(nodeNumber=bearing_node, coordinate=axis))]))
    journal_node = mbs.AddNode(NodeRigidBody2D(referenceCoordinates=[0, 0, 0], initialCoordinates=[0, -0.3 * C, 0]))
    journal = mbs.AddObject(ObjectRigidBody2D(nodeNumber=journal_node, mass=MASS_PARAMETER * load / (C * OMEGA ** 2),
                                              inertia=INERTIA))
    mbs.AddLoad(LoadForceVector(markerNumber=mbs.AddMarker(MarkerBodyPosition(bodyNumber=journal)),
                                loadVector=[0, -load, 0]))
    joint = exuclear.CreateClearanceJoint(mbs, itemNumbers=[bearing, journal], position=[0, 0, 0], axis=[0, 0, 1],
                                          journal_radius=R, bearing_radius=R + C, length=2.0 * R * width_ratio,
                                          cr=0.9, backend=backend, **lubricated("short"))
    solve(mbs, 0.2 if backend == "python" else T_END, STEP)
    out = joint.outputs()
    eps, beta = float(out["eccentricity_ratio"][-1]), float(np.degrees(out["attitude_angle"][-1]))
    assert abs(eps - eps_target) < 1e-3  # the python run is shorter: settled to ~1e-4
    assert abs(beta - beta_target) < 0.1
    # the eccentricity is at rest in space, so it turns at -OMEGA in the bearing's frame
    phi = np.unwrap(np.arctan2(out["ecc_y"], out["ecc_x"]))
    t = out["time"]
    rate = (phi[-1] - phi[len(phi) // 2]) / (t[-1] - t[len(t) // 2])
    assert rate == pytest.approx(-OMEGA, rel=1e-3)
    # and it sits where the spinning journal's does, on the same side of the load (eps and
    # |beta| alone would not tell omega_eff = +OMEGA from -OMEGA, the mirror image)
    spinning_journal = steady_run("short", width_ratio, load, backend=backend, t_end=t[-1])
    where = mbs.GetNodeOutput(journal_node, exu.OutputVariableType.Position)[:2]
    ecc = [spinning_journal["ecc_x"][-1], spinning_journal["ecc_y"][-1]]  # in the fixed bearing's joint frame
    np.testing.assert_allclose(where, spinning_journal["frame"][:2, :2] @ ecc, atol=2e-3 * C)


# -- balance: the film passes momentum and angular momentum between two free bodies -----------
@needs_compiled
@pytest.mark.parametrize("model, backend", [("short", "compiled"), ("long", "compiled"), ("finite", "compiled"),
                                            ("short", "python")])
def test_two_free_bodies_keep_momentum_and_angular_momentum(model, backend):
    # a spinning bearing and a journal, both free, coupled by the film alone: the film's force
    # pair keeps the momentum to round-off; its moments (eq. (69): M_J + M_B + (e x F)_z = 0,
    # the bearing's share through the torque connector) keep the angular momentum to the
    # integrator's error, here below 1e-5 of what the film passes from bearing to journal
    mbs = exu.SystemContainer().AddSystem()
    m_b, j_b, m_j, j_j = 2.0, 1e-3, 0.5, 1e-4
    nodes = [mbs.AddNode(NodeRigidBody2D(referenceCoordinates=[0, 0, 0], initialVelocities=[0.0, 0.0, 80.0])),
             mbs.AddNode(NodeRigidBody2D(referenceCoordinates=[0, 0, 0], initialCoordinates=[0.4 * C, 0.1 * C, 0],
                                         initialVelocities=[0.0, 0.02, -20.0]))]
    bodies = [mbs.AddObject(ObjectRigidBody2D(nodeNumber=n, mass=m, inertia=j))
              for n, m, j in zip(nodes, (m_b, m_j), (j_b, j_j))]
    exuclear.CreateClearanceJoint(mbs, itemNumbers=bodies, position=[0, 0, 0], axis=[0, 0, 1], journal_radius=R,
                                  bearing_radius=R + C, length=0.01, cr=0.8, backend=backend,
                                  lubrication=Lubrication(viscosity=0.01, model=model))
    kinds = (exu.OutputVariableType.Position, exu.OutputVariableType.Velocity,
             exu.OutputVariableType.AngularVelocity)
    sensors = [mbs.AddSensor(SensorNode(nodeNumber=n, storeInternal=True, outputVariableType=v))
               for n in nodes for v in kinds]
    solve(mbs, 0.02 if backend == "compiled" else 0.005, 1e-5)
    p_b, v_b, w_b, p_j, v_j, w_j = (np.asarray(mbs.GetSensorStoredData(s)) for s in sensors)
    momentum = m_b * v_b[:, 1:3] + m_j * v_j[:, 1:3]
    angular = (j_b * w_b[:, 3] + j_j * w_j[:, 3] + m_b * (p_b[:, 1] * v_b[:, 2] - p_b[:, 2] * v_b[:, 1])
               + m_j * (p_j[:, 1] * v_j[:, 2] - p_j[:, 2] * v_j[:, 1]))
    passed = j_b * abs(w_b[-1, 3] - w_b[0, 3])
    assert passed > 1e-5  # the film does pass angular momentum
    assert np.max(np.abs(momentum - momentum[0])) < 1e-12 * m_j * 0.02
    assert np.max(np.abs(angular - angular[0])) < 1e-5 * passed


# -- the two kernels ---------------------------------------------------------------------------
#: Viscosity [Pa s] of the impact: thin enough for the journal to reach the wall (the long
#: model's squeeze film, ~R^2/B^2 = 16 times the short one's here, gets a thinner oil)
#: Exudyn's default relative Newton tolerance, which the impact run keeps.
NEWTON_RTOL = 1e-8
IMPACT_VISCOSITY = {"short": 1e-3, "long": 3e-4, "finite": 1e-3}


def impact_run(model: str, backend: str) -> dict:
    """A 5 kg journal thrown at 0.5 m/s against the wall through a thin film: film, blend and
    metal contact (largest penetration 2.6 um short, 8 um long, 16 um finite: the short
    model's squeeze film is the stiffest, physics.md section 10.6) within 2 ms."""
    mbs = exu.SystemContainer().AddSystem()
    ground = mbs.AddObject(ObjectGround())
    node = mbs.AddNode(NodeRigidBody2D(referenceCoordinates=[0, 0, 0], initialVelocities=[0.5, 0.1, 50.0]))
    pin = mbs.AddObject(ObjectRigidBody2D(nodeNumber=node, mass=5.0, inertia=1e-4))
    joint = exuclear.CreateClearanceJoint(mbs, itemNumbers=[ground, pin], position=[0, 0, 0], axis=[0, 0, 1],
                                          journal_radius=R, bearing_radius=R + C, length=0.01, cr=0.8,
                                          friction="coulomb:0.1", backend=backend,
                                          lubrication=Lubrication(viscosity=IMPACT_VISCOSITY[model], model=model))
    solve(mbs, 2e-3, 1e-6)
    return joint.outputs()


@needs_compiled
@pytest.mark.parametrize("model", ["short", "long", "finite"])
def test_compiled_equals_python_on_a_lubricated_impact(model):
    # the same formulas in the same order: equal to round-off (the cavitation arcs are found
    # in closed form (short) and by the same Halley iterations (long) in both kernels: 1e-12
    # relative on the force).  Over 2000
    # steps of a contact the runs agree to Newton's relative tolerance (1e-8, Exudyn's
    # default): the joint's finite-difference increment of 1e-9 (exuclear.engine.steering)
    # turns the kernels' round-off into Jacobians that differ at 1e-7, so Newton stops at
    # iterates that differ within its tolerance (measured 1.4e-9 relative with an increment
    # of 1e-10)
    compiled, python = impact_run(model, "compiled"), impact_run(model, "python")
    assert (compiled["regime"] == REGIME_CONTACT).any(), "the journal should reach the wall"
    assert (compiled["regime"] == 0).any()
    for name in ("ecc_x", "ecc_y", "normal_force", "film_fx", "film_fy", "film_torque", "v0"):
        scale = np.max(np.abs(python[name])) or 1.0
        np.testing.assert_allclose(compiled[name], python[name], rtol=0, atol=NEWTON_RTOL * scale, err_msg=name)


@needs_compiled
def test_kernels_agree_on_the_film_load_at_single_states():
    # force_torque of both kernels on the same arguments, across eccentricity, squeeze,
    # whirl and the blend to the wall (eps up to 1.05): the loads to 1e-12 relative
    from exuclear.engine import _python_kernel
    from exuclear.engine.layout import MAIN, parameters

    rng = np.random.default_rng(23)
    for model in ("short", "long", "finite"):
        joint = exuclear.make_joint(journal_radius=R, bearing_radius=R + C, length=0.01, cr=0.8,
                                    lubrication=Lubrication(viscosity=0.03, model=model))
        py = _python_kernel.JointKernel(joint)
        joint_id = kernel.COMPILED.new_joint()
        try:
            p = parameters(joint, joint_id, MAIN, 1e-3)
            # random states, then a journal at rest and creeping (1e-9 m/s, both ways) at the
            # blend's start eps_film = 0.9 (and just either side), inside it and near its cap,
            # spinning: where the finite model's squeeze turns (eq. (66a)) and the blend begins
            states = [(rng.uniform(0.0, 1.05), rng.uniform(-math.pi, math.pi), [*rng.normal(0.0, 1e-3, 2), 0.0],
                       rng.normal(0.0, 100.0)) for _ in range(200)]
            states += [(eps, 0.3, [math.cos(0.3) * rate, math.sin(0.3) * rate, 0.0], spin)
                       for eps in (math.nextafter(0.9, 0.0), 0.9, math.nextafter(0.9, 1.0), 0.924, 0.99)
                       for rate in (0.0, 1e-9, -1e-9) for spin in (OMEGA, -OMEGA)]
            for eps, phi, v, spin in states:
                d = [eps * C * math.cos(phi), eps * C * math.sin(phi), 0.0]
                w = [0.0, 0.0, spin]
                t = 1.0  # after the run's start: both take their initial state from the first call
                args = (None, t, 0, d, [0.0] * 3, v, w, p, p, [[0.0] * 3] * 3, [[0.0] * 3] * 3, [0.0] * 6)
                a = np.array(kernel.COMPILED.force_torque(*args))
                b = np.array(py.force_torque(*args))
                np.testing.assert_allclose(a, b, rtol=1e-12, atol=1e-12 * np.max(np.abs(b)))
        finally:
            kernel.COMPILED.release(joint_id)


# -- the spatial joint: a film per slice ------------------------------------------------------------
@needs_compiled
@pytest.mark.parametrize("backend", ["compiled", "python"])
def test_aligned_spatial_film_is_the_planar_film(backend):
    # an aligned journal: every slice sees the planar film's state, and N shares of 1/N add
    # up to the planar film (the run equals the planar one to round-off)
    width_ratio = 0.25
    so, _ = ocvirk(width_ratio, 0.5)
    load = so * unit_load(width_ratio)
    planar = steady_run("short", width_ratio, load, backend=backend, t_end=0.05)
    spatial = steady_run("short", width_ratio, load, backend=backend, t_end=0.05, slices=4)
    assert spatial["film_fx"].shape == (len(planar["time"]), 4)
    for k in range(4):
        np.testing.assert_allclose(spatial["ecc_x"][:, k], planar["ecc_x"], rtol=0, atol=1e-12 * C)
        np.testing.assert_allclose(spatial["ecc_y"][:, k], planar["ecc_y"], rtol=0, atol=1e-12 * C)
        np.testing.assert_allclose(4.0 * spatial["film_fx"][:, k], planar["film_fx"], rtol=1e-12, atol=1e-9)


@needs_compiled
@pytest.mark.parametrize("model", ["short", "long", "finite"])
def test_tilted_journal_film_loads_per_slice(model):
    # a journal tilted about x by alpha, spinning about its own axis, its centre 0.5 c below the
    # bearing's: each slice's film at its own eccentricity, a share 1/N each; both kernels'
    # torque equals minus the journal's moment about its centre summed from the film law
    # here, to 1e-12, and the film resists the tilt (the journal's moment about x opposes it)
    from exuclear.engine import _python_kernel
    from exuclear.engine.layout import MAIN, parameters
    from exuclear.spatial import slice_centres

    slices, alpha, length = 8, 2e-3, 0.01
    joint = exuclear.make_joint(journal_radius=R, bearing_radius=R + C, length=length, cr=0.8,
                                lubrication=Lubrication(viscosity=0.03, model=model))
    p, u = (0.0, -0.5 * C, 0.0), (0.0, -math.sin(alpha), math.cos(alpha))
    moment = np.zeros(3)
    for z in slice_centres(length, slices):
        s_k = (z - p[2]) / u[2]
        r = joint.film.blended_load(p[0] + s_k * u[0], p[1] + s_k * u[1], 0.0, 0.0, OMEGA, 0.0)
        moment += np.cross([s_k * u[0], s_k * u[1], s_k * u[2]], [r.fx, r.fy, 0.0]) / slices
        moment[2] += r.torque_journal / slices
    args = (None, 1.0, 0, list(p), [alpha, 0.0, 0.0], [0.0] * 3, [OMEGA * v for v in u])  # spin about its axis
    python = _python_kernel.JointKernel(joint, slices)
    joint_id = kernel.COMPILED.new_joint()
    try:
        par = parameters(joint, joint_id, MAIN, 1e-3, slices=slices)
        rest = (par, par, [[0.0] * 3] * 3, [[0.0] * 3] * 3, [0.0] * 6)
        for loads in (kernel.COMPILED.force_torque(*args, *rest), python.force_torque(*args, *rest)):
            np.testing.assert_allclose(-np.array(loads[3:]), moment, rtol=1e-12, atol=1e-12 * np.abs(moment).max())
    finally:
        kernel.COMPILED.release(joint_id)
    assert moment[0] < 0.0  # the slice nearer the wall (z > 0) pushes harder: back towards alignment


def spatial_run(backend: str) -> dict:
    """A 3D steel journal (20 mm radius, 40 mm long) in a fixed bearing with axial play and
    a film (short model, 1e-4 Pa s), thrown sideways and axially, tilting and spinning: the
    film carries it (eps up to 0.44, per slice) while the end faces take the axial impact,
    within 2 ms."""
    from exudyn.utilities import InertiaCylinder

    mbs = exu.SystemContainer().AddSystem()
    ground = mbs.CreateGround()
    body = mbs.CreateRigidBody(inertia=InertiaCylinder(7800.0, 0.04, R, 2), referencePosition=[0, 0, 0],
                               initialVelocity=[0.3, 0.05, -0.02], initialAngularVelocity=[0.05, -0.03, 50.0],
                               nodeType=exu.NodeType.RotationRxyz, returnDict=True)
    joint = exuclear.CreateClearanceJoint(mbs, itemNumbers=[ground, body["bodyNumber"]], position=[0, 0, 0],
                                          slices=6, journal_radius=R, bearing_radius=R + C, length=0.04, cr=0.8,
                                          friction="coulomb:0.1", axial_clearance=2e-5, shoulder_radius=1.2 * R,
                                          backend=backend, show=False,
                                          lubrication=Lubrication(viscosity=1e-4, model="short"))
    solve(mbs, 2e-3, 1e-6)
    return joint.outputs()


@needs_compiled
def test_compiled_equals_python_on_a_lubricated_spatial_joint():
    compiled, python = spatial_run("compiled"), spatial_run("python")
    assert compiled["film_fx"].shape[1] == 6
    for name in ("tilt_x", "tilt_y", "axial_displacement", "ecc_x", "ecc_y", "film_fx", "film_fy", "film_torque",
                 "normal_force", "face_normal_force"):
        scale = np.max(np.abs(python[name])) or 1.0
        np.testing.assert_allclose(compiled[name], python[name], rtol=0, atol=NEWTON_RTOL * scale, err_msg=name)


# -- outputs and refusals ------------------------------------------------------------------------
@needs_compiled
def test_dry_joint_keeps_its_data_node_and_outputs():
    mbs = exu.SystemContainer().AddSystem()
    ground = mbs.AddObject(ObjectGround())
    node = mbs.AddNode(NodeRigidBody2D(referenceCoordinates=[0, 0, 0], initialVelocities=[0.05, 0, 0]))
    pin = mbs.AddObject(ObjectRigidBody2D(nodeNumber=node, mass=0.5, inertia=1e-4))
    joint = exuclear.CreateClearanceJoint(mbs, itemNumbers=[ground, pin], position=[0, 0, 0], axis=[0, 0, 1],
                                          journal_radius=R, bearing_radius=R + C, length=0.01, cr=0.8)
    solve(mbs, 1e-3, 1e-5)
    assert len(mbs.GetNode(joint.nodeNumber)["initialCoordinates"]) == len(DATA_COLUMNS)
    assert set(joint.outputs()) == {"time", *OUTPUT_COLUMNS}


@needs_compiled
def test_lubricated_outputs_hold_the_film_columns():
    out = impact_run("short", "compiled")
    assert set(out) == {"time", *OUTPUT_COLUMNS, *FILM_OUTPUT_COLUMNS}
    np.testing.assert_allclose(out["min_film_thickness"], C * (1.0 - out["eccentricity_ratio"]), rtol=1e-12)
    np.testing.assert_allclose(out["film_force"], np.hypot(out["film_fx"], out["film_fy"]), rtol=1e-12)
    assert len(FILM_DATA_COLUMNS) == kernel.COMPILED.N_FILM_DATA


PAPER = {"journal_radius": 9.9e-3, "bearing_radius": 10e-3, "length": 15e-3, "cr": 0.9}


@pytest.mark.parametrize("value", ["oil", 0.05, {"viscosity": 0.05}])
def test_lubrication_must_be_a_lubrication(value):
    with pytest.raises(ValueError, match="`lubrication`"):
        exuclear.make_joint(**PAPER, lubrication=value)


def test_finite_model_refuses_a_width_ratio_outside_its_fits():
    with pytest.raises(ValueError, match="B/D"):  # the paper's B/D = 0.76 fits; 2 does not
        exuclear.make_joint(**{**PAPER, "length": 0.04}, lubrication=Lubrication(viscosity=0.05, model="finite"))


def _two_bodies():
    mbs = exu.SystemContainer().AddSystem()
    ground = mbs.AddObject(ObjectGround())
    node = mbs.AddNode(NodeRigidBody2D(referenceCoordinates=[0, 0, 0]))
    return mbs, ground, mbs.AddObject(ObjectRigidBody2D(nodeNumber=node, mass=1.0, inertia=1e-3))


def test_a_joint_cannot_switch_between_dry_and_lubricated():
    mbs, ground, pin = _two_bodies()
    joint = exuclear.CreateClearanceJoint(mbs, itemNumbers=[ground, pin], position=[0, 0, 0], axis=[0, 0, 1],
                                          **PAPER)
    with pytest.raises(ValueError, match="dry and lubricated"):
        joint.joint = exuclear.make_joint(**PAPER, lubrication=Lubrication(viscosity=0.05))
