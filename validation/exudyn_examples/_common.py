"""The zoo's interface: what a model module provides, the registry of models, and the
helpers model authors share.

A model is a module of this package with ``EXAMPLE`` (the Exudyn example it follows),
``BODIES`` (the body and node types it covers), ``REPLACED`` (which revolute joint became
a clearance joint) and a ``build(clearance, end_time=None, **joint_options) -> ZooModel``
decorated with :func:`register`.  The models come in groups (:data:`GROUPS`), one
package each: the zoo's default table, this package's own modules, and "beyond", more of
Exudyn's examples in the subpackage ``beyond``, which run only when asked for.
:mod:`._runs` runs one model four ways (ideal,
clearance with the example's own settings, clearance through ``exuclear.simulate``, a
convergence check); :mod:`._table` runs them all and writes the table and the report
that ``python -m validation.exudyn_examples`` prints and writes.
"""
from __future__ import annotations

import functools
import importlib
import pkgutil
from collections.abc import Callable
from dataclasses import dataclass, field
from types import ModuleType
from typing import Any

import exudyn as exu
import numpy as np
from exudyn.itemInterface import LoadMassProportional, MarkerBodyMass, NodePoint2DSlope1, ObjectANCFCable2D

import exuclear
from exuclear.settings import METHODS

# =======================================================================================
# the interface
# =======================================================================================


@dataclass
class ZooModel:
    """One assembled zoo model, ideal or with its clearance joint.

    Attributes
    ----------
    name : str
        The registered name.
    mbs : exudyn.MainSystem
        The assembled system.
    simulation_settings : exudyn.SimulationSettings
        The example's own solver settings (step, end time or the given ``end_time``,
        Newton settings as the example sets them); solution files off.
    solver_type : exudyn.DynamicSolverType
        The example's solver.
    joint : exuclear.ClearanceJointHandle or None
        The clearance joint; None for the ideal model.
    clearance : float or None
        Radial clearance c = R_B - R_J [m]; None for the ideal model.
    probe : callable ``mbs -> ndarray``
        A few observables at the end of a run (e.g. the position [m] of a point of a body
        that the replaced joint carries), compared between ideal and clearance models.
    solver_settings : exuclear.SolverSettings
        The example's settings for :func:`exuclear.simulate`, with ``step="auto"``
        (:func:`solver_settings_like`).
    energy : callable ``mbs -> (float, float)``, optional
        Kinetic and potential energy [J] of a conservative model, for the test of the
        ideal model (energy conservation); None where the model has drives or damping.
    probe_bound : float, optional
        ``k`` such that, over a short run (tens of ms) from the example's initial state,
        ``|probe - ideal probe| <= k (c + largest penetration)`` holds for geometric
        reasons the model's docstring gives (the journal's offset in the bearing, and the
        rotation the carried body loses while the journal crosses the gap); None: the
        tests do not check the probe.
    """

    name: str
    mbs: exu.MainSystem
    simulation_settings: exu.SimulationSettings
    solver_type: exu.DynamicSolverType
    joint: Any
    clearance: float | None
    probe: Callable[[exu.MainSystem], np.ndarray]
    solver_settings: exuclear.SolverSettings
    energy: Callable[[exu.MainSystem], tuple[float, float]] | None = None
    probe_bound: float | None = None


@dataclass(frozen=True)
class Entry:
    """A registered model: its module (for EXAMPLE, BODIES, REPLACED), its build function
    and the keyword arguments fixed for this entry (a variant of a model); its group is
    its module's package's (:data:`GROUPS`)."""

    name: str
    module: ModuleType
    build: Callable[..., ZooModel]
    fixed: dict[str, Any] = field(default_factory=dict)

    def __call__(self, clearance: bool, end_time: float | None = None, **joint_options: Any) -> ZooModel:
        model = self.build(clearance, end_time, **{**self.fixed, **joint_options})
        model.name = self.name  # a variant's name, not its build's
        return model

    @property
    def example(self) -> str:
        return getattr(self.module, "EXAMPLE", "")

    @property
    def bodies(self) -> str:
        return getattr(self.module, "BODIES", "")

    @property
    def replaced(self) -> str:
        return getattr(self.module, "REPLACED", "")

    @property
    def group(self) -> str:
        return group_of(self.module.__name__)


