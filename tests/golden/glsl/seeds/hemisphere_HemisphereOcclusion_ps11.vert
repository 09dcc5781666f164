// hemisphere.fx technique HemisphereOcclusion_ps11, lowered for geforce3
// pass 1 of 1: P0
#version 330 core
// vertex shader for IR program 28ee7fb64d6a4de7
in vec4 attr_position;
in vec4 attr_tangent;
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
uniform vec4 u_vs_c44;
uniform vec2 d3d_pixel_size;  // (2/W, 2/H): one pixel in NDC
out vec4 vary_color0;
out vec4 vary_texcoord0;
out vec4 vary_texcoord1;

void main() {
#line 16
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
    vec4 v13 = attr_tangent;  // %13 = input tangent
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
    vec4 v24 = attr_normal;  // %24 = input normal
    vec4 v25 = vec4(dot(v24.xyz, v14.xyz));  // %25 = dp3 %24, %14
    vec4 v26 = vec4(dot(v24.xyz, v16.xyz));  // %26 = dp3 %24, %16
    vec4 v27 = vec4(v25.x, v26.y, v25.z, v25.w);  // %27 = merge %25, %26 mask=y
    vec4 v28 = vec4(dot(v24.xyz, v19.xyz));  // %28 = dp3 %24, %19
    vec4 v29 = vec4(v27.x, v27.y, v28.z, v27.w);  // %29 = merge %27, %28 mask=z
    vec4 v30 = vec4(v29.x, v29.y, v29.z, v22.w);  // %30 = merge %22, %29 mask=xyz
    vec4 v31 = v30.yzxx;  // %31 = swizzle %30 pattern=yzxx
    vec4 v32 = v23.zxyy;  // %32 = swizzle %23 pattern=zxyy
    vec4 v33 = (v31 * v32);  // %33 = mul %31, %32
    vec4 v34 = vec4(v33.x, v33.y, v33.z, v22.w);  // %34 = merge %22, %33 mask=xyz
    vec4 v35 = v30.zxyy;  // %35 = swizzle %30 pattern=zxyy
    vec4 v36 = (-v35);  // %36 = neg %35
    vec4 v37 = v23.yzxx;  // %37 = swizzle %23 pattern=yzxx
    vec4 v38 = (v36 * v37 + v34);  // %38 = mad %36, %37, %34
    vec4 v39 = vec4(v38.x, v38.y, v38.z, v22.w);  // %39 = merge %22, %38 mask=xyz
    vec4 v40 = u_vs_c40;  // %40 = input vs_c40
    vec4 v41 = vec4(dot(v23.xyz, v40.xyz));  // %41 = dp3 %23, %40
    vec4 v42 = vec4(v41.x, v22.y, v22.z, v22.w);  // %42 = merge %22, %41 mask=x
    vec4 v43 = vec4(dot(v39.xyz, v40.xyz));  // %43 = dp3 %39, %40
    vec4 v44 = vec4(v42.x, v43.y, v42.z, v42.w);  // %44 = merge %42, %43 mask=y
    vec4 v45 = vec4(dot(v30.xyz, v40.xyz));  // %45 = dp3 %30, %40
    vec4 v46 = vec4(v44.x, v44.y, v45.z, v44.w);  // %46 = merge %44, %45 mask=z
    vec4 v47 = v46.xyzz;  // %47 = swizzle %46 pattern=xyzz
    vec4 v48 = u_vs_c33;  // %48 = input vs_c33
    vec4 v49 = (v47 * v48 + v48);  // %49 = mad %47, %48, %48
    vec4 v50 = vec4(1.0, 1.0, 1.0, 1.0);  // %50 = const (1.0, 1.0, 1.0, 1.0)
    vec4 v51 = vec4(v49.x, v49.y, v49.z, v50.w);  // %51 = merge %50, %49 mask=xyz
    vec4 v52 = u_vs_c44;  // %52 = input vs_c44
    vec4 v53 = v52.wwww;  // %53 = swizzle %52 pattern=wwww
    vec4 v54 = attr_texcoord0;  // %54 = input texcoord0
    vec4 v55 = v54.zzzz;  // %55 = swizzle %54 pattern=zzzz
    vec4 v56 = (v53 - v55);  // %56 = sub %53, %55
    vec4 v57 = vec4(v51.x, v51.y, v51.z, v56.w);  // %57 = merge %51, %56 mask=w
    vec4 v58 = vec4(v54.x, v54.y, v12.z, v12.w);  // %58 = merge %12, %54 mask=xy
    vec4 v59 = clamp(v57, 0.0, 1.0);  // %59 = saturate %57
    vec4 out_position = v11;  // output position = %11
    vec4 out_color0 = v59;  // output color0 = %59
    vec4 out_texcoord0 = v58;  // output texcoord0 = %58
    vec4 out_texcoord1 = v58;  // output texcoord1 = %58
#line 10000
    vary_color0 = clamp(out_color0, 0.0, 1.0);
    vary_texcoord0 = out_texcoord0;
    vary_texcoord1 = out_texcoord1;
    vec4 p = out_position;
    // D3D clip space to GL's: half-pixel shift to D3D9 pixel centres, y flipped
    // (GL row r is D3D row r), z in [0, w] to [-w, w].
    gl_Position = vec4(p.x + 0.5 * d3d_pixel_size.x * p.w,
                       -(p.y - 0.5 * d3d_pixel_size.y * p.w),
                       2.0 * p.z - p.w, p.w);
}
