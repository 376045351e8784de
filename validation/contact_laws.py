"""The contact-law library (issue 13): every stiffness model, every damping model.

Source problem: example 1 of X. Wang, G. Liu, S. Ma, R. Tong, J. Mech. Sci. Technol.
31(2) (2017) 587-597 (docs/physics.md section 6.1): a 0.04 kg steel journal starts touching a
fixed steel bearing (R_B = 10 mm, R_J = 9.9 mm, L = 15 mm) and moves into it at
0.3 m/s.  Outputs, in ``results/contact_laws/``:

- ``stiffness_curves.png`` / ``.csv``: the elastic force of every stiffness model of
  :data:`exuclear.contact.STIFFNESS_MODELS` against penetration at the paper's geometry;
- ``restitution.md`` / ``.csv``: the effective restitution (departure / impact speed) of
  every damping model of :data:`exuclear.contact.DAMPING_MODELS`, cr = 0.1, ..., 1.0, from
  an independent one-degree-of-freedom SciPy integration, next to the exact value of
  :func:`exuclear.contact.restitution_of_damping`, with the largest deviation; a few
  runs through the library's Exudyn element;
- ``impact_curves_cr*.png`` / ``pairings.md`` / ``.csv``: force-penetration and
  rate-penetration curves (the paper's Figs. 4-7) for a few pairings.

The reference is written here, independently of the library's mechanics: the journal is
a point mass on the line of the normal, ``m x'' = -F_N(x, x', v0)`` with ``x`` the
penetration, integrated by ``scipy.integrate.solve_ivp`` (DOP853, rtol 1e-11) until the
event ``x = 0``.  Only the law's force comes from the library.

Run from the repository root::

    python -m validation.contact_laws [--out DIR]
"""
from __future__ import annotations

import argparse
import math
import os
import sys
import warnings
from dataclasses import dataclass
from typing import ClassVar

import numpy as np
from scipy.integrate import solve_ivp

import exuclear
from exuclear.contact import (
    DAMPING_MODELS,
    STIFFNESS_MODELS,
    ContactLaw,
    DampingModel,
    ValidityWarning,
    contact_law,
    restitution_of_damping,
    stiffness_model,
)
from validation._tables import markdown_table, write_csv

DEFAULT_OUT = os.path.join("results", "contact_laws")

#: The paper's scene (docs/physics.md section 6.1).
GEOMETRY = exuclear.BearingGeometry(9.9e-3, 10e-3, 15e-3)
E_STAR = exuclear.composite_modulus("steel", "steel")
MASS = 0.04  # kg
V_IMPACT = 0.3  # m/s

#: cr of the restitution table (rounded so that 0.3 is 0.3, not 0.30000000000000004).
CR_GRID = tuple(round(0.1 * k, 1) for k in range(1, 11))

#: Tolerances of the reference integration: rtol 1e-11 and an absolute error of 1e-18 m
#: (1e-12 of a micrometre penetration) and 1e-13 m/s keep the departure speed to ~1e-10.
RTOL = 1e-11
ATOL = (1e-18, 1e-13)
#: Longest integration [s]: a paper impact lasts 10-60 us; the event ends it long before.
T_END = 2e-3

#: The stiffness model of the restitution table: a power law (the Hertz point contact).
TABLE_STIFFNESS = "hertz"

#: Pairings of the impact-curve figures (the paper's Figs. 4-7 style) and their cr.
PAIRINGS = ("wang-liu", "lankarani-nikravesh", "johnson+carvalho-martins", "pereira+gonthier",
            "radzimovsky+hu-guo", "esdu-78035+flores")
CURVE_CRS = (0.5, 0.9)


# -- the independent reference ----------------------------------------------------------
@dataclass(frozen=True)
class Impact:
    """One impact of the point mass: departure speed and the curves (SI units)."""

    restitution: float
    max_force: float
    max_penetration: float
    duration: float
    t: np.ndarray
    delta: np.ndarray
    rate: np.ndarray
    force: np.ndarray