#: The groups of models, each the package that holds its modules: "zoo", the default table
#: (``python -m validation.exudyn_examples``, the tests' short runs of every model), and
#: "beyond", more of Exudyn's examples (the subpackage's docstring lists them), which run
#: only when asked for (``--group beyond``, or their names), so that the default table keeps
#: its cost.
GROUPS: dict[str, str] = {"zoo": __package__, "beyond": f"{__package__}.beyond"}
#: The default group.
DEFAULT_GROUP = "zoo"

#: The registered models by name, in the order of registration: the models of the groups
#: loaded so far (:func:`load_models`; :func:`group_names` lists one group's).
REGISTRY: dict[str, Entry] = {}
#: Model modules that failed to import: name (for a group other than the default, prefixed
#: with its package, e.g. ``beyond.crane``) -> first line of the error.
IMPORT_ERRORS: dict[str, str] = {}


def group_of(module_name: str) -> str:
    """The group (:data:`GROUPS`) of a model module, from its package; ``ValueError`` for a
    module outside every group's package."""
    package = module_name.rpartition(".")[0]
    for group, group_package in GROUPS.items():
        if package == group_package:
            return group
    raise ValueError(f"module {module_name!r} is in no zoo group's package; the groups: "
                     f"{', '.join(f'{g} ({p})' for g, p in GROUPS.items())}")


def register(build: Callable[..., ZooModel] | None = None, *, name: str | None = None,
             **fixed: Any) -> Callable[..., ZooModel]:
    """Register a model's ``build``; returns it unchanged.

    ``@register`` registers it under its module's name.  ``register(build, name=...,
    **fixed)`` registers a variant: ``fixed`` are keyword arguments passed to every call
    (e.g. ``node_type="rxyz"`` or ``friction="paper"``).
    """
    if build is None:
        return functools.partial(register, name=name, **fixed)  # type: ignore[return-value]
    module = importlib.import_module(build.__module__)
    group_of(module.__name__)  # a model outside every group's package is refused here, not when listed
    key = name or build.__module__.rsplit(".", 1)[-1]
    if key in REGISTRY and REGISTRY[key].build is not build:
        raise ValueError(f"zoo model {key!r} is registered twice (modules {REGISTRY[key].module.__name__} and "
                         f"{module.__name__})")
    REGISTRY[key] = Entry(key, module, build, dict(fixed))
    return build


def load_models(group: str | None = DEFAULT_GROUP) -> dict[str, Entry]:
    """Import the model modules (names not starting with ``_``) of ``group`` (None: of every
    group) into :data:`REGISTRY` and return it; a module that fails to import is noted in
    :data:`IMPORT_ERRORS`, not raised.  ``ValueError`` for an unknown group."""
    groups = list(GROUPS) if group is None else [_checked_group(group)]
    for g in groups:
        package = importlib.import_module(GROUPS[g])
        prefix = "" if g == DEFAULT_GROUP else f"{g}."
        for info in pkgutil.iter_modules(package.__path__):
            if info.name.startswith("_") or info.ispkg:
                continue
            try:
                importlib.import_module(f"{GROUPS[g]}.{info.name}")
            except Exception as err:  # a broken model must not stop the others
                IMPORT_ERRORS[prefix + info.name] = f"{type(err).__name__}: {_first_line(err)}"
    return REGISTRY


def group_names(group: str = DEFAULT_GROUP) -> list[str]:
    """The names of ``group``'s models (:data:`GROUPS`), loaded, in the order of registration."""
    load_models(group)
    return [name for name, entry in REGISTRY.items() if entry.group == group]


def group_import_errors(group: str) -> dict[str, str]:
    """The :data:`IMPORT_ERRORS` of ``group``'s modules."""
    prefix = "" if group == DEFAULT_GROUP else f"{group}."
    return {name: error for name, error in IMPORT_ERRORS.items()
            if (name.startswith(prefix) if prefix else "." not in name)}


def _checked_group(group: str) -> str:
    if group not in GROUPS:
        raise ValueError(f"`group` must be one of {', '.join(GROUPS)}, got {group!r}")
    return group


def model_names(text: str) -> list[str]:
    """The zoo models named in ``text`` (comma-separated), the modules of every group loaded;
    ``ValueError`` naming the unknown ones and the known ones (the validation scripts'
    ``--models``)."""
    load_models(None)
    names = [n for n in text.split(",") if n]
    unknown = [n for n in names if n not in REGISTRY]
    if unknown:
        raise ValueError(f"unknown model(s) {', '.join(unknown)}; known: {', '.join(sorted(REGISTRY))}")
    return names


