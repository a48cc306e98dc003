"""Graph calculations, one module per analysis family. Importing registers them."""

from . import fatigue, joints, loads, moft, torsion  # noqa: F401