def one_dof_impact(law: ContactLaw, mass: float = MASS, v_impact: float = V_IMPACT, dense: int = 0) -> Impact:
    """Integrate ``m x'' = -F_N(x, x', v_impact)`` from ``x = 0``, ``x' = v_impact`` to ``x = 0``.

    ``x`` is the penetration, ``x'`` its rate (approach positive); ``v0`` is the impact
    speed for the whole contact (docs/physics.md section 2.3, eq. (17)).  ``dense`` > 0 samples the curves at that
    many instants; else only the accepted steps are returned.
    """
    def rhs(_t, y):
        return (y[1], -law.normal_force(y[0], y[1], v_impact) / mass)

    def left(_t, y):
        return y[0]
    left.terminal, left.direction = True, -1.0

    sol = solve_ivp(rhs, (0.0, T_END), (0.0, v_impact), method="DOP853", rtol=RTOL, atol=ATOL, events=left,
                    dense_output=dense > 0)
    if sol.status != 1:
        raise RuntimeError(f"{law.name}: the reference impact did not end by {T_END} s ({sol.message})")
    t_end = float(sol.t_events[0][0])
    departure = -float(sol.y_events[0][0][1])
    t = np.linspace(0.0, t_end, dense) if dense > 0 else sol.t
    y = sol.sol(t) if dense > 0 else sol.y
    force = np.array([law.normal_force(d, r, v_impact) for d, r in zip(y[0], y[1], strict=True)])
    return Impact(departure / v_impact, float(force.max()), float(y[0].max()), t_end, t, y[0], y[1], force)


def table_law(damping: str, cr: float, stiffness: str = TABLE_STIFFNESS) -> ContactLaw:
    return contact_law(f"{stiffness}+{damping}", GEOMETRY, E_STAR, cr)


# -- stiffness curves ----------------------------------------------------------------------
def stiffness_records(deltas: np.ndarray) -> list[dict[str, object]]:
    """Elastic force of every stiffness model at each penetration [N]."""
    models = {name: stiffness_model(name, GEOMETRY, E_STAR) for name in STIFFNESS_MODELS}
    return [{"penetration_m": float(d), **{f"{n}_N": m.elastic_force(float(d)) for n, m in models.items()}}
            for d in deltas]


def plot_stiffness(records: list[dict[str, object]], path: str) -> str:
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    d = np.array([r["penetration_m"] for r in records])
    fig, axes = plt.subplots(1, 2, figsize=(11, 4.5))
    for name in STIFFNESS_MODELS:
        f = np.array([r[f"{name}_N"] for r in records])
        axes[0].plot(d * 1e6, f / 1e3, label=name)
        axes[1].loglog(d * 1e6, f, label=name)
    axes[0].set(xlabel="penetration [um]", ylabel="elastic force [kN]", title="linear scale")
    axes[1].set(xlabel="penetration [um]", ylabel="elastic force [N]", title="log-log")
    axes[0].legend(fontsize=8)
    fig.suptitle(f"stiffness models at the paper's geometry (R_B = 10 mm, c = 0.1 mm, L = 15 mm, steel, "
                 f"E* = {E_STAR / 1e9:.1f} GPa)", fontsize=10)
    fig.tight_layout()
    fig.savefig(path, dpi=120)
    plt.close(fig)
    return path


# -- restitution table ---------------------------------------------------------------------
@dataclass(frozen=True)
class RestitutionRow:
    damping: str
    cr: float
    D: float
    exact: float
    reference: float


def restitution_rows() -> list[RestitutionRow]:
    """Every damping model over :data:`CR_GRID` with the power-law stiffness; damping
    ``none`` only at cr = 1.  Plus the rejected half form of Hu-Guo, from ``D`` alone."""
    rows = []
    for name, cls in DAMPING_MODELS.items():
        for cr in (CR_GRID if cls.dissipative else (1.0,)):
            with warnings.catch_warnings():
                warnings.simplefilter("ignore", ValidityWarning)  # zhiying-qishao below 0.3: tabulated anyway
                law = table_law(name, cr)
            rows.append(RestitutionRow(name, cr, law.damping_factor, restitution_of_damping(law.damping_factor),
                                       one_dof_impact(law).restitution))
    for cr in CR_GRID:
        law = ContactLaw(stiffness_model(TABLE_STIFFNESS, GEOMETRY, E_STAR), HuGuoHalfForm(cr))
        rows.append(RestitutionRow("hu-guo (half form, rejected)", cr, law.damping_factor,
                                   restitution_of_damping(law.damping_factor), one_dof_impact(law).restitution))
    return rows


@dataclass(frozen=True)
class HuGuoHalfForm(DampingModel):
    """Hu-Guo's factor as some compilations quote it, ``3 (1 - cr) / (4 cr)``: tabulated to
    show why the library uses ``3 (1 - cr) / (2 cr)`` (see :class:`exuclear.contact.HuGuoDamping`)."""

    name: ClassVar[str] = "hu-guo-half"

    def _factor(self) -> float:
        return 3.0 * (1.0 - self.cr) / (4.0 * self.cr)


