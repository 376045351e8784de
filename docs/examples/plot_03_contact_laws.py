"""
The contact law library: force-penetration curves and restitution
=================================================================

A contact law is a stiffness model (the elastic force ``F_e(delta)``) and a damping model
(the dissipation that sets the coefficient of restitution ``cr``), built by
:func:`exuclear.contact_law` by name: a named law (``"wang-liu"``) or
``"STIFFNESS+DAMPING"``.  The models live in :mod:`exuclear.contact`; the laws need no
Exudyn.  Geometry and materials are the paper's journal bearing: steel on steel,
R_B = 10 mm, R_J = 9.9 mm, L = 15 mm.
"""

import matplotlib.pyplot as plt
import numpy as np
from scipy.integrate import solve_ivp

import exuclear
from exuclear.contact import DAMPING_MODELS, STIFFNESS_MODELS, restitution_of_damping

geometry = exuclear.BearingGeometry(
    journal_radius=9.9e-3, bearing_radius=10e-3, length=15e-3
)
E_star = exuclear.composite_modulus("steel", "steel")  # composite modulus [Pa]

# %%
# Stiffness models
# ----------------
# The elastic force of each stiffness model against the penetration (no damping,
# ``cr = 1``).  The cylindrical models (Johnson, Radzimovsky, ESDU, Liu, Pereira...) are
# stiffer than a Hertz point contact at small penetrations and nearly linear.
delta = np.logspace(-8, -5, 200)  # penetration [m]
fig, ax = plt.subplots(figsize=(6.5, 4.5), layout="constrained")
for name in STIFFNESS_MODELS:
    law = exuclear.contact_law(f"{name}+none", geometry, E_star, cr=1.0)
    ax.loglog(delta * 1e6, [law.elastic_force(d) for d in delta], label=name)
ax.set(
    xlabel="penetration delta [um]",
    ylabel="elastic force F_e [N]",
    title="stiffness models, steel on steel, c = 0.1 mm",
)
ax.legend(fontsize="small")
ax.grid(True, which="both", alpha=0.3)
plt.show()

# %%
# Hysteresis of one impact
# ------------------------
# The journal (0.04 kg) hits the wall at 0.3 m/s: ``m delta'' = -F_N(delta, delta',
# v0)`` until it leaves.  Each damping model, asked for ``cr = 0.5``, dissipates the energy
# inside the loop; the departure velocity over the impact velocity is the restitution it
# actually gives (the legend).  Lankarani-Nikravesh and Hunt-Crossley assume little
# dissipation and overshoot at cr = 0.5; the exact relation on the right is what
# ``carvalho-martins`` inverts.
mass, v0 = 0.04, 0.3  # [kg], [m/s]


def impact(law):
    """One impact of a free mass; returns (delta, delta_dot, force) and the restitution."""

    def rhs(t, y):
        return [y[1], -law.normal_force(y[0], y[1], v0) / mass]

    def left(t, y):  # the journal leaves the wall: delta back to 0, moving out
        return y[0] if t > 0 else 1.0

    left.terminal, left.direction = True, -1

    sol = solve_ivp(
        rhs, (0, 1e-3), [0.0, v0], events=left, rtol=1e-10, atol=1e-14, max_step=1e-7
    )
    d, dd = sol.y
    return (
        d,
        dd,
        np.array([law.normal_force(a, b, v0) for a, b in zip(d, dd)]),
        -dd[-1] / v0,
    )


fig, ax = plt.subplots(1, 2, figsize=(12, 4.5), layout="constrained")
rows = []
for damping in (
    "lankarani-nikravesh",
    "hunt-crossley",
    "flores",
    "gonthier",
    "carvalho-martins",
):
    law = exuclear.contact_law(f"johnson+{damping}", geometry, E_star, cr=0.5)
    d, dd, f, e = impact(law)
    rows.append((damping, e))
    ax[0].plot(d * 1e6, f, label=f"{damping}: e = {e:.3f}")
ax[0].set(
    xlabel="penetration delta [um]",
    ylabel="normal force F_N [N]",
    title="one impact at 0.3 m/s, Johnson stiffness, cr = 0.5",
)
ax[0].legend(fontsize="small")

# right: the restitution that the damping of F_e (1 + D delta'/v0) gives, exactly, for any
# elastic force (exuclear.contact.restitution_of_damping); the damping models of the
# literature differ in how they pick D from cr
D = np.linspace(0, 1.5, 200)
ax[1].plot(D, [restitution_of_damping(x) for x in D], "k")
ax[1].set(
    xlabel="damping factor D [-]",
    ylabel="effective restitution e [-]",
    title="restitution of F_e (1 + D delta'/v0)",
)
ax[1].grid(alpha=0.3)
plt.show()

for damping, e in rows:
    print(f"{damping:22s} asked cr = 0.5, gives e = {e:.3f}")
print("damping models:", ", ".join(DAMPING_MODELS))
