"""The worn-in journal: the joint's wear against its closed-form law (docs/physics.md
section 11.6, :mod:`exuclear.wear.analytic`).

A journal (a planar rigid body, radius ``r = R - c``) turns at a constant speed, held by a
velocity constraint on its angle, in a fixed bearing and under a constant force ``F``
along ``-x``; the bearing wears.  Once the imprint is deeper than the elastic approach,
its depth under the load follows eq. (83), and with Coulomb friction ``mu`` its deepest
point turns by ``atan(mu)`` and its growth slows by ``sqrt(1 + mu^2)`` (eq. (84)).

Outputs, in ``results/wear/``: ``worn_in_journal.png`` (depth against slip, the element
and the law; the worn profile), ``worn_in_journal.md`` (the numbers).  Run from the
repository root::

    python -m validation.wear.worn_in_journal [--out DIR] [--backend python|compiled]
"""
from __future__ import annotations

import argparse
import math
import os
import time
from dataclasses import dataclass

import exudyn as exu
import numpy as np
from exudyn.itemInterface import (
    CoordinateConstraint,
    Force,
    MarkerBodyRigid,
    MarkerNodeCoordinate,
    NodePointGround,
    NodeRigidBody2D,
    ObjectGround,
    ObjectRigidBody2D,
)

import exuclear
from exuclear.wear import analytic
from validation._tables import markdown_table

DEFAULT_OUT = os.path.join("results", "wear")

#: The scene: the paper's bearing (R = 10 mm, c = 0.1 mm, L = 15 mm), steel, 500 N, 100 rad/s.
RADIUS, CLEARANCE, LENGTH = 10e-3, 0.1e-3, 15e-3
FORCE, SPIN = 500.0, 100.0
#: An accelerated wear coefficient [1/Pa]: tens of micrometres in a fraction of a second.
COEFFICIENT = 1e-10


@dataclass(frozen=True)
class Run:
    """One run: its profiles, the slip at the contact [m], the last contact state and its wall time [s]."""

    profile: exuclear.wear.profile.WearProfile
    slip: float
    state: object
    wall_time: float
    handle: object


def build(wear: exuclear.Wear | None, *, friction: str = "none", backend: str = "python", spin: float = SPIN,
          force: float = FORCE, velocity: float = 0.0, hold_spin: bool = True,
          lubrication: exuclear.Lubrication | None = None, start: float = CLEARANCE,
          slices: int | None = None) -> tuple:
    """The worn-in journal's model, not yet assembled: the journal at ``(-start, 0)`` (by
    default against the wall), moving along -x at ``velocity`` [m/s], turning at ``spin`` [rad/s] (held there
    by a velocity constraint on its angle where ``hold_spin``), pressed along -x by ``force``
    [N], in a joint with ``wear`` (None: none) and ``lubrication`` (None: dry), planar or of
    ``slices`` slices (the planar body keeps the journal's axis parallel to the bearing's: an
    aligned spatial joint).  Returns ``(mbs, handle, node)``."""
    mbs = exu.SystemContainer().AddSystem()
    ground = mbs.AddObject(ObjectGround())
    r_j = RADIUS - CLEARANCE
    node = mbs.AddNode(NodeRigidBody2D(referenceCoordinates=[-start, 0.0, 0.0],
                                       initialVelocities=[-velocity, 0.0, spin]))
    body = mbs.AddObject(ObjectRigidBody2D(nodeNumber=node, mass=1.0, inertia=0.5 * r_j**2))
    m_body, m_ground = mbs.AddMarker(MarkerBodyRigid(bodyNumber=body)), mbs.AddMarker(MarkerBodyRigid(bodyNumber=ground))
    mbs.AddLoad(Force(markerNumber=m_body, loadVector=[-force, 0.0, 0.0]))
    if hold_spin:
        m_angle = mbs.AddMarker(MarkerNodeCoordinate(nodeNumber=node, coordinate=2))
        m_fixed = mbs.AddMarker(MarkerNodeCoordinate(nodeNumber=mbs.AddNode(NodePointGround()), coordinate=0))
        mbs.AddObject(CoordinateConstraint(markerNumbers=[m_fixed, m_angle], offset=spin, velocityLevel=True))
    handle = exuclear.AddClearanceJoint(
        mbs, [m_ground, m_body], journal_radius=r_j, bearing_radius=RADIUS, length=LENGTH,
        law="lankarani-nikravesh", cr=0.5, friction=friction, backend=backend, show=False, wear=wear,
        lubrication=lubrication, slices=slices)
    return mbs, handle, node


def settings(end_time: float, step: float, adaptive: bool = True) -> exu.SimulationSettings:
    """Exudyn's generalized-alpha over ``end_time`` [s] with steps of at most ``step`` [s]."""
    s = exu.SimulationSettings()
    s.timeIntegration.numberOfSteps = max(1, round(end_time / step))
    s.timeIntegration.endTime = end_time
    s.timeIntegration.adaptiveStep = adaptive
    s.solution.file.write = False
    return s


