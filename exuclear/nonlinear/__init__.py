"""Nonlinear dynamics of driven mechanisms: Poincare sections, the largest Lyapunov
exponent, the 0-1 test for chaos, the verdict periodic / quasi-periodic / chaotic, and
orbit (bifurcation) diagrams on the study runner (docs/guide/nonlinear.md; the algorithms
in docs/physics.md section 12).

One role per module: :mod:`.sections` (sections of recorded signals) and :mod:`.chaos`
(the 0-1 test, the verdict) need no exudyn; :mod:`.flow` runs a :class:`Driven` model,
records its section and, with a second copy in the same system, its exponent;
:mod:`.diagram` (orbit diagrams), :mod:`.cli` (``exuclear bifurcation``) and the opt-in
:mod:`.plot` (matplotlib, imported by whoever plots)."""
from .chaos import Classification, ZeroOneResult, classify, period_of, test01
from .diagram import orbit_diagram
from .flow import Driven, LyapunovResult, SectionRun, exponent_of, lyapunov, run_sections
from .sections import crossings, stroboscopic

__all__ = ["stroboscopic", "crossings", "test01", "ZeroOneResult", "classify", "Classification", "period_of",
           "orbit_diagram", "Driven", "run_sections", "SectionRun", "exponent_of", "lyapunov",
           "LyapunovResult"]
