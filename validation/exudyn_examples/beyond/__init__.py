"""The zoo's group "beyond": more of Exudyn's examples, each with one revolute joint
replaced by a clearance joint (a kinematic tree closed by a joint, an ANCF cable on a
driven hub, the spatial slider-crank).  Their modules are loaded only when the group or
one of its models is asked for (``python -m validation.exudyn_examples --group beyond``;
``_common.GROUPS``), so that the default table keeps its cost."""
