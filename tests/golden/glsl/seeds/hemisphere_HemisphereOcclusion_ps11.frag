// hemisphere.fx technique HemisphereOcclusion_ps11, lowered for geforce3
// pass 1 of 1: P0
#version 330 core
// fragment shader for IR program 6daa0a6b14696965
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
    vec4 v13 = clamp(v12, -1.0, 1.0);  // %13 = clamp %12 lo=-1.0 hi=1.0
    vec4 v14 = (sign(clamp(v13, -1.0, 1.0)) * floor(abs(clamp(v13, -1.0, 1.0)) * 255.0 + 0.5) / 255.0);  // %14 = quantize %13 bits=9 signed=true
    vec4 v15 = u_ps_c5;  // %15 = input ps_c5
    vec4 v16 = clamp(v15, -1.0, 1.0);  // %16 = clamp %15 lo=-1.0 hi=1.0
    vec4 v17 = (v14 + v16);  // %17 = add %14, %16
    vec4 v18 = clamp(v17, -1.0, 1.0);  // %18 = clamp %17 lo=-1.0 hi=1.0
    vec4 v19 = (sign(clamp(v18, -1.0, 1.0)) * floor(abs(clamp(v18, -1.0, 1.0)) * 255.0 + 0.5) / 255.0);  // %19 = quantize %18 bits=9 signed=true
    vec4 v20 = u_ps_c1;  // %20 = input ps_c1
    vec4 v21 = clamp(v20, -1.0, 1.0);  // %21 = clamp %20 lo=-1.0 hi=1.0
    vec4 v22 = u_ps_c2;  // %22 = input ps_c2
    vec4 v23 = clamp(v22, -1.0, 1.0);  // %23 = clamp %22 lo=-1.0 hi=1.0
    vec4 v24 = mix(v23, v21, v19);  // %24 = lrp %19, %21, %23
    vec4 v25 = clamp(v24, -1.0, 1.0);  // %25 = clamp %24 lo=-1.0 hi=1.0
    vec4 v26 = (sign(clamp(v25, -1.0, 1.0)) * floor(abs(clamp(v25, -1.0, 1.0)) * 255.0 + 0.5) / 255.0);  // %26 = quantize %25 bits=9 signed=true
    vec4 v27 = (v26 * v3);  // %27 = mul %26, %3
    vec4 v28 = clamp(v27, -1.0, 1.0);  // %28 = clamp %27 lo=-1.0 hi=1.0
    vec4 v29 = (sign(clamp(v28, -1.0, 1.0)) * floor(abs(clamp(v28, -1.0, 1.0)) * 255.0 + 0.5) / 255.0);  // %29 = quantize %28 bits=9 signed=true
    vec4 v30 = v4.wwww;  // %30 = swizzle %4 pattern=wwww
    vec4 v31 = (v29 * v30);  // %31 = mul %29, %30
    vec4 v32 = clamp(v31, -1.0, 1.0);  // %32 = clamp %31 lo=-1.0 hi=1.0
    vec4 v33 = (sign(clamp(v32, -1.0, 1.0)) * floor(abs(clamp(v32, -1.0, 1.0)) * 255.0 + 0.5) / 255.0);  // %33 = quantize %32 bits=9 signed=true
    vec4 v34 = v1.wwww;  // %34 = swizzle %1 pattern=wwww
    vec4 v35 = (v33 * v34);  // %35 = mul %33, %34
    vec4 v36 = clamp(v35, -1.0, 1.0);  // %36 = clamp %35 lo=-1.0 hi=1.0
    vec4 v37 = (sign(clamp(v36, -1.0, 1.0)) * floor(abs(clamp(v36, -1.0, 1.0)) * 255.0 + 0.5) / 255.0);  // %37 = quantize %36 bits=9 signed=true
    vec4 v38 = clamp(v37, 0.0, 1.0);  // %38 = saturate %37
    vec4 out_color0 = v38;  // output color0 = %38
#line 10000
    vec4 color = out_color0;
    frag_color = color;
}
