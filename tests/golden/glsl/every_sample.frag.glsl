#version 330 core
// fragment shader for IR program c299394adba300e8
in vec4 vary_texcoord0;
uniform sampler1D sampler0;
uniform sampler1D sampler1;
uniform sampler2D sampler2;
uniform sampler2D sampler3;
uniform sampler2D sampler4;
uniform sampler2D sampler5;
uniform sampler3D sampler6;
uniform sampler3D sampler7;
uniform sampler3D sampler8;
uniform samplerCube sampler9;
uniform samplerCube sampler10;
uniform samplerCube sampler11;
layout(location = 0, index = 0) out vec4 frag_color;

void main() {
#line 15
    vec4 v0 = vary_texcoord0;  // %0 = input texcoord0
    vec4 v1 = texture(sampler0, v0.x);  // %1 = sample %0 sampler=0 kind=1d
    vec4 v2 = textureProj(sampler1, v0.xw);  // %2 = sample %0 sampler=1 kind=1d proj=true
    vec4 v3 = (v1 + v2);  // %3 = add %1, %2
    vec4 v4 = texture(sampler2, v0.xy);  // %4 = sample %0 sampler=2
    vec4 v5 = (v3 + v4);  // %5 = add %3, %4
    vec4 v6 = textureProj(sampler3, v0.xyw);  // %6 = sample %0 sampler=3 proj=true
    vec4 v7 = (v5 + v6);  // %7 = add %5, %6
    vec4 v8 = texture(sampler4, v0.xy, v0.w);  // %8 = sample %0 sampler=4 bias=true
    vec4 v9 = (v7 + v8);  // %9 = add %7, %8
    vec4 v10 = textureLod(sampler5, v0.xy, v0.w);  // %10 = sample %0 sampler=5 lod=true
    vec4 v11 = (v9 + v10);  // %11 = add %9, %10
    vec4 v12 = texture(sampler6, v0.xyz);  // %12 = sample %0 sampler=6 kind=3d
    vec4 v13 = (v11 + v12);  // %13 = add %11, %12
    vec4 v14 = textureProj(sampler7, v0);  // %14 = sample %0 sampler=7 kind=3d proj=true
    vec4 v15 = (v13 + v14);  // %15 = add %13, %14
    vec4 v16 = textureLod(sampler8, v0.xyz, v0.w);  // %16 = sample %0 sampler=8 kind=3d lod=true
    vec4 v17 = (v15 + v16);  // %17 = add %15, %16
    vec4 v18 = texture(sampler9, v0.xyz);  // %18 = sample %0 sampler=9 kind=cube
    vec4 v19 = (v17 + v18);  // %19 = add %17, %18
    vec4 v20 = texture(sampler10, v0.xyz / v0.w);  // %20 = sample %0 sampler=10 kind=cube proj=true
    vec4 v21 = (v19 + v20);  // %21 = add %19, %20
    vec4 v22 = texture(sampler11, v0.xyz, v0.w);  // %22 = sample %0 sampler=11 kind=cube bias=true
    vec4 v23 = (v21 + v22);  // %23 = add %21, %22
    vec4 out_color0 = v23;  // output color0 = %23
#line 10000
    vec4 color = out_color0;
    frag_color = color;
}
