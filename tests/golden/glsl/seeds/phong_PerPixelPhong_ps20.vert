// phong.fx technique PerPixelPhong_ps20, lowered for geforcefx5900
// pass 1 of 1: P0
#version 330 core
// vertex shader for IR program 79b4a5f4a240bf04
in vec4 attr_position;
in vec4 attr_texcoord0;
in vec4 attr_tangent;
in vec4 attr_normal;
uniform vec4 u_vs_c0;
uniform vec4 u_vs_c1;
uniform vec4 u_vs_c2;
uniform vec4 u_vs_c3;
uniform vec4 u_vs_c4;
uniform vec4 u_vs_c5;
uniform vec4 u_vs_c6;
uniform vec4 u_vs_c7;
uniform vec4 u_vs_c9;
uniform vec4 u_vs_c8;
uniform vec2 d3d_pixel_size;  // (2/W, 2/H): one pixel in NDC
out vec4 vary_texcoord0;
out vec4 vary_texcoord1;
out vec4 vary_texcoord2;

void main() {
#line 16
    vec4 v0 = attr_position;  // %0 = input position
    vec4 v1 = u_vs_c0;  // %1 = input vs_c0
    vec4 v2 = vec4(dot(v0, v1));  // %2 = dp4 %0, %1
    vec4 v3 = u_vs_c1;  // %3 = input vs_c1
    vec4 v4 = vec4(dot(v0, v3));  // %4 = dp4 %0, %3
    vec4 v5 = vec4(v2.x, v4.y, v2.z, v2.w);  // %5 = merge %2, %4 mask=y
    vec4 v6 = u_vs_c2;  // %6 = input vs_c2
    vec4 v7 = vec4(dot(v0, v6));  // %7 = dp4 %0, %6
    vec4 v8 = vec4(v5.x, v5.y, v7.z, v5.w);  // %8 = merge %5, %7 mask=z
    vec4 v9 = u_vs_c3;  // %9 = input vs_c3
    vec4 v10 = vec4(dot(v0, v9));  // %10 = dp4 %0, %9
    vec4 v11 = vec4(v8.x, v8.y, v8.z, v10.w);  // %11 = merge %8, %10 mask=w
    vec4 v12 = vec4(0.0, 0.0, 0.0, 1.0);  // %12 = const (0.0, 0.0, 0.0, 1.0)
    vec4 v13 = attr_texcoord0;  // %13 = input texcoord0
    vec4 v14 = vec4(v13.x, v13.y, v12.z, v12.w);  // %14 = merge %12, %13 mask=xy
    vec4 v15 = u_vs_c4;  // %15 = input vs_c4
    vec4 v16 = vec4(dot(v0, v15));  // %16 = dp4 %0, %15
    vec4 v17 = u_vs_c5;  // %17 = input vs_c5
    vec4 v18 = vec4(dot(v0, v17));  // %18 = dp4 %0, %17
    vec4 v19 = vec4(v16.x, v18.y, v16.z, v16.w);  // %19 = merge %16, %18 mask=y
    vec4 v20 = u_vs_c6;  // %20 = input vs_c6
    vec4 v21 = vec4(dot(v0, v20));  // %21 = dp4 %0, %20
    vec4 v22 = vec4(v19.x, v19.y, v21.z, v19.w);  // %22 = merge %19, %21 mask=z
    vec4 v23 = u_vs_c7;  // %23 = input vs_c7
    vec4 v24 = vec4(dot(v0, v23));  // %24 = dp4 %0, %23
    vec4 v25 = vec4(v22.x, v22.y, v22.z, v24.w);  // %25 = merge %22, %24 mask=w
    vec4 v26 = vec4(0.0, 0.0, 0.0, 0.0);  // %26 = const (0.0, 0.0, 0.0, 0.0)
    vec4 v27 = attr_tangent;  // %27 = input tangent
    vec4 v28 = vec4(dot(v27.xyz, v15.xyz));  // %28 = dp3 %27, %15
    vec4 v29 = vec4(dot(v27.xyz, v17.xyz));  // %29 = dp3 %27, %17
    vec4 v30 = vec4(v28.x, v29.y, v28.z, v28.w);  // %30 = merge %28, %29 mask=y
    vec4 v31 = vec4(dot(v27.xyz, v20.xyz));  // %31 = dp3 %27, %20
    vec4 v32 = vec4(v30.x, v30.y, v31.z, v30.w);  // %32 = merge %30, %31 mask=z
    vec4 v33 = vec4(v32.x, v32.y, v32.z, v26.w);  // %33 = merge %26, %32 mask=xyz
    vec4 v34 = attr_normal;  // %34 = input normal
    vec4 v35 = vec4(dot(v34.xyz, v15.xyz));  // %35 = dp3 %34, %15
    vec4 v36 = vec4(dot(v34.xyz, v17.xyz));  // %36 = dp3 %34, %17
    vec4 v37 = vec4(v35.x, v36.y, v35.z, v35.w);  // %37 = merge %35, %36 mask=y
    vec4 v38 = vec4(dot(v34.xyz, v20.xyz));  // %38 = dp3 %34, %20
    vec4 v39 = vec4(v37.x, v37.y, v38.z, v37.w);  // %39 = merge %37, %38 mask=z
    vec4 v40 = vec4(v39.x, v39.y, v39.z, v26.w);  // %40 = merge %26, %39 mask=xyz
    vec4 v41 = v40.yzxx;  // %41 = swizzle %40 pattern=yzxx
    vec4 v42 = v33.zxyy;  // %42 = swizzle %33 pattern=zxyy
    vec4 v43 = (v41 * v42);  // %43 = mul %41, %42
    vec4 v44 = vec4(v43.x, v43.y, v43.z, v26.w);  // %44 = merge %26, %43 mask=xyz
    vec4 v45 = v40.zxyy;  // %45 = swizzle %40 pattern=zxyy
    vec4 v46 = (-v45);  // %46 = neg %45
    vec4 v47 = v33.yzxx;  // %47 = swizzle %33 pattern=yzxx
    vec4 v48 = (v46 * v47 + v44);  // %48 = mad %46, %47, %44
    vec4 v49 = vec4(v48.x, v48.y, v48.z, v44.w);  // %49 = merge %44, %48 mask=xyz
    vec4 v50 = u_vs_c9;  // %50 = input vs_c9
    vec4 v51 = (v50 - v25);  // %51 = sub %50, %25
    vec4 v52 = vec4(dot(v51.xyz, v33.xyz));  // %52 = dp3 %51, %33
    vec4 v53 = vec4(v52.x, v12.y, v12.z, v12.w);  // %53 = merge %12, %52 mask=x
    vec4 v54 = vec4(dot(v51.xyz, v49.xyz));  // %54 = dp3 %51, %49
    vec4 v55 = vec4(v53.x, v54.y, v53.z, v53.w);  // %55 = merge %53, %54 mask=y
    vec4 v56 = vec4(dot(v51.xyz, v40.xyz));  // %56 = dp3 %51, %40
    vec4 v57 = vec4(v55.x, v55.y, v56.z, v55.w);  // %57 = merge %55, %56 mask=z
    vec4 v58 = u_vs_c8;  // %58 = input vs_c8
    vec4 v59 = (v58 - v25);  // %59 = sub %58, %25
    vec4 v60 = vec4(dot(v59.xyz, v33.xyz));  // %60 = dp3 %59, %33
    vec4 v61 = vec4(v60.x, v12.y, v12.z, v12.w);  // %61 = merge %12, %60 mask=x
    vec4 v62 = vec4(dot(v59.xyz, v49.xyz));  // %62 = dp3 %59, %49
    vec4 v63 = vec4(v61.x, v62.y, v61.z, v61.w);  // %63 = merge %61, %62 mask=y
    vec4 v64 = vec4(dot(v59.xyz, v40.xyz));  // %64 = dp3 %59, %40
    vec4 v65 = vec4(v63.x, v63.y, v64.z, v63.w);  // %65 = merge %63, %64 mask=z
    vec4 out_position = v11;  // output position = %11
    vec4 out_texcoord0 = v14;  // output texcoord0 = %14
    vec4 out_texcoord1 = v57;  // output texcoord1 = %57
    vec4 out_texcoord2 = v65;  // output texcoord2 = %65
#line 10000
    vary_texcoord0 = out_texcoord0;
    vary_texcoord1 = out_texcoord1;
    vary_texcoord2 = out_texcoord2;
    vec4 p = out_position;
    // D3D clip space to GL's: half-pixel shift to D3D9 pixel centres, y flipped
    // (GL row r is D3D row r), z in [0, w] to [-w, w].
    gl_Position = vec4(p.x + 0.5 * d3d_pixel_size.x * p.w,
                       -(p.y - 0.5 * d3d_pixel_size.y * p.w),
                       2.0 * p.z - p.w, p.w);
}
