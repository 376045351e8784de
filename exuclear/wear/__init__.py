"""Wear of the clearance joint: the local Archard law with the worn profiles fed back into
the contact (docs/physics.md section 11).

- :class:`Wear` says how a joint wears (``wear=`` of :func:`exuclear.make_joint`,
  :func:`exuclear.CreateClearanceJoint`, :func:`exuclear.AddClearanceJoint`);
- a run's profiles come back as a :class:`WearProfile`
  (``handle.wear_profile()``);
- :func:`predict_wear` extrapolates the wear of one cycle over many;
- :mod:`.surface` is the contact of the worn surfaces and one step's wear, :mod:`.analytic`
  the worn-in journal's closed-form law that checks it.
"""
from .cycles import DIVERGENCE_BOUND, SAFETY_DEFAULT, WearPrediction, predict_wear
from .law import COEFFICIENT_WARN_ABOVE, NODES_DEFAULT, PRESSURES, SURFACES, Wear
from .profile import WearProfile

__all__ = ["Wear", "WearProfile", "predict_wear", "WearPrediction", "SURFACES", "PRESSURES", "NODES_DEFAULT",
           "COEFFICIENT_WARN_ABOVE", "DIVERGENCE_BOUND", "SAFETY_DEFAULT"]
