"""Build of the optional compiled kernel (exuclear._ckernel); everything else is in pyproject.toml.

The extension is optional: where it cannot be built (no compiler, no Python headers),
``pip install`` still succeeds and exuclear runs its Python kernel, saying so once at
import (exuclear/engine/kernel.py).
"""
from glob import glob

from setuptools import setup

try:
    from pybind11.setup_helpers import Pybind11Extension, build_ext
except ImportError:  # pybind11 is a build requirement; without it, install the pure-Python package
    ext_modules, cmdclass = [], {}
else:
    ext_modules = [Pybind11Extension(
        # one translation unit; the headers it includes (exuclear/_kernel/*.hpp) hold the kernel by role
        "exuclear._ckernel", ["exuclear/_kernel/bindings.cpp"],
        depends=sorted(glob("exuclear/_kernel/*.hpp")),
        cxx_std=17,
        extra_compile_args=["-ffp-contract=off"],  # no fused multiply-add: equal to the Python kernel to round-off
        optional=True,  # a failed build leaves the pure-Python package working
    )]
    cmdclass = {"build_ext": build_ext}

setup(ext_modules=ext_modules, cmdclass=cmdclass)