def element_runs(pairs: tuple[tuple[str, float], ...] = (("wang-liu", 0.3), ("wang-liu", 0.5), ("wang-liu", 0.9),
                                                          ("johnson+carvalho-martins", 0.5),
                                                          ("pereira+gonthier", 0.7))) -> list[dict[str, object]]:
    """The same impact through the library's Exudyn element (README's public API), for a few
    pairings and every backend the installed library offers; failures are recorded, not raised."""
    import exudyn as exu
    from exudyn.itemInterface import MarkerBodyRigid, NodeRigidBody2D, ObjectGround, ObjectRigidBody2D

    backends = tuple(getattr(exuclear, "BACKENDS", ("python",)))
    records = []
    for law_name, cr in pairs:
        ref = one_dof_impact(contact_law(law_name, GEOMETRY, E_STAR, cr), dense=4000)
        for backend in backends:
            record = {"law": law_name, "cr": cr, "backend": backend, "reference": ref.restitution,
                      "reference_max_force": ref.max_force}
            try:
                mbs = exu.SystemContainer().AddSystem()
                ground = mbs.AddObject(ObjectGround())
                c = GEOMETRY.clearance
                node = mbs.AddNode(NodeRigidBody2D(referenceCoordinates=[c, 0, 0],
                                                   initialVelocities=[V_IMPACT, 0, 0]))
                pin = mbs.AddObject(ObjectRigidBody2D(nodeNumber=node, mass=MASS,
                                                      inertia=0.5 * MASS * GEOMETRY.journal_radius**2))
                markers = [mbs.AddMarker(MarkerBodyRigid(bodyNumber=body, localPosition=[0.0, 0.0, 0.0]))
                           for body in (ground, pin)]  # bearing, journal
                handle = exuclear.AddClearanceJoint(
                    mbs, markers, journal_radius=GEOMETRY.journal_radius, bearing_radius=GEOMETRY.bearing_radius,
                    length=GEOMETRY.length, law=law_name, cr=cr, backend=backend)
                mbs.Assemble()
                sim = exuclear.simulate(mbs, exuclear.SolverSettings(
                    end_time=2e-4, method="dopri5", step=1e-7, rtol=1e-10, atol=1e-14, output_step=1e-8))
                v = mbs.GetNodeOutput(node, exu.OutputVariableType.Velocity)
                record.update(element=-float(v[0]) / V_IMPACT, element_max_force=float(
                    np.max(handle.outputs()["normal_force"])), success=bool(sim.success), message=sim.message)
            except Exception as err:  # noqa: BLE001 - the element's API may change under this study
                record.update(element=math.nan, element_max_force=math.nan, success=False,
                              message=f"{type(err).__name__}: {err}")
            record["difference"] = record["element"] - ref.restitution
            record["force_difference"] = record["element_max_force"] / ref.max_force - 1.0
            records.append(record)
    return records


# -- impact curves of a few pairings ---------------------------------------------------------
def pairing_impacts() -> dict[tuple[str, float], Impact]:
    return {(name, cr): one_dof_impact(contact_law(name, GEOMETRY, E_STAR, cr), dense=400)
            for cr in CURVE_CRS for name in PAIRINGS}


def plot_pairings(impacts: dict[tuple[str, float], Impact], directory: str) -> list[str]:
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    paths = []
    for cr in CURVE_CRS:
        fig, (a, b) = plt.subplots(1, 2, figsize=(11, 4.5))
        for (name, c), imp in impacts.items():
            if c != cr:
                continue
            a.plot(imp.delta * 1e6, imp.force, label=name)
            b.plot(imp.delta * 1e6, imp.rate, label=name)
        a.set(xlabel="penetration [um]", ylabel="contact force [N]", title="force - penetration (paper Figs. 4-7 a)")
        b.set(xlabel="penetration [um]", ylabel="penetration rate [m/s]", title="rate - penetration (Figs. 4-7 b)")
        a.legend(fontsize=8)
        fig.suptitle(f"journal-bearing impact, 0.3 m/s, cr = {cr:g}: pairings of stiffness and damping", fontsize=10)
        fig.tight_layout()
        path = os.path.join(directory, f"impact_curves_cr{cr:g}.png")
        fig.savefig(path, dpi=120)
        plt.close(fig)
        paths.append(path)
    return paths


