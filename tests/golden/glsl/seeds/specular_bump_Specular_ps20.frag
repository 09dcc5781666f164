// specular_bump.fx technique Specular_ps20, lowered for geforcefx5900
// pass 1 of 1: P0
#version 330 core
// fragment shader for IR program c3b1831c16396ce1
in vec4 vary_texcoord0;
in vec4 vary_texcoord1;
in vec4 vary_texcoord2;
uniform vec4 u_ps_c1;
uniform vec4 u_ps_c2;
uniform sampler2D sampler0;
uniform sampler2D sampler1;
layout(location = 0, index = 0) out vec4 frag_color;

void main() {
#line 9
    vec4 v0 = vary_texcoord0;  // %0 = input texcoord0
    vec4 v1 = texture(sampler0, v0.xy);  // %1 = sample %0 sampler=0
    vec4 v2 = vec4(0.0, 0.0, 0.0, 0.0);  // %2 = const (0.0, 0.0, 0.0, 0.0)
    vec4 v3 = texture(sampler1, v0.xy);  // %3 = sample %0 sampler=1
    vec4 v4 = vec4(2.0, 2.0, 2.0, 2.0);  // %4 = const (2.0, 2.0, 2.0, 2.0)
    vec4 v5 = vec4(1.0, 1.0, 1.0, 1.0);  // %5 = const (1.0, 1.0, 1.0, 1.0)
    vec4 v6 = (-v5);  // %6 = neg %5
    vec4 v7 = (v3 * v4 + v6);  // %7 = mad %3, %4, %6
    vec4 v8 = vec4(v7.x, v7.y, v7.z, v3.w);  // %8 = merge %3, %7 mask=xyz
    vec4 v9 = (v8 * (dot(v8.xyz, v8.xyz) != 0.0 ? inversesqrt(dot(v8.xyz, v8.xyz)) : 3.4028235e+38));  // %9 = nrm %8
    vec4 v10 = vec4(v9.x, v9.y, v9.z, v2.w);  // %10 = merge %2, %9 mask=xyz
    vec4 v11 = vary_texcoord1;  // %11 = input texcoord1
    vec4 v12 = (v11 * (dot(v11.xyz, v11.xyz) != 0.0 ? inversesqrt(dot(v11.xyz, v11.xyz)) : 3.4028235e+38));  // %12 = nrm %11
    vec4 v13 = vec4(v12.x, v12.y, v12.z, v2.w);  // %13 = merge %2, %12 mask=xyz
    vec4 v14 = vary_texcoord2;  // %14 = input texcoord2
    vec4 v15 = (v14 * (dot(v14.xyz, v14.xyz) != 0.0 ? inversesqrt(dot(v14.xyz, v14.xyz)) : 3.4028235e+38));  // %15 = nrm %14
    vec4 v16 = vec4(v15.x, v15.y, v15.z, v2.w);  // %16 = merge %2, %15 mask=xyz
    vec4 v17 = vec4(dot(v10.xyz, v13.xyz));  // %17 = dp3 %10, %13
    vec4 v18 = clamp(v17, 0.0, 1.0);  // %18 = saturate %17
    vec4 v19 = vec4(dot(v10.xyz, v16.xyz));  // %19 = dp3 %10, %16
    vec4 v20 = clamp(v19, 0.0, 1.0);  // %20 = saturate %19
    vec4 v21 = v20.xxxx;  // %21 = swizzle %20 pattern=xxxx
    vec4 v22 = u_ps_c1;  // %22 = input ps_c1
    vec4 v23 = v22.xxxx;  // %23 = swizzle %22 pattern=xxxx
    vec4 v24 = mix(pow(abs(v21), v23), mix(vec4(uintBitsToFloat(0x7F800000u)), vec4(1.0), equal(v23, vec4(0.0))), bvec4(vec4(lessThanEqual(v23, vec4(0.0))) * vec4(equal(v21, vec4(0.0)))));  // %24 = pow %21, %23
    vec4 v25 = u_ps_c2;  // %25 = input ps_c2
    vec4 v26 = (v24 * v25);  // %26 = mul %24, %25
    vec4 v27 = (v1 * v18 + v26);  // %27 = mad %1, %18, %26
    vec4 out_color0 = v27;  // output color0 = %27
#line 10000
    vec4 color = out_color0;
    frag_color = color;
}
