"""The engine description: the typed engine in SI and the crank derived from its geometry."""
