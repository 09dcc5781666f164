// phong.fx technique PerPixelPhong_ps20, lowered for geforcefx5900
// pass 1 of 1: P0
#version 330 core
// fragment shader for IR program 049a4d86de0489f8
in vec4 vary_texcoord0;
in vec4 vary_texcoord1;
in vec4 vary_texcoord2;
uniform vec4 u_ps_c3;
uniform vec4 u_ps_c2;
uniform vec4 u_ps_c1;
uniform vec4 u_ps_c5;
uniform vec4 u_ps_c4;
uniform sampler2D sampler0;
uniform sampler2D sampler1;
uniform sampler2D sampler2;
layout(location = 0, index = 0) out vec4 frag_color;

void main() {
#line 13
    vec4 v0 = vary_texcoord0;  // %0 = input texcoord0
    vec4 v1 = texture(sampler0, v0.xy);  // %1 = sample %0 sampler=0
    vec4 v2 = vec4(0.0, 0.0, 0.0, 0.0);  // %2 = const (0.0, 0.0, 0.0, 0.0)
    vec4 v3 = texture(sampler1, v0.xy);  // %3 = sample %0 sampler=1
    vec4 v4 = texture(sampler2, v0.xy);  // %4 = sample %0 sampler=2
    vec4 v5 = vec4(2.0, 2.0, 2.0, 2.0);  // %5 = const (2.0, 2.0, 2.0, 2.0)
    vec4 v6 = vec4(1.0, 1.0, 1.0, 1.0);  // %6 = const (1.0, 1.0, 1.0, 1.0)
    vec4 v7 = (-v6);  // %7 = neg %6
    vec4 v8 = (v3 * v5 + v7);  // %8 = mad %3, %5, %7
    vec4 v9 = vec4(v8.x, v8.y, v8.z, v3.w);  // %9 = merge %3, %8 mask=xyz
    vec4 v10 = vec4(dot(v9.xyz, v9.xyz));  // %10 = dp3 %9, %9
    vec4 v11 = vec4(v2.x, v2.y, v2.z, v10.w);  // %11 = merge %2, %10 mask=w
    vec4 v12 = v11.wwww;  // %12 = swizzle %11 pattern=wwww
    vec4 v13 = mix(inversesqrt(abs(v12)), vec4(uintBitsToFloat(0x7F800000u)), equal(v12, vec4(0.0)));  // %13 = rsq %12
    vec4 v14 = vec4(v11.x, v11.y, v11.z, v13.w);  // %14 = merge %11, %13 mask=w
    vec4 v15 = v14.wwww;  // %15 = swizzle %14 pattern=wwww
    vec4 v16 = (v9 * v15);  // %16 = mul %9, %15
    vec4 v17 = vec4(v16.x, v16.y, v16.z, v9.w);  // %17 = merge %9, %16 mask=xyz
    vec4 v18 = vary_texcoord1;  // %18 = input texcoord1
    vec4 v19 = vec4(dot(v18.xyz, v18.xyz));  // %19 = dp3 %18, %18
    vec4 v20 = v19.xxxx;  // %20 = swizzle %19 pattern=xxxx
    vec4 v21 = mix(inversesqrt(abs(v20)), vec4(uintBitsToFloat(0x7F800000u)), equal(v20, vec4(0.0)));  // %21 = rsq %20
    vec4 v22 = vec4(v19.x, v19.y, v19.z, v21.w);  // %22 = merge %19, %21 mask=w
    vec4 v23 = v22.wwww;  // %23 = swizzle %22 pattern=wwww
    vec4 v24 = (v18 * v23);  // %24 = mul %18, %23
    vec4 v25 = u_ps_c3;  // %25 = input ps_c3
    vec4 v26 = v25.xxxx;  // %26 = swizzle %25 pattern=xxxx
    vec4 v27 = u_ps_c2;  // %27 = input ps_c2
    vec4 v28 = v27.xxxx;  // %28 = swizzle %27 pattern=xxxx
    vec4 v29 = (v26 * v22 + v28);  // %29 = mad %26, %22, %28
    vec4 v30 = v29.xxxx;  // %30 = swizzle %29 pattern=xxxx
    vec4 v31 = mix(1.0 / v30, vec4(uintBitsToFloat(0x7F800000u)), equal(v30, vec4(0.0)));  // %31 = rcp %30
    vec4 v32 = vec4(dot(v24.xyz, v17.xyz));  // %32 = dp3 %24, %17
    vec4 v33 = clamp(v32, 0.0, 1.0);  // %33 = saturate %32
    vec4 v34 = vary_texcoord2;  // %34 = input texcoord2
    vec4 v35 = vec4(dot(v34.xyz, v34.xyz));  // %35 = dp3 %34, %34
    vec4 v36 = v35.xxxx;  // %36 = swizzle %35 pattern=xxxx
    vec4 v37 = mix(inversesqrt(abs(v36)), vec4(uintBitsToFloat(0x7F800000u)), equal(v36, vec4(0.0)));  // %37 = rsq %36
    vec4 v38 = vec4(v35.x, v35.y, v35.z, v37.w);  // %38 = merge %35, %37 mask=w
    vec4 v39 = v38.wwww;  // %39 = swizzle %38 pattern=wwww
    vec4 v40 = (v34 * v39);  // %40 = mul %34, %39
    vec4 v41 = (v32 * v5);  // %41 = mul %32, %5
    vec4 v42 = (-v24);  // %42 = neg %24
    vec4 v43 = (v41 * v17 + v42);  // %43 = mad %41, %17, %42
    vec4 v44 = vec4(dot(v43.xyz, v40.xyz));  // %44 = dp3 %43, %40
    vec4 v45 = clamp(v44, 0.0, 1.0);  // %45 = saturate %44
    vec4 v46 = v45.xxxx;  // %46 = swizzle %45 pattern=xxxx
    vec4 v47 = u_ps_c1;  // %47 = input ps_c1
    vec4 v48 = v47.xxxx;  // %48 = swizzle %47 pattern=xxxx
    vec4 v49 = mix(pow(abs(v46), v48), mix(vec4(uintBitsToFloat(0x7F800000u)), vec4(1.0), equal(v48, vec4(0.0))), bvec4(vec4(lessThanEqual(v48, vec4(0.0))) * vec4(equal(v46, vec4(0.0)))));  // %49 = pow %46, %48
    vec4 v50 = (v49 * v4);  // %50 = mul %49, %4
    vec4 v51 = (v33 * v1 + v50);  // %51 = mad %33, %1, %50
    vec4 v52 = (v51 * v31);  // %52 = mul %51, %31
    vec4 v53 = u_ps_c5;  // %53 = input ps_c5
    vec4 v54 = (v52 * v53);  // %54 = mul %52, %53
    vec4 v55 = u_ps_c4;  // %55 = input ps_c4
    vec4 v56 = (v1 * v55 + v54);  // %56 = mad %1, %55, %54
    vec4 out_color0 = v56;  // output color0 = %56
#line 10000
    vec4 color = out_color0;
    frag_color = color;
}
