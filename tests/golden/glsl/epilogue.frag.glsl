#version 330 core
// fragment shader for IR program a4c6cde122807bb5
in vec4 vary_texcoord1;
uniform vec4 u_LightDirection;
uniform vec4 u_MaterialDiffuse;
uniform vec2 d3d_depth_bias;  // (DepthBias, SlopeScaleDepthBias)
uniform int d3d_alpha_func;  // index in COMPARE_FUNCS
uniform int d3d_alpha_ref;
layout(location = 0, index = 0) out vec4 frag_color;
bool d3d_compare(int func, int a, int b) {  // D3DCMPFUNC, numbered as COMPARE_FUNCS
    if (func == 0) return false;
    if (func == 1) return a < b;
    if (func == 2) return a == b;
    if (func == 3) return a <= b;
    if (func == 4) return a > b;
    if (func == 5) return a != b;
    if (func == 6) return a >= b;
    return true;
}
vec3 d3d_linear_to_srgb(vec3 x) {  // IEC 61966-2-1
    x = clamp(x, 0.0, 1.0);
    return mix(1.055 * pow(x, vec3(1.0 / 2.4)) - 0.055, 12.92 * x,
               lessThanEqual(x, vec3(0.0031308)));
}

void main() {
#line 5
    vec4 v0 = vary_texcoord1;  // %0 = input texcoord1
    vec4 v1 = (v0 * (dot(v0.xyz, v0.xyz) != 0.0 ? inversesqrt(dot(v0.xyz, v0.xyz)) : 3.4028235e+38));  // %1 = nrm %0
    vec4 v2 = u_LightDirection;  // %2 = input LightDirection
    vec4 v3 = (v2 * (dot(v2.xyz, v2.xyz) != 0.0 ? inversesqrt(dot(v2.xyz, v2.xyz)) : 3.4028235e+38));  // %3 = nrm %2
    vec4 v4 = u_MaterialDiffuse;  // %4 = input MaterialDiffuse
    vec4 v5 = vec4(dot(v1.xyz, v3.xyz));  // %5 = dp3 %1, %3
    vec4 v6 = clamp(v5, 0.0, 1.0);  // %6 = saturate %5
    vec4 v7 = (v6 * v4);  // %7 = mul %6, %4
    vec4 v8 = vec4(v7.x, v7.y, v7.z, v4.w);  // %8 = merge %7, %4 mask=w
    vec4 out_color0 = v8;  // output color0 = %8
#line 10000
    vec4 color = out_color0;
    float z_slope = max(abs(dFdx(gl_FragCoord.z)), abs(dFdy(gl_FragCoord.z)));
    gl_FragDepth = gl_FragCoord.z + d3d_depth_bias.x + d3d_depth_bias.y * z_slope;
    int alpha8 = int(floor(clamp(color.a, 0.0, 1.0) * 255.0 + 0.5));
    if (!d3d_compare(d3d_alpha_func, alpha8, d3d_alpha_ref)) discard;
    color.rgb = d3d_linear_to_srgb(color.rgb);
    frag_color = color;
}