# -- report ----------------------------------------------------------------------------------
def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(prog="python -m validation.contact_laws", description=__doc__.split("\n")[0])
    ap.add_argument("--out", default=DEFAULT_OUT, help="output directory (default %(default)s)")
    ap.add_argument("--no-element", action="store_true", help="skip the runs through the Exudyn element")
    args = ap.parse_args(argv)
    os.makedirs(args.out, exist_ok=True)
    written = []

    curves = stiffness_records(np.linspace(0.0, 5e-6, 201)[1:])
    written += [write_csv(os.path.join(args.out, "stiffness_curves.csv"), curves),
                plot_stiffness(curves, os.path.join(args.out, "stiffness_curves.png"))]

    rows = restitution_rows()
    written.append(write_csv(os.path.join(args.out, "restitution.csv"),
                             [{"damping": r.damping, "cr": r.cr, "D": r.D, "exact": r.exact,
                               "one_dof": r.reference, "one_dof_minus_exact": r.reference - r.exact} for r in rows]))
    names = list(dict.fromkeys(r.damping for r in rows))
    by = {(r.damping, r.cr): r for r in rows}
    table = markdown_table(["damping \\ cr", *(f"{c:g}" for c in CR_GRID)],
                           [[n, *(f"{by[(n, c)].reference:.4f}" if (n, c) in by else "-" for c in CR_GRID)]
                            for n in names])
    deviation = max(abs(r.reference - r.exact) for r in rows)
    worst = max(rows, key=lambda r: abs(r.reference - r.exact))
    lines = ["# Effective restitution of the damping models",
             "",
             f"Departure / impact speed of the paper's journal impact (0.04 kg, 0.3 m/s, steel, R_B = 10 mm, "
             f"R_J = 9.9 mm, L = 15 mm), stiffness `{TABLE_STIFFNESS}` (a power law), one-degree-of-freedom "
             f"SciPy integration (DOP853, rtol {RTOL:g}, event at penetration 0):", "", table, "",
             f"Largest deviation from the exact relation D (1 + e) = ln(1 + D) - ln(1 - D e): "
             f"{deviation:.2e} ({worst.damping}, cr = {worst.cr:g}).", ""]
    if not args.no_element:
        element = element_runs()
        written.append(write_csv(os.path.join(args.out, "element.csv"), element))
        lines += ["## Through the Exudyn element", "",
                  "Restitution and peak force of the same impact through `exuclear.AddClearanceJoint` / "
                  "`exuclear.simulate` (DOPRI5, steps <= 1e-7 s, rtol 1e-10; peak force sampled every 1e-8 s) "
                  "against the one-DOF reference (peak force sampled at 4000 instants). The restitution does not "
                  "depend on the stiffness model, the peak force does.", "",
                  markdown_table(["law", "cr", "backend", "e one-DOF", "e element", "difference",
                                  "peak force one-DOF [N]", "element / one-DOF - 1", "status"],
                                 [[e["law"], e["cr"], e["backend"], f"{e['reference']:.6f}", f"{e['element']:.6f}",
                                   f"{e['difference']:+.1e}", f"{e['reference_max_force']:.1f}",
                                   f"{e['force_difference']:+.1e}", "ok" if e["success"] else e["message"][:80]]
                                  for e in element]), ""]
    with open(os.path.join(args.out, "restitution.md"), "w", encoding="utf-8") as f:
        f.write("\n".join(lines))
    written.append(os.path.join(args.out, "restitution.md"))

    impacts = pairing_impacts()
    records = [{"law": n, "cr": c, "departure_velocity": i.restitution * V_IMPACT, "restitution": i.restitution,
                "max_force_N": i.max_force, "max_penetration_m": i.max_penetration, "duration_s": i.duration}
               for (n, c), i in impacts.items()]
    written.append(write_csv(os.path.join(args.out, "pairings.csv"), records))
    with open(os.path.join(args.out, "pairings.md"), "w", encoding="utf-8") as f:
        f.write(markdown_table(["law", "cr", "departure [m/s]", "max force [N]", "max penetration [um]",
                                "duration [us]"],
                               [[r["law"], r["cr"], f"{r['departure_velocity']:.4f}", f"{r['max_force_N']:.1f}",
                                 f"{r['max_penetration_m'] * 1e6:.4f}", f"{r['duration_s'] * 1e6:.2f}"]
                                for r in records]) + "\n")
    written.append(os.path.join(args.out, "pairings.md"))
    written += plot_pairings(impacts, args.out)
    for path in written:
        print(f"wrote {path}")
    print(f"largest deviation of the one-DOF restitution from the exact relation: {deviation:.2e}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
