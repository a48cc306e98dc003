"""Graph calculations, one module per analysis family. Importing registers them."""

from . import fatigue, joints, loads, torsion  # noqa: F401
