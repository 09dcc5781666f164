#version 330 core
// vertex shader for IR program e149c90699786abb
in vec4 attr_position;
const vec4 attr_color0 = vec4(1.0, 1.0, 1.0, 1.0);  // no color0 stream
in vec4 attr_texcoord0;
uniform vec4 u_WorldViewProjection_c0;
uniform vec4 u_WorldViewProjection_c1;
uniform vec4 u_WorldViewProjection_c2;
uniform vec4 u_WorldViewProjection_c3;
uniform vec2 d3d_pixel_size;  // (2/W, 2/H): one pixel in NDC
out vec4 vary_color0;
out vec4 vary_texcoord0;
out vec4 vary_texcoord1;

void main() {
#line 9
    vec4 v0 = attr_position;  // %0 = input position
    vec4 v1 = u_WorldViewProjection_c0;  // %1 = input WorldViewProjection_c0
    vec4 v2 = vec4(dot(v0, v1));  // %2 = dp4 %0, %1
    vec4 v3 = u_WorldViewProjection_c1;  // %3 = input WorldViewProjection_c1
    vec4 v4 = vec4(dot(v0, v3));  // %4 = dp4 %0, %3
    vec4 v5 = u_WorldViewProjection_c2;  // %5 = input WorldViewProjection_c2
    vec4 v6 = vec4(dot(v0, v5));  // %6 = dp4 %0, %5
    vec4 v7 = u_WorldViewProjection_c3;  // %7 = input WorldViewProjection_c3
    vec4 v8 = vec4(dot(v0, v7));  // %8 = dp4 %0, %7
    vec4 v9 = vec4(v2.x, v4.y, v2.z, v2.w);  // %9 = merge %2, %4 mask=y
    vec4 v10 = vec4(v9.x, v9.y, v6.z, v9.w);  // %10 = merge %9, %6 mask=z
    vec4 v11 = vec4(v10.x, v10.y, v10.z, v8.w);  // %11 = merge %10, %8 mask=w
    vec4 v12 = attr_color0;  // %12 = input color0
    vec4 v13 = attr_texcoord0;  // %13 = input texcoord0
    vec4 v14 = v6.zzzz;  // %14 = swizzle %6 pattern=zzzz
    vec4 out_position = v11;  // output position = %11
    vec4 out_color0 = v12;  // output color0 = %12
    vec4 out_texcoord0 = v13;  // output texcoord0 = %13
    vec4 out_fog = v14;  // output fog = %14
#line 10000
    vary_color0 = clamp(out_color0, 0.0, 1.0);
    vary_texcoord0 = out_texcoord0;
    vary_texcoord1 = vec4(0.0, 0.0, 0.0, 1.0);
    vec4 p = out_position;
    // D3D clip space to GL's: half-pixel shift to D3D9 pixel centres, y flipped
    // (GL row r is D3D row r), z in [0, w] to [-w, w].
    gl_Position = vec4(p.x + 0.5 * d3d_pixel_size.x * p.w,
                       -(p.y - 0.5 * d3d_pixel_size.y * p.w),
                       2.0 * p.z - p.w, p.w);
}
