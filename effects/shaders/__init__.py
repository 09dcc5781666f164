"""Shader languages: Direct3D assembly (asm/) and HLSL."""
