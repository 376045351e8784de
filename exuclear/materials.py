"""Elastic materials of journal and bearing, and the composite modulus.

Source: the paper (Wang, Liu, Ma, Tong, J. Mech. Sci. Technol. 31(2) 2017), Table 3
for the moduli and eq. (9) for the composite modulus; ``docs/physics.md`` eq. (10) and section 6.2.
"""
from __future__ import annotations

from dataclasses import dataclass

from .checks import check_choice, check_open, check_positive, warn_unit

#: Young's moduli below this are legal but softer than engineering polymers (~1e9 Pa):
#: a warning asks whether the modulus was given in MPa or GPa instead of Pa.
E_WARN_BELOW = 1e8


@dataclass(frozen=True)
class Material:
    """An isotropic linear-elastic material.

    Parameters
    ----------
    E : float
        Young's modulus [Pa], > 0.
    nu : float
        Poisson's ratio [-], in (-1, 0.5).
    name : str
        Label used in tables and plots.
    """

    E: float
    nu: float
    name: str = "user"

    def __post_init__(self) -> None:
        object.__setattr__(self, "E", check_positive("E", self.E))
        object.__setattr__(self, "nu", check_open("nu", self.nu, -1.0, 0.5))
        if self.E < E_WARN_BELOW:
            warn_unit(f"Young's modulus E = {self.E:.3g} Pa of {self.name!r} is below {E_WARN_BELOW:.0e} Pa; "
                      "moduli are in Pa: was it given in MPa or GPa?")

    @property
    def compliance(self) -> float:
        """``(1 - nu^2) / E`` [1/Pa], one material's share of eq. (9)."""
        return (1.0 - self.nu**2) / self.E


#: The materials of the paper (its Table 3, restated in docs/physics.md section 6.2).
MATERIALS: dict[str, Material] = {
    "steel": Material(207e9, 0.30, "steel"),
    "ductile-iron": Material(173e9, 0.30, "ductile-iron"),
    "copper": Material(106e9, 0.324, "copper"),
    "aluminium": Material(69e9, 0.33, "aluminium"),
}


def material(spec: str | Material) -> Material:
    """Return a :class:`Material` from a name of :data:`MATERIALS` or a Material."""
    if isinstance(spec, Material):
        return spec
    return MATERIALS[check_choice("material", spec, MATERIALS)]


def composite_modulus(journal: str | Material, bearing: str | Material) -> float:
    """Composite modulus ``E* = 1 / ((1 - nu1^2)/E1 + (1 - nu2^2)/E2)`` [Pa], eq. (9)."""
    return 1.0 / (material(journal).compliance + material(bearing).compliance)
