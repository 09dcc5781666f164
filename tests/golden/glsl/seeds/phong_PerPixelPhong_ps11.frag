// phong.fx technique PerPixelPhong_ps11, lowered for geforce3
// pass 1 of 2: Diffuse
#version 330 core
// fragment shader for IR program a9f2aa6ec30585a4
in vec4 vary_color0;
in vec4 vary_color1;
in vec4 vary_texcoord0;
in vec4 vary_texcoord3;
uniform vec4 u_ps_c0;
uniform sampler2D sampler0;
uniform sampler2D sampler3;
layout(location = 0, index = 0) out vec4 frag_color;

void main() {
#line 9
    vec4 v0 = vary_texcoord0;  // %0 = input texcoord0
    vec4 v1 = texture(sampler0, v0.xy);  // %1 = sample %0 sampler=0
    vec4 v2 = vary_texcoord3;  // %2 = input texcoord3
    vec4 v3 = texture(sampler3, v2.xy);  // %3 = sample %2 sampler=3
    vec4 v4 = vec4(0.5, 0.5, 0.5, 0.5);  // %4 = const (0.5, 0.5, 0.5, 0.5)
    vec4 v5 = (v1 - v4);  // %5 = sub %1, %4
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
    vec4 v16 = u_ps_c0;  // %16 = input ps_c0
    vec4 v17 = clamp(v16, -1.0, 1.0);  // %17 = clamp %16 lo=-1.0 hi=1.0
    vec4 v18 = (v14 * v15 + v17);  // %18 = mad %14, %15, %17
    vec4 v19 = clamp(v18, -1.0, 1.0);  // %19 = clamp %18 lo=-1.0 hi=1.0
    vec4 v20 = (sign(clamp(v19, -1.0, 1.0)) * floor(abs(clamp(v19, -1.0, 1.0)) * 255.0 + 0.5) / 255.0);  // %20 = quantize %19 bits=9 signed=true
    vec4 v21 = (v20 * v3);  // %21 = mul %20, %3
    vec4 v22 = clamp(v21, -1.0, 1.0);  // %22 = clamp %21 lo=-1.0 hi=1.0
    vec4 v23 = (sign(clamp(v22, -1.0, 1.0)) * floor(abs(clamp(v22, -1.0, 1.0)) * 255.0 + 0.5) / 255.0);  // %23 = quantize %22 bits=9 signed=true
    vec4 v24 = clamp(v23, 0.0, 1.0);  // %24 = saturate %23
    vec4 out_color0 = v24;  // output color0 = %24
#line 10000
    vec4 color = out_color0;
    frag_color = color;
}
// pass 2 of 2: Specular
#version 330 core
// fragment shader for IR program b08902f987db2132
in vec4 vary_color1;
in vec4 vary_texcoord0;
in vec4 vary_texcoord1;
in vec4 vary_texcoord2;
in vec4 vary_texcoord3;
uniform sampler2D sampler0;
uniform sampler2D sampler2;
uniform sampler2D sampler3;
layout(location = 0, index = 0) out vec4 frag_color;

void main() {
#line 10
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
    vec4 v14 = (v11 * v13);  // %14 = mul %11, %13
    vec4 v15 = clamp(v14, -1.0, 1.0);  // %15 = clamp %14 lo=-1.0 hi=1.0
    vec4 v16 = (sign(clamp(v15, -1.0, 1.0)) * floor(abs(clamp(v15, -1.0, 1.0)) * 255.0 + 0.5) / 255.0);  // %16 = quantize %15 bits=9 signed=true
    vec4 v17 = vary_color1;  // %17 = input color1
    vec4 v18 = (v16 * v17);  // %18 = mul %16, %17
    vec4 v19 = clamp(v18, -1.0, 1.0);  // %19 = clamp %18 lo=-1.0 hi=1.0
    vec4 v20 = (sign(clamp(v19, -1.0, 1.0)) * floor(abs(clamp(v19, -1.0, 1.0)) * 255.0 + 0.5) / 255.0);  // %20 = quantize %19 bits=9 signed=true
    vec4 v21 = clamp(v20, 0.0, 1.0);  // %21 = saturate %20
    vec4 out_color0 = v21;  // output color0 = %21
#line 10000
    vec4 color = out_color0;
    frag_color = color;
}