# ---------------------------------------------------------------------------------------
# helpers for model authors
# ---------------------------------------------------------------------------------------

#: The zoo's joint physics: steel on steel, the Wang-Liu law (exuclear's default law), a
#: coefficient of restitution of 0.9, no friction unless a model or the runner asks.
JOINT_DEFAULTS: dict[str, Any] = {"law": "wang-liu", "cr": 0.9, "journal_material": "steel",
                                  "bearing_material": "steel", "friction": "none"}

#: Exudyn's solver types -> exuclear's method names (:data:`exuclear.settings.METHODS`).
METHOD_OF_SOLVER = {getattr(exu.DynamicSolverType, exudyn_name): method
                    for method, (exudyn_name, _explicit, _adaptive) in METHODS.items()}


def joint_parameters(bearing_radius: float, clearance: float, length: float, **joint_options: Any) -> dict[str, Any]:
    """Keyword arguments of :func:`exuclear.CreateClearanceJoint` for a zoo joint: bearing
    radius R_B [m], radial clearance c [m] (R_J = R_B - c), bearing length L [m], the
    :data:`JOINT_DEFAULTS` overridden by ``joint_options`` (e.g. ``friction="paper"``)."""
    return {"bearing_radius": bearing_radius, "journal_radius": bearing_radius - clearance, "length": length,
            **JOINT_DEFAULTS, **joint_options}


def example_settings(end_time: float, steps: int) -> exu.SimulationSettings:
    """``exu.SimulationSettings`` with an example's end time and number of steps, silent
    (verbose 0) and without a solution file: the zoo reads sensors and probes only."""
    ss = exu.SimulationSettings()
    ss.timeIntegration.endTime = end_time
    ss.timeIntegration.numberOfSteps = max(1, int(round(steps)))
    ss.timeIntegration.verboseMode = 0
    ss.solution.file.write = False
    return ss


def rigid_body_energy(bodies: list[Any], inertias: list[Any], gravity: Any) -> Callable[[exu.MainSystem], tuple]:
    """``ZooModel.energy`` of bodies made by ``mbs.CreateRigidBody``: kinetic energy and the
    gravity potential ``-m g . r`` of each centre of mass (0 at the origin) [J], for the
    bodies' ``RigidBodyInertia`` (``com`` in the body frame) and the gravity vector [m/s^2]."""
    g = np.asarray(gravity, dtype=float)

    def energy(mbs: exu.MainSystem) -> tuple[float, float]:
        kinetic = potential = 0.0
        for body, inertia in zip(bodies, inertias):
            com = [float(x) for x in inertia.com]
            v = np.asarray(mbs.GetObjectOutputBody(body, exu.OutputVariableType.Velocity, com))
            w = np.asarray(mbs.GetObjectOutputBody(body, exu.OutputVariableType.AngularVelocityLocal, com))
            r = np.asarray(mbs.GetObjectOutputBody(body, exu.OutputVariableType.Position, com))
            kinetic += 0.5 * inertia.mass * v @ v + 0.5 * w @ np.asarray(inertia.InertiaCOM()) @ w
            potential -= inertia.mass * g @ r
        return kinetic, potential

    return energy


def straight_ancf_cable(mbs: exu.MainSystem, length: float, n_elements: int, gravity: Any,
                        **element: Any) -> tuple[list[int], list[int]]:
    """A straight cable of ``ObjectANCFCable2D`` elements along x from the origin, as Exudyn's
    examples build it with the deprecated ``GenerateStraightLineANCFCable2D`` (without its
    constraints): ``n_elements + 1`` ``NodePoint2DSlope1`` nodes (position x, y, slope (1, 0)),
    the elements with ``element``'s parameters (``massPerLength`` [kg/m], ``bendingStiffness``
    [N m^2], ...; their ``length`` is set), a ``LoadMassProportional`` of ``gravity``
    [m/s^2] on each.  Returns the node and the element numbers."""
    l_elem = length / n_elements
    nodes = [mbs.AddNode(NodePoint2DSlope1(referenceCoordinates=[k * l_elem, 0.0, 1.0, 0.0]))
             for k in range(n_elements + 1)]
    cables = [mbs.AddObject(ObjectANCFCable2D(nodeNumbers=[nodes[k], nodes[k + 1]], length=l_elem, **element))
              for k in range(n_elements)]
    for cable in cables:
        mbs.AddLoad(LoadMassProportional(markerNumber=mbs.AddMarker(MarkerBodyMass(bodyNumber=cable)),
                                         loadVector=list(gravity)))
    return nodes, cables


