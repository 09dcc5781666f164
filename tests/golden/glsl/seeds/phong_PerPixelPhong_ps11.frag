// phong.fx technique PerPixelPhong_ps11, lowered for geforce3
// pass 1 of 2: Diffuse
#version 330 core
// fragment shader for IR program de851114614d6a10
in vec4 vary_color0;
in vec4 vary_texcoord0;
in vec4 vary_texcoord1;
in vec4 vary_texcoord3;
uniform vec4 u_ps_c0;
uniform sampler2D sampler0;
uniform sampler2D sampler1;
layout(location = 0, index = 0) out vec4 frag_color;

void main() {
#line 9
    vec4 v0 = vary_texcoord0;  // %0 = input texcoord0
    vec4 v1 = texture(sampler0, v0.xy);  // %1 = sample %0 sampler=0
    vec4 v2 = vary_texcoord1;  // %2 = input texcoord1
    vec4 v3 = texture(sampler1, v2.xy);  // %3 = sample %2 sampler=1
    vec4 v4 = vary_texcoord3;  // %4 = input texcoord3
    vec4 v5 = clamp(v4, 0.0, 1.0);  // %5 = saturate %4
    vec4 v6 = vec4(1.0, 1.0, 1.0, 1.0);  // %6 = const (1.0, 1.0, 1.0, 1.0)
    vec4 v7 = vec4(v5.x, v5.y, v5.z, v6.w);  // %7 = merge %6, %5 mask=xyz
    vec4 v8 = clamp(v7, -1.0, 1.0);  // %8 = clamp %7 lo=-1.0 hi=1.0
    vec4 v9 = (sign(clamp(v8, -1.0, 1.0)) * floor(abs(clamp(v8, -1.0, 1.0)) * 255.0 + 0.5) / 255.0);  // %9 = quantize %8 bits=9 signed=true
    vec4 v10 = vec4(0.5, 0.5, 0.5, 0.5);  // %10 = const (0.5, 0.5, 0.5, 0.5)
    vec4 v11 = (v3 - v10);  // %11 = sub %3, %10
    vec4 v12 = vec4(2.0, 2.0, 2.0, 2.0);  // %12 = const (2.0, 2.0, 2.0, 2.0)
    vec4 v13 = (v11 * v12);  // %13 = mul %11, %12
    vec4 v14 = vary_color0;  // %14 = input color0
    vec4 v15 = (v14 - v10);  // %15 = sub %14, %10
    vec4 v16 = (v15 * v12);  // %16 = mul %15, %12
    vec4 v17 = vec4(dot(v13.xyz, v16.xyz));  // %17 = dp3 %13, %16
    vec4 v18 = clamp(v17, 0.0, 1.0);  // %18 = saturate %17
    vec4 v19 = clamp(v18, -1.0, 1.0);  // %19 = clamp %18 lo=-1.0 hi=1.0
    vec4 v20 = (sign(clamp(v19, -1.0, 1.0)) * floor(abs(clamp(v19, -1.0, 1.0)) * 255.0 + 0.5) / 255.0);  // %20 = quantize %19 bits=9 signed=true
    vec4 v21 = u_ps_c0;  // %21 = input ps_c0
    vec4 v22 = clamp(v21, -1.0, 1.0);  // %22 = clamp %21 lo=-1.0 hi=1.0
    vec4 v23 = (v20 * v9 + v22);  // %23 = mad %20, %9, %22
    vec4 v24 = clamp(v23, -1.0, 1.0);  // %24 = clamp %23 lo=-1.0 hi=1.0
    vec4 v25 = (sign(clamp(v24, -1.0, 1.0)) * floor(abs(clamp(v24, -1.0, 1.0)) * 255.0 + 0.5) / 255.0);  // %25 = quantize %24 bits=9 signed=true
    vec4 v26 = (v25 * v1);  // %26 = mul %25, %1
    vec4 v27 = clamp(v26, -1.0, 1.0);  // %27 = clamp %26 lo=-1.0 hi=1.0
    vec4 v28 = (sign(clamp(v27, -1.0, 1.0)) * floor(abs(clamp(v27, -1.0, 1.0)) * 255.0 + 0.5) / 255.0);  // %28 = quantize %27 bits=9 signed=true
    vec4 v29 = clamp(v28, 0.0, 1.0);  // %29 = saturate %28
    vec4 out_color0 = v29;  // output color0 = %29
#line 10000
    vec4 color = out_color0;
    frag_color = color;
}
// pass 2 of 2: Specular
#version 330 core
// fragment shader for IR program 554beef2c619bf75
in vec4 vary_color1;
in vec4 vary_texcoord1;
in vec4 vary_texcoord2;
in vec4 vary_texcoord3;
uniform sampler2D sampler1;
uniform sampler2D sampler2;
layout(location = 0, index = 0) out vec4 frag_color;

