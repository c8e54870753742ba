"""adaptobs: adaptive observers, recursive estimators of the state and the
unknown parameters of a dynamic system from its inputs and outputs.

The classes and functions are the C++ library's (``include/adaptobs``) with
run-time sizes and double precision. Arguments are NumPy arrays: a float64
array of any layout is read in place; other input is converted once to float64.
Bad configuration raises :class:`ConfigurationError` (a ``ValueError``) naming
the argument; a rejected sample is a returned :class:`UpdateStatus`, never an
exception, and leaves the observer exactly as it was.
"""

from . import _core
from ._core import *  # noqa: F403  (the public names are the extension module's)

__version__ = "0.1.0"

__all__ = sorted(name for name in dir(_core) if not name.startswith("_"))
