// hemisphere.fx technique SingleTexture, lowered for g400
// pass 1 of 1: P0
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