void main() {
#line 8
    vec4 v0 = vary_texcoord1;  // %0 = input texcoord1
    vec4 v1 = texture(sampler1, v0.xy);  // %1 = sample %0 sampler=1
    vec4 v2 = vary_texcoord2;  // %2 = input texcoord2
    vec4 v3 = texture(sampler2, v2.xy);  // %3 = sample %2 sampler=2
    vec4 v4 = vary_texcoord3;  // %4 = input texcoord3
    vec4 v5 = clamp(v4, 0.0, 1.0);  // %5 = saturate %4
    vec4 v6 = vec4(1.0, 1.0, 1.0, 1.0);  // %6 = const (1.0, 1.0, 1.0, 1.0)
    vec4 v7 = vec4(v5.x, v5.y, v5.z, v6.w);  // %7 = merge %6, %5 mask=xyz
    vec4 v8 = clamp(v7, -1.0, 1.0);  // %8 = clamp %7 lo=-1.0 hi=1.0
    vec4 v9 = (sign(clamp(v8, -1.0, 1.0)) * floor(abs(clamp(v8, -1.0, 1.0)) * 255.0 + 0.5) / 255.0);  // %9 = quantize %8 bits=9 signed=true
    vec4 v10 = vec4(0.5, 0.5, 0.5, 0.5);  // %10 = const (0.5, 0.5, 0.5, 0.5)
    vec4 v11 = (v1 - v10);  // %11 = sub %1, %10
    vec4 v12 = vec4(2.0, 2.0, 2.0, 2.0);  // %12 = const (2.0, 2.0, 2.0, 2.0)
    vec4 v13 = (v11 * v12);  // %13 = mul %11, %12
    vec4 v14 = vary_color1;  // %14 = input color1
    vec4 v15 = (v14 - v10);  // %15 = sub %14, %10
    vec4 v16 = (v15 * v12);  // %16 = mul %15, %12
    vec4 v17 = vec4(dot(v13.xyz, v16.xyz));  // %17 = dp3 %13, %16
    vec4 v18 = clamp(v17, 0.0, 1.0);  // %18 = saturate %17
    vec4 v19 = clamp(v18, -1.0, 1.0);  // %19 = clamp %18 lo=-1.0 hi=1.0
    vec4 v20 = (sign(clamp(v19, -1.0, 1.0)) * floor(abs(clamp(v19, -1.0, 1.0)) * 255.0 + 0.5) / 255.0);  // %20 = quantize %19 bits=9 signed=true
    vec4 v21 = (v20 * v20);  // %21 = mul %20, %20
    vec4 v22 = clamp(v21, -1.0, 1.0);  // %22 = clamp %21 lo=-1.0 hi=1.0
    vec4 v23 = (sign(clamp(v22, -1.0, 1.0)) * floor(abs(clamp(v22, -1.0, 1.0)) * 255.0 + 0.5) / 255.0);  // %23 = quantize %22 bits=9 signed=true
    vec4 v24 = (v23 * v23);  // %24 = mul %23, %23
    vec4 v25 = clamp(v24, -1.0, 1.0);  // %25 = clamp %24 lo=-1.0 hi=1.0
    vec4 v26 = (sign(clamp(v25, -1.0, 1.0)) * floor(abs(clamp(v25, -1.0, 1.0)) * 255.0 + 0.5) / 255.0);  // %26 = quantize %25 bits=9 signed=true
    vec4 v27 = (v26 * v26);  // %27 = mul %26, %26
    vec4 v28 = clamp(v27, -1.0, 1.0);  // %28 = clamp %27 lo=-1.0 hi=1.0
    vec4 v29 = (sign(clamp(v28, -1.0, 1.0)) * floor(abs(clamp(v28, -1.0, 1.0)) * 255.0 + 0.5) / 255.0);  // %29 = quantize %28 bits=9 signed=true
    vec4 v30 = (v29 * v29);  // %30 = mul %29, %29
    vec4 v31 = clamp(v30, -1.0, 1.0);  // %31 = clamp %30 lo=-1.0 hi=1.0
    vec4 v32 = (sign(clamp(v31, -1.0, 1.0)) * floor(abs(clamp(v31, -1.0, 1.0)) * 255.0 + 0.5) / 255.0);  // %32 = quantize %31 bits=9 signed=true
    vec4 v33 = (v32 * v29);  // %33 = mul %32, %29
    vec4 v34 = clamp(v33, -1.0, 1.0);  // %34 = clamp %33 lo=-1.0 hi=1.0
    vec4 v35 = (sign(clamp(v34, -1.0, 1.0)) * floor(abs(clamp(v34, -1.0, 1.0)) * 255.0 + 0.5) / 255.0);  // %35 = quantize %34 bits=9 signed=true
    vec4 v36 = (v35 * v3);  // %36 = mul %35, %3
    vec4 v37 = clamp(v36, -1.0, 1.0);  // %37 = clamp %36 lo=-1.0 hi=1.0
    vec4 v38 = (sign(clamp(v37, -1.0, 1.0)) * floor(abs(clamp(v37, -1.0, 1.0)) * 255.0 + 0.5) / 255.0);  // %38 = quantize %37 bits=9 signed=true
    vec4 v39 = (v38 * v9);  // %39 = mul %38, %9
    vec4 v40 = clamp(v39, -1.0, 1.0);  // %40 = clamp %39 lo=-1.0 hi=1.0
    vec4 v41 = (sign(clamp(v40, -1.0, 1.0)) * floor(abs(clamp(v40, -1.0, 1.0)) * 255.0 + 0.5) / 255.0);  // %41 = quantize %40 bits=9 signed=true
    vec4 v42 = clamp(v41, 0.0, 1.0);  // %42 = saturate %41
    vec4 out_color0 = v42;  // output color0 = %42
#line 10000
    vec4 color = out_color0;
    frag_color = color;
}