def run(end_time: float, *, coefficient: float = COEFFICIENT, mu: float = 0.0, nodes: int = 720,
        surface: str = "bearing", pressure: str = "winkler", backend: str = "python", step: float = 1e-4,
        spin: float = SPIN, force: float = FORCE, adaptive: bool = True, wear: exuclear.Wear | None = None,
        worn: bool = True) -> Run:
    """The worn-in journal over ``end_time`` [s] with steps of at most ``step`` [s]; ``wear``
    replaces the one of ``coefficient``, ``surface``, ``nodes`` and ``pressure``; ``worn``
    False: the same joint without wear (its ``profile`` None)."""
    if wear is None and worn:
        wear = exuclear.Wear(coefficient=coefficient, surface=surface, nodes=nodes, pressure=pressure)
    mbs, handle, _ = build(wear, friction="none" if mu == 0.0 else f"coulomb:{mu}", backend=backend, spin=spin,
                           force=force)
    mbs.Assemble()
    start = time.perf_counter()
    mbs.SolveDynamic(settings(end_time, step, adaptive))
    wall = time.perf_counter() - start
    return Run(handle.wear_profile() if worn else None, spin * (RADIUS - CLEARANCE) * end_time, handle.state(), wall,
               handle)


def law_depth(slip: float, coefficient: float = COEFFICIENT, mu: float = 0.0, force: float = FORCE) -> float:
    """eq. (83)'s depth [m] after ``slip`` [m] for this scene."""
    return analytic.depth_after_slip(slip, force, coefficient, RADIUS - CLEARANCE, CLEARANCE, LENGTH, mu)


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(prog="python -m validation.wear.worn_in_journal", description=__doc__.split("\n\n")[0])
    ap.add_argument("--out", default=DEFAULT_OUT, help="output directory (default %(default)s)")
    ap.add_argument("--backend", default="python", choices=("python", "compiled"), help="the joint's kernel")
    args = ap.parse_args(argv)
    os.makedirs(args.out, exist_ok=True)
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    rows, series = [], {}
    for mu in (0.0, 0.2):
        times = (0.025, 0.05, 0.1, 0.2, 0.4)
        depths, slips = [], []
        for end in times:
            r = run(end, mu=mu, backend=args.backend)
            depth, angle = r.profile.deepest()
            expected = law_depth(r.slip, mu=mu)
            rows.append([f"{mu:g}", f"{r.slip:.4g}", f"{depth * 1e6:.3f}", f"{expected * 1e6:.3f}",
                         f"{(depth / expected - 1.0) * 100:+.2f}", f"{math.degrees(angle) - 180.0:+.1f}",
                         f"{-math.degrees(math.atan(mu)):+.1f}" if mu else "0", f"{r.wall_time:.2f}"])
            depths.append(depth)
            slips.append(r.slip)
        series[mu] = (np.array(slips), np.array(depths), r.profile)
        print(f"mu = {mu:g}: done")
    fig, (ax, ax_p) = plt.subplots(1, 2, figsize=(10, 4.2))
    s_law = np.linspace(1e-4, max(series[0.0][0]), 60)
    for (mu, (slips, depths, _)), color in zip(series.items(), ("C0", "C3")):
        ax.plot(s_law, [law_depth(x, mu=mu) * 1e6 for x in s_law], "-", color=color, lw=1,
                label=f"eq. (83)-(84), mu = {mu:g}")
        ax.plot(slips, depths * 1e6, "o", color=color, mfc="none", label=f"exuclear, mu = {mu:g}")
    early = [analytic.early_depth(x, FORCE, COEFFICIENT, RADIUS - CLEARANCE, CLEARANCE, LENGTH) * 1e6 for x in s_law]
    ax.plot(s_law, early, "k:", lw=1, label="early law (d0 << c)")
    ax.set_xlabel("slip s [m]")
    ax.set_ylabel("depth under the load d0 [um]")
    ax.legend(fontsize=8)
    ax.grid(alpha=0.3)
    profile = series[0.0][2]
    ax_p.plot(np.degrees(profile.theta), profile.bearing * 1e6, "C0", label="mu = 0")
    ax_p.plot(np.degrees(series[0.2][2].theta), series[0.2][2].bearing * 1e6, "C3", label="mu = 0.2")
    ax_p.set_title(f"the worn bearing after s = {series[0.0][0][-1]:.3g} m of slip", fontsize=10)
    ax_p.set_xlim(90, 270)
    ax_p.set_xlabel("angle in the joint frame [deg] (load at 180)")
    ax_p.set_ylabel("bearing depth [um]")
    ax_p.legend(fontsize=8)
    ax_p.grid(alpha=0.3)
    fig.tight_layout()
    png = os.path.join(args.out, "worn_in_journal.png")
    fig.savefig(png, dpi=130)
    header = ["mu", "slip [m]", "depth [um]", "eq. (83) [um]", "error [%]", "deepest from load [deg]",
              "-atan(mu) [deg]", "wall [s]"]
    md = os.path.join(args.out, "worn_in_journal.md")
    with open(md, "w") as f:
        f.write("# The worn-in journal against eq. (83)\n\n" + markdown_table(header, rows) + "\n")
    print(markdown_table(header, rows))
    print(f"wrote {png}\nwrote {md}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
