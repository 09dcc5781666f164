#version 330 core
// vertex shader for IR program pass-through
in vec4 attr_position;
in vec4 attr_color0;
in vec4 attr_texcoord0;
const vec4 attr_texcoord1 = vec4(0.0, 0.0, 0.0, 1.0);  // no texcoord1 stream
const vec4 attr_texcoord2 = vec4(0.0, 0.0, 0.0, 1.0);  // no texcoord2 stream
uniform vec2 d3d_pixel_size;  // (2/W, 2/H): one pixel in NDC
flat out vec4 vary_color0;
out vec4 vary_texcoord0;
out vec4 vary_texcoord1;
out vec4 vary_texcoord2;

void main() {
#line 10000
    vary_color0 = clamp(attr_color0, 0.0, 1.0);
    vary_texcoord0 = attr_texcoord0;
    vary_texcoord1 = attr_texcoord1;
    vary_texcoord2 = attr_texcoord2;
    vec4 p = attr_position;
    // D3D clip space to GL's: half-pixel shift to D3D9 pixel centres, y flipped
    // (GL row r is D3D row r), z in [0, w] to [-w, w].
    gl_Position = vec4(p.x + 0.5 * d3d_pixel_size.x * p.w,
                       -(p.y - 0.5 * d3d_pixel_size.y * p.w),
                       2.0 * p.z - p.w, p.w);
}
