// specular_bump.fx technique Emboss_dx6, lowered for rage128
// pass 1 of 2: Emboss
#version 330 core
// fragment shader for IR program 8945cc99b71b2ebf
in vec4 vary_texcoord0;
in vec4 vary_texcoord1;
uniform sampler2D sampler0;
uniform sampler2D sampler1;
layout(location = 0, index = 0) out vec4 frag_color;

void main() {
#line 6
    vec4 v0 = vary_texcoord0;  // %0 = input texcoord0
    vec4 v1 = texture(sampler0, v0.xy);  // %1 = sample %0 sampler=0
    vec4 v2 = (sign(clamp(v1, 0.0, 1.0)) * floor(abs(clamp(v1, 0.0, 1.0)) * 255.0 + 0.5) / 255.0);  // %2 = quantize %1 bits=8
    vec4 v3 = vary_texcoord1;  // %3 = input texcoord1
    vec4 v4 = texture(sampler1, v3.xy);  // %4 = sample %3 sampler=1
    vec4 v5 = vec4(1.0, 1.0, 1.0, 1.0);  // %5 = const (1.0, 1.0, 1.0, 1.0)
    vec4 v6 = (v5 - v4);  // %6 = sub %5, %4
    vec4 v7 = (v6 + v2);  // %7 = add %6, %2
    vec4 v8 = vec4(0.5, 0.5, 0.5, 0.5);  // %8 = const (0.5, 0.5, 0.5, 0.5)
    vec4 v9 = (v7 - v8);  // %9 = sub %7, %8
    vec4 v10 = clamp(v9, 0.0, 1.0);  // %10 = saturate %9
    vec4 v11 = vec4(v10.x, v10.y, v10.z, v2.w);  // %11 = merge %10, %2 mask=w
    vec4 v12 = (sign(clamp(v11, 0.0, 1.0)) * floor(abs(clamp(v11, 0.0, 1.0)) * 255.0 + 0.5) / 255.0);  // %12 = quantize %11 bits=8
    vec4 out_color0 = v12;  // output color0 = %12
#line 10000
    vec4 color = out_color0;
    frag_color = color;
}
// pass 2 of 2: Colour
#version 330 core
// fragment shader for IR program 297966781b8af26b
in vec4 vary_color0;
in vec4 vary_texcoord0;
uniform sampler2D sampler0;
layout(location = 0, index = 0) out vec4 frag_color;

void main() {
#line 5
    vec4 v0 = vary_color0;  // %0 = input color0
    vec4 v1 = vary_texcoord0;  // %1 = input texcoord0
    vec4 v2 = texture(sampler0, v1.xy);  // %2 = sample %1 sampler=0
    vec4 v3 = (v2 * v0);  // %3 = mul %2, %0
    vec4 v4 = vec4(v3.x, v3.y, v3.z, v2.w);  // %4 = merge %3, %2 mask=w
    vec4 v5 = (sign(clamp(v4, 0.0, 1.0)) * floor(abs(clamp(v4, 0.0, 1.0)) * 255.0 + 0.5) / 255.0);  // %5 = quantize %4 bits=8
    vec4 out_color0 = v5;  // output color0 = %5
#line 10000
    vec4 color = out_color0;
    frag_color = color;
}
