// specular_bump.fx technique SpecularMultiply_ps11, lowered for geforce3
// pass 1 of 1: P0
#version 330 core
// fragment shader for IR program 93ff1137232913d8
in vec4 vary_color0;
in vec4 vary_color1;
in vec4 vary_texcoord0;
in vec4 vary_texcoord1;
uniform sampler2D sampler0;
uniform sampler2D sampler1;
layout(location = 0, index = 0) out vec4 frag_color;

void main() {
#line 8
    vec4 v0 = vary_texcoord0;  // %0 = input texcoord0
    vec4 v1 = texture(sampler0, v0.xy);  // %1 = sample %0 sampler=0
    vec4 v2 = vary_texcoord1;  // %2 = input texcoord1
    vec4 v3 = texture(sampler1, v2.xy);  // %3 = sample %2 sampler=1
    vec4 v4 = vec4(0.5, 0.5, 0.5, 0.5);  // %4 = const (0.5, 0.5, 0.5, 0.5)
    vec4 v5 = (v3 - v4);  // %5 = sub %3, %4
    vec4 v6 = vec4(2.0, 2.0, 2.0, 2.0);  // %6 = const (2.0, 2.0, 2.0, 2.0)
    vec4 v7 = (v5 * v6);  // %7 = mul %5, %6
    vec4 v8 = vary_color0;  // %8 = input color0
    vec4 v9 = (v8 - v4);  // %9 = sub %8, %4
    vec4 v10 = (v9 * v6);  // %10 = mul %9, %6
    vec4 v11 = vec4(dot(v7.xyz, v10.xyz));  // %11 = dp3 %7, %10
    vec4 v12 = clamp(v11, 0.0, 1.0);  // %12 = saturate %11
    vec4 v13 = clamp(v12, -1.0, 1.0);  // %13 = clamp %12 lo=-1.0 hi=1.0
    vec4 v14 = (sign(clamp(v13, -1.0, 1.0)) * floor(abs(clamp(v13, -1.0, 1.0)) * 255.0 + 0.5) / 255.0);  // %14 = quantize %13 bits=9 signed=true
    vec4 v15 = vary_color1;  // %15 = input color1
    vec4 v16 = (v15 - v4);  // %16 = sub %15, %4
    vec4 v17 = (v16 * v6);  // %17 = mul %16, %6
    vec4 v18 = vec4(dot(v7.xyz, v17.xyz));  // %18 = dp3 %7, %17
    vec4 v19 = clamp(v18, 0.0, 1.0);  // %19 = saturate %18
    vec4 v20 = clamp(v19, -1.0, 1.0);  // %20 = clamp %19 lo=-1.0 hi=1.0
    vec4 v21 = (sign(clamp(v20, -1.0, 1.0)) * floor(abs(clamp(v20, -1.0, 1.0)) * 255.0 + 0.5) / 255.0);  // %21 = quantize %20 bits=9 signed=true
    vec4 v22 = (v21 * v21);  // %22 = mul %21, %21
    vec4 v23 = clamp(v22, -1.0, 1.0);  // %23 = clamp %22 lo=-1.0 hi=1.0
    vec4 v24 = (sign(clamp(v23, -1.0, 1.0)) * floor(abs(clamp(v23, -1.0, 1.0)) * 255.0 + 0.5) / 255.0);  // %24 = quantize %23 bits=9 signed=true
    vec4 v25 = (v24 * v24);  // %25 = mul %24, %24
    vec4 v26 = clamp(v25, -1.0, 1.0);  // %26 = clamp %25 lo=-1.0 hi=1.0
    vec4 v27 = (sign(clamp(v26, -1.0, 1.0)) * floor(abs(clamp(v26, -1.0, 1.0)) * 255.0 + 0.5) / 255.0);  // %27 = quantize %26 bits=9 signed=true
    vec4 v28 = (v27 * v27);  // %28 = mul %27, %27
    vec4 v29 = clamp(v28, -1.0, 1.0);  // %29 = clamp %28 lo=-1.0 hi=1.0
    vec4 v30 = (sign(clamp(v29, -1.0, 1.0)) * floor(abs(clamp(v29, -1.0, 1.0)) * 255.0 + 0.5) / 255.0);  // %30 = quantize %29 bits=9 signed=true
    vec4 v31 = (v30 * v30);  // %31 = mul %30, %30
    vec4 v32 = clamp(v31, -1.0, 1.0);  // %32 = clamp %31 lo=-1.0 hi=1.0
    vec4 v33 = (sign(clamp(v32, -1.0, 1.0)) * floor(abs(clamp(v32, -1.0, 1.0)) * 255.0 + 0.5) / 255.0);  // %33 = quantize %32 bits=9 signed=true
    vec4 v34 = (v14 * v1 + v33);  // %34 = mad %14, %1, %33
    vec4 v35 = clamp(v34, -1.0, 1.0);  // %35 = clamp %34 lo=-1.0 hi=1.0
    vec4 v36 = (sign(clamp(v35, -1.0, 1.0)) * floor(abs(clamp(v35, -1.0, 1.0)) * 255.0 + 0.5) / 255.0);  // %36 = quantize %35 bits=9 signed=true
    vec4 v37 = clamp(v36, 0.0, 1.0);  // %37 = saturate %36
    vec4 out_color0 = v37;  // output color0 = %37
#line 10000
    vec4 color = out_color0;
    frag_color = color;
}
