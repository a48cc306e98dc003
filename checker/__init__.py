"""checker: an open design-rule checker for engine crank trains."""

__version__ = "0.1.0"
