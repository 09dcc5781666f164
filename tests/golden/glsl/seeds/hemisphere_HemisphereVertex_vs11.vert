// hemisphere.fx technique HemisphereVertex_vs11, lowered for g400
// pass 1 of 1: P0
#version 330 core
// vertex shader for IR program 6e637f73112b4769
in vec4 attr_position;
in vec4 attr_normal;
in vec4 attr_texcoord0;
uniform vec4 u_vs_c8;
uniform vec4 u_vs_c9;
uniform vec4 u_vs_c10;
uniform vec4 u_vs_c11;
uniform vec4 u_vs_c0;
uniform vec4 u_vs_c1;
uniform vec4 u_vs_c2;
uniform vec4 u_vs_c40;
uniform vec4 u_vs_c33;
uniform vec4 u_vs_c42;
uniform vec4 u_vs_c41;
uniform vec4 u_vs_c44;
uniform vec4 u_vs_c43;
uniform vec2 d3d_pixel_size;  // (2/W, 2/H): one pixel in NDC
out vec4 vary_color0;
out vec4 vary_texcoord0;

void main() {
#line 18
    vec4 v0 = attr_position;  // %0 = input position
    vec4 v1 = u_vs_c8;  // %1 = input vs_c8
    vec4 v2 = vec4(dot(v0, v1));  // %2 = dp4 %0, %1
    vec4 v3 = u_vs_c9;  // %3 = input vs_c9
    vec4 v4 = vec4(dot(v0, v3));  // %4 = dp4 %0, %3
    vec4 v5 = vec4(v2.x, v4.y, v2.z, v2.w);  // %5 = merge %2, %4 mask=y
    vec4 v6 = u_vs_c10;  // %6 = input vs_c10
    vec4 v7 = vec4(dot(v0, v6));  // %7 = dp4 %0, %6
    vec4 v8 = vec4(v5.x, v5.y, v7.z, v5.w);  // %8 = merge %5, %7 mask=z
    vec4 v9 = u_vs_c11;  // %9 = input vs_c11
    vec4 v10 = vec4(dot(v0, v9));  // %10 = dp4 %0, %9
    vec4 v11 = vec4(v8.x, v8.y, v8.z, v10.w);  // %11 = merge %8, %10 mask=w
    vec4 v12 = vec4(0.0, 0.0, 0.0, 1.0);  // %12 = const (0.0, 0.0, 0.0, 1.0)
    vec4 v13 = attr_normal;  // %13 = input normal
    vec4 v14 = u_vs_c0;  // %14 = input vs_c0
    vec4 v15 = vec4(dot(v13.xyz, v14.xyz));  // %15 = dp3 %13, %14
    vec4 v16 = u_vs_c1;  // %16 = input vs_c1
    vec4 v17 = vec4(dot(v13.xyz, v16.xyz));  // %17 = dp3 %13, %16
    vec4 v18 = vec4(v15.x, v17.y, v15.z, v15.w);  // %18 = merge %15, %17 mask=y
    vec4 v19 = u_vs_c2;  // %19 = input vs_c2
    vec4 v20 = vec4(dot(v13.xyz, v19.xyz));  // %20 = dp3 %13, %19
    vec4 v21 = vec4(v18.x, v18.y, v20.z, v18.w);  // %21 = merge %18, %20 mask=z
    vec4 v22 = vec4(0.0, 0.0, 0.0, 0.0);  // %22 = const (0.0, 0.0, 0.0, 0.0)
    vec4 v23 = vec4(v21.x, v21.y, v21.z, v22.w);  // %23 = merge %22, %21 mask=xyz
    vec4 v24 = u_vs_c40;  // %24 = input vs_c40
    vec4 v25 = vec4(dot(v23.xyz, v24.xyz));  // %25 = dp3 %23, %24
    vec4 v26 = u_vs_c33;  // %26 = input vs_c33
    vec4 v27 = (v25 * v26 + v26);  // %27 = mad %25, %26, %26
    vec4 v28 = u_vs_c42;  // %28 = input vs_c42
    vec4 v29 = u_vs_c41;  // %29 = input vs_c41
    vec4 v30 = (v29 - v28);  // %30 = sub %29, %28
    vec4 v31 = (v30 * v27 + v28);  // %31 = mad %30, %27, %28
    vec4 v32 = u_vs_c44;  // %32 = input vs_c44
    vec4 v33 = attr_texcoord0;  // %33 = input texcoord0
    vec4 v34 = v33.zzzz;  // %34 = swizzle %33 pattern=zzzz
    vec4 v35 = (v32 - v34);  // %35 = sub %32, %34
    vec4 v36 = (v31 * v35);  // %36 = mul %31, %35
    vec4 v37 = u_vs_c43;  // %37 = input vs_c43
    vec4 v38 = (v36 * v37);  // %38 = mul %36, %37
    vec4 v39 = v33.xyyy;  // %39 = swizzle %33 pattern=xyyy
    vec4 v40 = vec4(v39.x, v39.y, v12.z, v12.w);  // %40 = merge %12, %39 mask=xy
    vec4 v41 = clamp(v38, 0.0, 1.0);  // %41 = saturate %38
    vec4 out_position = v11;  // output position = %11
    vec4 out_color0 = v41;  // output color0 = %41
    vec4 out_texcoord0 = v40;  // output texcoord0 = %40
#line 10000
    vary_color0 = clamp(out_color0, 0.0, 1.0);
    vary_texcoord0 = out_texcoord0;
    vec4 p = out_position;
    // D3D clip space to GL's: half-pixel shift to D3D9 pixel centres, y flipped
    // (GL row r is D3D row r), z in [0, w] to [-w, w].
    gl_Position = vec4(p.x + 0.5 * d3d_pixel_size.x * p.w,
                       -(p.y - 0.5 * d3d_pixel_size.y * p.w),
                       2.0 * p.z - p.w, p.w);
}
