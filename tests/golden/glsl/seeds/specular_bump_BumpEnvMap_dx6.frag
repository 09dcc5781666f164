// specular_bump.fx technique BumpEnvMap_dx6, lowered for g400
// pass 1 of 1: P0
#version 330 core
// fragment shader for IR program 2ee7fc6d234992d7
in vec4 vary_color0;
in vec4 vary_texcoord0;
in vec4 vary_texcoord1;
in vec4 vary_texcoord2;
uniform vec4 u_bumpenv1_mat;
uniform sampler2D sampler0;
uniform sampler2D sampler1;
uniform sampler2D sampler2;
layout(location = 0, index = 0) out vec4 frag_color;

void main() {
#line 10
    vec4 v0 = vary_color0;  // %0 = input color0
    vec4 v1 = vec4(0.0, 0.0, 0.0, 0.0);  // %1 = const (0.0, 0.0, 0.0, 0.0)
    vec4 v2 = vary_texcoord0;  // %2 = input texcoord0
    vec4 v3 = texture(sampler0, v2.xy);  // %3 = sample %2 sampler=0
    vec4 v4 = (v3 * v0);  // %4 = mul %3, %0
    vec4 v5 = vec4(v4.x, v4.y, v4.z, v3.w);  // %5 = merge %4, %3 mask=w
    vec4 v6 = (sign(clamp(v5, 0.0, 1.0)) * floor(abs(clamp(v5, 0.0, 1.0)) * 255.0 + 0.5) / 255.0);  // %6 = quantize %5 bits=8
    vec4 v7 = vary_texcoord2;  // %7 = input texcoord2
    vec4 v8 = vary_texcoord1;  // %8 = input texcoord1
    vec4 v9 = texture(sampler1, v8.xy);  // %9 = sample %8 sampler=1
    vec4 v10 = u_bumpenv1_mat;  // %10 = input bumpenv1_mat
    vec4 v11 = v9.xxxx;  // %11 = swizzle %9 pattern=xxxx
    vec4 v12 = v10.xyxy;  // %12 = swizzle %10 pattern=xyxy
    vec4 v13 = v9.yyyy;  // %13 = swizzle %9 pattern=yyyy
    vec4 v14 = v10.zwzw;  // %14 = swizzle %10 pattern=zwzw
    vec4 v15 = (v13 * v14);  // %15 = mul %13, %14
    vec4 v16 = (v11 * v12 + v15);  // %16 = mad %11, %12, %15
    vec4 v17 = vec4(v16.x, v16.y, v1.z, v1.w);  // %17 = merge %1, %16 mask=xy
    vec4 v18 = (v7 + v17);  // %18 = add %7, %17
    vec4 v19 = texture(sampler2, v18.xy);  // %19 = sample %18 sampler=2
    vec4 v20 = (v19 + v6);  // %20 = add %19, %6
    vec4 v21 = clamp(v20, 0.0, 1.0);  // %21 = saturate %20
    vec4 v22 = vec4(v21.x, v21.y, v21.z, v6.w);  // %22 = merge %21, %6 mask=w
    vec4 v23 = (sign(clamp(v22, 0.0, 1.0)) * floor(abs(clamp(v22, 0.0, 1.0)) * 255.0 + 0.5) / 255.0);  // %23 = quantize %22 bits=8
    vec4 out_color0 = v23;  // output color0 = %23
#line 10000
    vec4 color = out_color0;
    frag_color = color;
}
