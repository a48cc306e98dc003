"""Pure NumPy calculation functions (SI units in, SI units out; no pint, no pandas)."""
