#version 330 core
// fragment shader for IR program 4457eb7afd0812f0
in vec4 vary_color0;
in vec4 vary_texcoord0;
in vec4 vary_texcoord1;
in vec4 vary_texcoord2;
uniform vec4 u_c0;
uniform sampler2D sampler0;
uniform sampler2D sampler1;
layout(location = 0, index = 0) out vec4 frag_color;

void main() {
#line 9
    vec4 v0 = vary_texcoord0;  // %0 = input texcoord0
    vec4 v1 = texture(sampler0, v0.xy);  // %1 = sample %0 sampler=0
    vec4 v2 = vary_texcoord1;  // %2 = input texcoord1
    vec4 v3 = texture(sampler1, v2.xy);  // %3 = sample %2 sampler=1
    vec4 v4 = vary_texcoord2;  // %4 = input texcoord2
    if (any(lessThan(v4.xyz, vec3(0.0)))) discard;  // kill %4 components=xyz
    vec4 v5 = vary_color0;  // %5 = input color0
    vec4 v6 = vec4(2.0, 2.0, 2.0, 2.0);  // %6 = const (2.0, 2.0, 2.0, 2.0)
    vec4 v7 = vec4(-1.0, -1.0, -1.0, -1.0);  // %7 = const (-1.0, -1.0, -1.0, -1.0)
    vec4 v8 = (v1 * v6 + v7);  // %8 = mad %1, %6, %7
    vec4 v9 = clamp(v8, -1.0, 1.0);  // %9 = clamp %8 lo=-1.0 hi=1.0
    vec4 v10 = (sign(clamp(v9, -1.0, 1.0)) * floor(abs(clamp(v9, -1.0, 1.0)) * 255.0 + 0.5) / 255.0);  // %10 = quantize %9 bits=9 signed=true
    vec4 v11 = (v5 * v6 + v7);  // %11 = mad %5, %6, %7
    vec4 v12 = clamp(v11, -1.0, 1.0);  // %12 = clamp %11 lo=-1.0 hi=1.0
    vec4 v13 = (sign(clamp(v12, -1.0, 1.0)) * floor(abs(clamp(v12, -1.0, 1.0)) * 255.0 + 0.5) / 255.0);  // %13 = quantize %12 bits=9 signed=true
    vec4 v14 = vec4(dot(v10.xyz, v13.xyz));  // %14 = dp3 %10, %13
    vec4 v15 = clamp(v14, -1.0, 1.0);  // %15 = clamp %14 lo=-1.0 hi=1.0
    vec4 v16 = (sign(clamp(v15, -1.0, 1.0)) * floor(abs(clamp(v15, -1.0, 1.0)) * 255.0 + 0.5) / 255.0);  // %16 = quantize %15 bits=9 signed=true
    vec4 v17 = (v16 * v3);  // %17 = mul %16, %3
    vec4 v18 = clamp(v17, -1.0, 1.0);  // %18 = clamp %17 lo=-1.0 hi=1.0
    vec4 v19 = (sign(clamp(v18, -1.0, 1.0)) * floor(abs(clamp(v18, -1.0, 1.0)) * 255.0 + 0.5) / 255.0);  // %19 = quantize %18 bits=9 signed=true
    vec4 v20 = v16.wwww;  // %20 = swizzle %16 pattern=wwww
    vec4 v21 = u_c0;  // %21 = input c0
    vec4 v22 = mix(v21, v3, v5);  // %22 = lrp %5, %3, %21
    vec4 v23 = mix(v22, v19, greaterThan(v20, vec4(0.5)));  // %23 = cnd %20, %19, %22
    vec4 v24 = clamp(v23, -1.0, 1.0);  // %24 = clamp %23 lo=-1.0 hi=1.0
    vec4 v25 = (sign(clamp(v24, -1.0, 1.0)) * floor(abs(clamp(v24, -1.0, 1.0)) * 255.0 + 0.5) / 255.0);  // %25 = quantize %24 bits=9 signed=true
    vec4 out_color0 = v25;  // output color0 = %25
#line 10000
    vec4 color = out_color0;
    frag_color = color;
}
