// hemisphere.fx technique HemispherePerPixel_ps11, lowered for geforce3
// pass 1 of 1: P0
#version 330 core
// fragment shader for IR program 2a4350f0c738ae66
in vec4 vary_color0;
in vec4 vary_texcoord0;
in vec4 vary_texcoord1;
uniform vec4 u_ps_c5;
uniform vec4 u_ps_c1;
uniform vec4 u_ps_c2;
uniform sampler2D sampler0;
uniform sampler2D sampler1;
layout(location = 0, index = 0) out vec4 frag_color;

void main() {
#line 10
    vec4 v0 = vary_texcoord0;  // %0 = input texcoord0
    vec4 v1 = texture(sampler0, v0.xy);  // %1 = sample %0 sampler=0
    vec4 v2 = vary_texcoord1;  // %2 = input texcoord1
    vec4 v3 = texture(sampler1, v2.xy);  // %3 = sample %2 sampler=1
    vec4 v4 = vary_color0;  // %4 = input color0
    vec4 v5 = vec4(0.5, 0.5, 0.5, 0.5);  // %5 = const (0.5, 0.5, 0.5, 0.5)
    vec4 v6 = (v4 - v5);  // %6 = sub %4, %5
    vec4 v7 = vec4(2.0, 2.0, 2.0, 2.0);  // %7 = const (2.0, 2.0, 2.0, 2.0)
    vec4 v8 = (v6 * v7);  // %8 = mul %6, %7
    vec4 v9 = (v1 - v5);  // %9 = sub %1, %5
    vec4 v10 = (v9 * v7);  // %10 = mul %9, %7
    vec4 v11 = vec4(dot(v8.xyz, v10.xyz));  // %11 = dp3 %8, %10
    vec4 v12 = (v11 * v5);  // %12 = mul %11, %5
    vec4 v13 = clamp(v12, 0.0, 1.0);  // %13 = saturate %12
    vec4 v14 = clamp(v13, -1.0, 1.0);  // %14 = clamp %13 lo=-1.0 hi=1.0
    vec4 v15 = (sign(clamp(v14, -1.0, 1.0)) * floor(abs(clamp(v14, -1.0, 1.0)) * 255.0 + 0.5) / 255.0);  // %15 = quantize %14 bits=9 signed=true
    vec4 v16 = u_ps_c5;  // %16 = input ps_c5
    vec4 v17 = clamp(v16, -1.0, 1.0);  // %17 = clamp %16 lo=-1.0 hi=1.0
    vec4 v18 = (v15 + v17);  // %18 = add %15, %17
    vec4 v19 = clamp(v18, -1.0, 1.0);  // %19 = clamp %18 lo=-1.0 hi=1.0
    vec4 v20 = (sign(clamp(v19, -1.0, 1.0)) * floor(abs(clamp(v19, -1.0, 1.0)) * 255.0 + 0.5) / 255.0);  // %20 = quantize %19 bits=9 signed=true
    vec4 v21 = u_ps_c1;  // %21 = input ps_c1
    vec4 v22 = clamp(v21, -1.0, 1.0);  // %22 = clamp %21 lo=-1.0 hi=1.0
    vec4 v23 = u_ps_c2;  // %23 = input ps_c2
    vec4 v24 = clamp(v23, -1.0, 1.0);  // %24 = clamp %23 lo=-1.0 hi=1.0
    vec4 v25 = mix(v24, v22, v20);  // %25 = lrp %20, %22, %24
    vec4 v26 = clamp(v25, -1.0, 1.0);  // %26 = clamp %25 lo=-1.0 hi=1.0
    vec4 v27 = (sign(clamp(v26, -1.0, 1.0)) * floor(abs(clamp(v26, -1.0, 1.0)) * 255.0 + 0.5) / 255.0);  // %27 = quantize %26 bits=9 signed=true
    vec4 v28 = (v27 * v3);  // %28 = mul %27, %3
    vec4 v29 = clamp(v28, -1.0, 1.0);  // %29 = clamp %28 lo=-1.0 hi=1.0
    vec4 v30 = (sign(clamp(v29, -1.0, 1.0)) * floor(abs(clamp(v29, -1.0, 1.0)) * 255.0 + 0.5) / 255.0);  // %30 = quantize %29 bits=9 signed=true
    vec4 v31 = clamp(v30, 0.0, 1.0);  // %31 = saturate %30
    vec4 out_color0 = v31;  // output color0 = %31
#line 10000
    vec4 color = out_color0;
    frag_color = color;
}
