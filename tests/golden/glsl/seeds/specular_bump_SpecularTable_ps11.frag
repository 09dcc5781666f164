// specular_bump.fx technique SpecularTable_ps11, lowered for geforce3
// pass 1 of 1: P0
#version 330 core
// fragment shader for IR program 40e024689275f2a8
in vec4 vary_texcoord0;
in vec4 vary_texcoord1;
in vec4 vary_texcoord2;
in vec4 vary_texcoord3;
uniform sampler2D sampler0;
uniform sampler2D sampler2;
uniform sampler2D sampler3;
layout(location = 0, index = 0) out vec4 frag_color;

void main() {
#line 9
    vec4 v0 = vary_texcoord0;  // %0 = input texcoord0
    vec4 v1 = texture(sampler0, v0.xy);  // %1 = sample %0 sampler=0
    vec4 v2 = vary_texcoord1;  // %2 = input texcoord1
    vec4 v3 = vec4(0.5, 0.5, 0.5, 0.5);  // %3 = const (0.5, 0.5, 0.5, 0.5)
    vec4 v4 = (v1 - v3);  // %4 = sub %1, %3
    vec4 v5 = vec4(2.0, 2.0, 2.0, 2.0);  // %5 = const (2.0, 2.0, 2.0, 2.0)
    vec4 v6 = (v4 * v5);  // %6 = mul %4, %5
    vec4 v7 = vec4(dot(v2.xyz, v6.xyz));  // %7 = dp3 %2, %6
    vec4 v8 = vary_texcoord2;  // %8 = input texcoord2
    vec4 v9 = vec4(dot(v8.xyz, v6.xyz));  // %9 = dp3 %8, %6
    vec4 v10 = vec4(v7.x, v9.y, v7.z, v7.w);  // %10 = merge %7, %9 mask=y
    vec4 v11 = texture(sampler2, v10.xy);  // %11 = sample %10 sampler=2
    vec4 v12 = vary_texcoord3;  // %12 = input texcoord3
    vec4 v13 = texture(sampler3, v12.xy);  // %13 = sample %12 sampler=3
    vec4 v14 = v11.wwww;  // %14 = swizzle %11 pattern=wwww
    vec4 v15 = (v13 * v14 + v11);  // %15 = mad %13, %14, %11
    vec4 v16 = clamp(v15, -1.0, 1.0);  // %16 = clamp %15 lo=-1.0 hi=1.0
    vec4 v17 = (sign(clamp(v16, -1.0, 1.0)) * floor(abs(clamp(v16, -1.0, 1.0)) * 255.0 + 0.5) / 255.0);  // %17 = quantize %16 bits=9 signed=true
    vec4 v18 = clamp(v17, 0.0, 1.0);  // %18 = saturate %17
    vec4 out_color0 = v18;  // output color0 = %18
#line 10000
    vec4 color = out_color0;
    frag_color = color;
}
