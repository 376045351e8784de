"""Nonlinear dynamics of driven mechanisms: Poincare sections, the largest Lyapunov
exponent, the 0-1 test for chaos, the verdict periodic / quasi-periodic / chaotic, and
orbit (bifurcation) diagrams on the study runner."""
from .chaos import Classification, ZeroOneResult, classify, period_of, test01
from .diagram import orbit_diagram
from .flow import Driven, LyapunovResult, SectionRun, lyapunov, run_sections
from .sections import crossings, stroboscopic

__all__ = ["stroboscopic", "crossings", "test01", "ZeroOneResult", "classify", "Classification", "period_of",
           "orbit_diagram", "Driven", "run_sections", "SectionRun", "lyapunov", "LyapunovResult"]
