"""Direct3D 9's tables: render, texture-stage and sampler states, texture-stage ops, the
caps profiles, the texel formats, the device state a pass sets, and fixed-point precision."""
