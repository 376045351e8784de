"""What every scene's ``build(params)`` returns: the assembled Exudyn system and its handles."""
from __future__ import annotations

from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any

if TYPE_CHECKING:
    import exudyn as exu

    from exuclear import ClearanceJointHandle


@dataclass
class Scene:
    """An assembled scene (``mbs.Assemble()`` done), ready for :func:`exuclear.simulate`.

    Every scene's ``build(params)`` returns one.  Its solver settings are not part of it:
    they are the scene's ``default_settings(params)``, and a run may use others.

    Attributes
    ----------
    params : dataclass
        The parameters it was built from (the scene's ``*Params``).
    mbs : exudyn.MainSystem
        The system.
    joints : dict of str to ClearanceJointHandle
        Its clearance joints by name (slider-crank: ``"O"``, ``"A"``, ``"B"``; empty for
        an ideal mechanism).
    sensors : dict of str to int
        Sensor numbers by name, stored internally (``mbs.GetSensorStoredData``).
    nodes : dict of str to int
        Node numbers of the bodies a result is read from, by name.
    build_time : float
        Wall time of building and assembling [s].
    main_joint : str or None
        Name of the joint the scene's summary reads (:attr:`joint`).
    """

    params: Any
    mbs: exu.MainSystem
    joints: dict[str, ClearanceJointHandle]
    sensors: dict[str, int] = field(default_factory=dict)
    nodes: dict[str, int] = field(default_factory=dict)
    build_time: float = 0.0
    main_joint: str | None = None

    @property
    def joint(self) -> ClearanceJointHandle | None:
        """The joint named :attr:`main_joint`, or None where it has no clearance."""
        return self.joints.get(self.main_joint) if self.main_joint is not None else None
