"""Numerical kernels (numba; arrays in, arrays out)."""
from .memory import keep_freed_memory

KEPT_FREED_MEMORY = keep_freed_memory()
