"""The zoo's group "beyond": more of Exudyn's examples, each with one revolute joint
replaced by a clearance joint: a four-bar kinematic tree closed by a joint, an ANCF cable
on a driven hub, the spatial slider-crank and a flyball governor tree.  Their modules are loaded only when the group or
one of its models is asked for (``python -m validation.exudyn_examples --group beyond``;
``_common.GROUPS``), so that the default table keeps its cost."""
