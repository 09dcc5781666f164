#version 330 core
// fragment shader for IR program a4c6cde122807bb5
in vec4 vary_texcoord1;
uniform vec4 u_LightDirection;
uniform vec4 u_MaterialDiffuse;
layout(location = 0, index = 0) out vec4 frag_color;

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
    frag_color = color;
}
