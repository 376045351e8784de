"""Validation: scripts that compute exuclear's results against sources and references and
write the figures and tables a person reads (to ``results/``).  Each names its source
problem at the top and runs from the repository root as ``python -m validation.NAME``.

The paper's scenes and the reference
    ``journal_bearing`` (the paper's example 1), ``slider_crank/`` (its example 2, a
    package by role), ``reference/`` (the independent SciPy solver and the Reynolds
    solver), ``cross_check/`` (the library against that reference), ``hard_cases/`` (the
    joint at the edges of its use), ``contact_laws``, ``peer_contact`` (against Exudyn's
    own contact element), ``scaled_defaults``.
The lubricated joint
    ``film_models`` (the film laws against the Reynolds reference),
    ``lubricated_slider_crank``.
Other people's models and input
    ``exudyn_examples/`` (the zoo: Exudyn's examples with one clearance joint),
    ``bad_input``.
Cost, timing and accuracy at the user's steps
    ``cost/``: one command, ``python -m validation.cost NAME``, for the benchmarks, the
    work-precision study and the cost scripts (``python -m validation.cost`` lists them).

Shared: ``_cli`` (command-line options) and ``_tables`` (Markdown tables, CSV files,
report templates).
"""
