"""What a render draws with: textures (files, .dds, procedural generators, mips), meshes
(.obj, built-in shapes, tangent space) and the tables some effects read (BRDF, occlusion)."""