def scaled_end(settings: exu.SimulationSettings, end_time: float | None) -> None:
    """Shorten (or lengthen) a run to ``end_time`` [s] at the same step; None: keep."""
    if end_time is None:
        return
    ti = settings.timeIntegration
    step = ti.endTime / ti.numberOfSteps
    ti.endTime = end_time
    ti.numberOfSteps = max(1, int(round(end_time / step)))


#: ``ZooModel.probe_bound`` of a probe that is a point of the body the journal carries, in
#: a short run from rest: the journal's offset in the bearing moves that body by at most
#: c + penetration (1x), and while the journal crosses the gap before its first contact
#: the body falls without the joint's load and so misses the rotation that load gave it
#: in the ideal model; the lever times that angle is of the order of the distance the
#: joint point travelled across the gap (at most c + penetration again, 1x for a lever as
#: long as the distance from the joint to the body's centre, up to 1x more for a probe
#: twice as far): 3 in all.  Measured in the zoo: 0.14 to 0.24 at 20 ms, up to 0.84 at 50 ms.
PROBE_BOUND_CARRIED = 3.0

#: Recorded outputs per run of exuclear.simulate in the zoo: the penetration peaks come
#: from the per-step impact records, so the outputs only serve the convergence check,
#: which compares paths on this grid.
OUTPUTS_PER_RUN = 2000


def solver_settings_like(settings: exu.SimulationSettings, solver_type: exu.DynamicSolverType,
                         **changes: Any) -> exuclear.SolverSettings:
    """The :class:`exuclear.SolverSettings` of an example's settings, for ``exuclear.simulate``:
    its end time, method, spectral radius and linear solver; ``step="auto"`` (an implicit method: steps
    the joints control, at most ``end_time / 1000``; fixed-step methods: ten steps per
    contact period); exuclear's Newton tolerances (an absolute 1e-8 instead of Exudyn's 1e-10,
    because stiff contact leaves a round-off floor under the residual, see
    :data:`exuclear.settings.NEWTON_ATOL_DEFAULT`)."""
    if solver_type not in METHOD_OF_SOLVER:
        raise ValueError(f"`solver_type` {solver_type} has no exuclear method; one of {sorted(METHOD_OF_SOLVER)}")
    method = METHOD_OF_SOLVER[solver_type]
    end = settings.timeIntegration.endTime
    kw: dict[str, Any] = {"end_time": end, "method": method, "step": "auto", "output_step": end / OUTPUTS_PER_RUN}
    if not METHODS[method][1]:
        kw["spectral_radius"] = settings.timeIntegration.generalizedAlpha.spectralRadius
        sparse = settings.linearSolver.solverType == exu.LinearSolverType.EigenSparse
        kw["linear_solver"] = "sparse" if sparse else "dense"
    kw.update(changes)
    return exuclear.SolverSettings(**kw)


def joint_peaks(joint: Any) -> tuple[float, float]:
    """Largest penetration [m] and largest contact force [N] of the last run, from the
    per-step impact records (every accepted step, whatever the output interval), the
    contact still open at the end, and the penetration of the step that stopped a run at
    the joint's limit (that step is never accepted, so no record holds it)."""
    pen, force = 0.0, 0.0
    for r in joint.impacts():
        pen, force = max(pen, r.max_penetration), max(force, r.peak_force)
    s = joint.state()
    if s.in_contact:
        pen, force = max(pen, s.max_penetration), max(force, s.peak_force)
    reason = joint.failure()[0]
    if reason.startswith("penetration "):  # "penetration 4.787e-05 m exceeds the limit ..."
        try:
            pen = max(pen, float(reason.split()[1]))
        except (IndexError, ValueError):
            pass  # another wording: the records' value stands
    return pen, force


def _first_line(err: BaseException | str) -> str:
    """The first line of an error's message (its type's name if it has none)."""
    text = str(err).strip()
    return text.splitlines()[0] if text else type(err).__name__
