"""A rigid shaft in two misaligned clearance bearings: tilt, edge loads and the force along each bearing.

Scene of exuclear (docs/physics.md section 9.5); no published scene with numbers
was reached, so it is stated here in full.  A steel shaft (radius R_J, length 0.12 m)
runs in two fixed bearings A and B, 0.1 m apart, each of the paper's journal-bearing
geometry (R_B = 10 mm, c = 0.1 mm, L = 15 mm).  Bearing B sits ``misalignment`` higher than
A (default 0.3 mm, three clearances), so the shaft must tilt in both bearings, and it
spins at ``speed``.  Gravity pulls it down at t = 0 from the straight line through both
bearing centres (no contact there: each edge is 20 um from its wall)::

         y
         ^            bearing B (raised by the misalignment)
         |   A                 ____
        _|__               ===|____|===
    ===|____|=====shaft===/
        -+--------------------------------> z
         0                0.1 m

The shaft's axial motion is held at A (``constrainAxial``), so the run is implicit
(generalized-alpha, impact-aware steps).  Outputs: the shaft's tilt in each bearing, the
edge loads (first and last slice) and the normal force per unit length along each bearing.

    python -m exuclear.models.misaligned_shaft --plot out/

``--help`` lists the options: one per :class:`ShaftParams` field.
"""
from __future__ import annotations

import argparse
import sys
import time
from dataclasses import field, replace

import exudyn as exu
import numpy as np
from exudyn.itemInterface import MarkerBodyRigid
from exudyn.rigidBodyUtilities import RotationMatrixX
from exudyn.utilities import InertiaCylinder

import exuclear
from exuclear import SolverSettings

from ._cli import SceneRun, run_main, scene_parser
from ._joint_fields import joint_field, joint_fields, scene_joint, scene_params
from ._params import changes_from_args, check_fields, count, param, positive, real
from .scene import Scene


@scene_params
class ShaftParams:
    """The scene's parameters (SI units); :meth:`default` is the scene of the module docstring."""

    # both bearings have this geometry, law and friction
    _joint_fields = joint_fields("journal_radius", "bearing_radius", "length", second_option=False, help={
        "bearing_radius": "bearing radius R_B of both bearings [m]", "length": "bearing length L of each bearing [m]"})
    shaft_length: float = field(metadata=param("shaft length [m]", positive))
    spacing: float = field(metadata=param("distance between the bearings' centres [m]", positive))
    misalignment: float = field(metadata=param("height of bearing B above A [m]", real))
    speed: float = field(metadata=param("shaft speed [rad/s]", real))
    _more_joint_fields = joint_fields("law", "cr", "friction")
    slices: int = field(metadata=param("slices per bearing", count))
    end_time: float = field(metadata=param("simulated time [s]", positive))
    backend: str = joint_field("backend")

    def __post_init__(self) -> None:
        check_fields(self)

    @classmethod
    def default(cls, **changes) -> ShaftParams:
        """The scene of the module docstring: the paper's journal-bearing geometry, 0.3 mm
        misalignment, 50 rad/s, Wang-Liu with cr 0.7, Coulomb friction 0.1, 20 slices, 0.05 s."""
        base = cls(journal_radius=9.9e-3, bearing_radius=10e-3, length=15e-3, shaft_length=0.12, spacing=0.1,
                   misalignment=0.3e-3, speed=50.0, law="wang-liu", cr=0.7, friction="coulomb:0.1", slices=20,
                   end_time=0.05)
        return replace(base, **changes)


def build(params: ShaftParams) -> Scene:
    """The shaft and its two bearings: joints ``"A"`` and ``"B"``, the shaft's node
    ``nodes["shaft"]``."""
    start = time.perf_counter()
    mbs = exu.SystemContainer().AddSystem()
    ground = mbs.CreateGround()
    tilt = np.arctan2(params.misalignment, params.spacing)  # the line through both bearing centres
    shaft = mbs.CreateRigidBody(
        inertia=InertiaCylinder(7800.0, params.shaft_length, params.journal_radius, 2),
        referencePosition=[0.0, 0.0, params.spacing / 2], gravity=[0.0, -9.81, 0.0],
        initialDisplacement=[0.0, params.misalignment / 2, 0.0], initialRotationMatrix=RotationMatrixX(-tilt),
        initialAngularVelocity=(RotationMatrixX(-tilt) @ [0.0, 0.0, params.speed]).tolist(),
        nodeType=exu.NodeType.RotationRxyz, returnDict=True)
    joint = scene_joint(params)  # the same physics in both bearings
    joints = {}
    for name, z, y in (("A", 0.0, 0.0), ("B", params.spacing, params.misalignment)):
        # bearing centre at (0, y, z); the journal centre on the shaft's axis (the shaft's
        # reference configuration is parallel to the bearings, as the joint takes its axis from it)
        mb = mbs.AddMarker(MarkerBodyRigid(bodyNumber=ground, localPosition=[0.0, y, z]))
        mj = mbs.AddMarker(MarkerBodyRigid(bodyNumber=shaft["bodyNumber"], localPosition=[0.0, 0.0, z - params.spacing / 2]))
        joints[name] = exuclear.AddClearanceJoint(mbs, [mb, mj], name=name, constrainAxial=name == "A", joint=joint,
                                                  backend=params.backend, slices=params.slices, show=False)
    mbs.Assemble()
    return Scene(params, mbs, joints, nodes={"shaft": shaft["nodeNumber"]}, build_time=time.perf_counter() - start)


def default_settings(params: ShaftParams) -> SolverSettings:
    """Generalized-alpha with impact-aware steps (the axial constraint needs an implicit method)."""
    return SolverSettings(end_time=params.end_time, method="generalized-alpha", step=2e-5, impact_step=1e-6,
                          output_step=1e-4)


