"""Lowering: a validated pass to a PassProgram (texture stages, vertex pipeline, shaders, precision)."""