def run(params: ShaftParams, settings: SolverSettings | None = None) -> tuple[exuclear.SimulationResult, dict]:
    """Simulate; returns the result and per bearing its outputs (``"A"``, ``"B"``) and
    the slice positions ``"z"``."""
    scene = build(params)
    result = exuclear.simulate(scene.mbs, settings or default_settings(params))
    out = {name: h.outputs() for name, h in scene.joints.items()}
    out["z"] = scene.joints["A"].slice_positions
    return result, out


def summary(params: ShaftParams, out: dict) -> dict[str, float]:
    """Tilt and loads at the end of the run, per bearing (SI units)."""
    width = params.length / params.slices
    s = {}
    for name in ("A", "B"):
        o = out[name]
        f = o["normal_force"][-1]
        s[f"{name}_tilt"] = float(np.hypot(o["tilt_x"][-1], o["tilt_y"][-1]))
        s[f"{name}_force"] = float(f.sum())
        s[f"{name}_edge_force_per_length"] = float(max(f[0], f[-1]) / width)
        s[f"{name}_mean_force_per_length"] = float(f.sum() / params.length)
        s[f"{name}_slices_in_contact"] = float((o["in_contact"][-1] > 0).sum())
    return s


def plot(params: ShaftParams, out: dict, directory: str) -> list[str]:
    """Three figures: tilt over time, edge loads over time, force per length along each bearing."""
    import os

    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    os.makedirs(directory, exist_ok=True)
    width = params.length / params.slices
    paths = []
    fig, ax = plt.subplots(figsize=(7, 4))
    for name in ("A", "B"):
        o = out[name]
        ax.plot(o["time"] * 1e3, np.hypot(o["tilt_x"], o["tilt_y"]) * 1e3, label=f"bearing {name}")
    ax.axhline(2 * (params.bearing_radius - params.journal_radius) / params.length * 1e3, color="grey", ls=":",
               label="2c / L: both edges touch at zero penetration")
    ax.set(xlabel="time [ms]", ylabel="tilt of the shaft in the bearing [mrad]", title="Tilt")
    ax.legend()
    paths.append(os.path.join(directory, "misaligned_shaft_tilt.png"))
    fig.savefig(paths[-1], dpi=120, bbox_inches="tight")
    fig, ax = plt.subplots(figsize=(7, 4))
    for name, style in (("A", "-"), ("B", "--")):
        f = out[name]["normal_force"] / width
        t = out[name]["time"] * 1e3
        ax.plot(t, f[:, 0] / 1e3, style, label=f"{name}, edge z = -L/2")
        ax.plot(t, f[:, -1] / 1e3, style, label=f"{name}, edge z = +L/2")
    ax.set(xlabel="time [ms]", ylabel="normal force per length at the edge slice [N/mm]", title="Edge loads")
    ax.legend()
    paths.append(os.path.join(directory, "misaligned_shaft_edge_loads.png"))
    fig.savefig(paths[-1], dpi=120, bbox_inches="tight")
    fig, ax = plt.subplots(figsize=(7, 4))
    for name in ("A", "B"):
        f = out[name]["normal_force"]
        late = out[name]["time"] >= 0.5 * out[name]["time"][-1]
        ax.plot(out["z"] * 1e3, f[late].mean(axis=0) / width / 1e3, "o-", label=f"bearing {name}, mean of 2nd half")
        ax.plot(out["z"] * 1e3, f[-1] / width / 1e3, "x:", label=f"bearing {name}, end")
    ax.set(xlabel="axial position in the bearing z [mm]", ylabel="normal force per length [N/mm]",
           title="Force distribution along the bearing")
    ax.legend()
    paths.append(os.path.join(directory, "misaligned_shaft_force_distribution.png"))
    fig.savefig(paths[-1], dpi=120, bbox_inches="tight")
    plt.close("all")
    return paths


def _parser() -> argparse.ArgumentParser:
    """The command line: one option per :class:`ShaftParams` field; defaults
    :meth:`ShaftParams.default`."""
    ap = scene_parser("misaligned_shaft", __doc__, ShaftParams.default())
    ap.add_argument("--plot", metavar="DIR", help="write the tilt, edge-load and force-distribution figures to DIR")
    return ap


class _ShaftRun(SceneRun):
    """The command line's run (:func:`~exuclear.models._cli.run_main`): the scene of the module
    docstring with the options' changes, the tilt and loads per bearing, and its figures."""

    def prepare(self, law: str, cr: float) -> None:
        self.params = ShaftParams.default(**changes_from_args(self.args, ShaftParams), law=law, cr=cr)

    def simulate(self) -> None:
        self.result, self.out = run(self.params)

    def summary(self) -> None:
        params, result = self.params, self.result
        s = summary(params, self.out)
        print(f"misaligned shaft: {params.misalignment * 1e3:g} mm misalignment, {params.speed:g} rad/s, "
              f"{params.slices} slices, {result.steps} steps, {result.wall_time:.2f} s")
        for name in ("A", "B"):
            print(f"  bearing {name}: tilt {s[f'{name}_tilt'] * 1e3:.3f} mrad, force {s[f'{name}_force']:.2f} N, "
                  f"edge {s[f'{name}_edge_force_per_length'] / 1e3:.3f} N/mm vs mean "
                  f"{s[f'{name}_mean_force_per_length'] / 1e3:.3f} N/mm, {s[f'{name}_slices_in_contact']:.0f} slices in contact")

    def plots(self, directory: str) -> list[str]:
        return plot(self.params, self.out, directory)


def main(argv: list[str] | None = None) -> int:
    return run_main(argv, _parser(), _ShaftRun)


if __name__ == "__main__":
    sys.exit(main())
