// specular_bump.fx technique Dot3_dx7, lowered for geforce2
// pass 1 of 1: P0
#version 330 core
// vertex shader for IR program 9f2876196ef1b065
in vec4 attr_position;
in vec4 attr_tangent;
in vec4 attr_normal;
in vec4 attr_texcoord1;
uniform vec4 u_vs_c8;
uniform vec4 u_vs_c9;
uniform vec4 u_vs_c10;
uniform vec4 u_vs_c11;
uniform vec4 u_vs_c0;
uniform vec4 u_vs_c1;
uniform vec4 u_vs_c2;
uniform vec4 u_vs_c12;
uniform vec4 u_vs_c3;
uniform vec4 u_vs_c14;
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
    vec4 v40 = u_vs_c12;  // %40 = input vs_c12
    vec4 v41 = (-v40);  // %41 = neg %40
    vec4 v42 = vec4(dot(v23.xyz, v41.xyz));  // %42 = dp3 %23, %41
    vec4 v43 = vec4(v42.x, v22.y, v22.z, v22.w);  // %43 = merge %22, %42 mask=x
    vec4 v44 = vec4(dot(v39.xyz, v41.xyz));  // %44 = dp3 %39, %41
    vec4 v45 = vec4(v43.x, v44.y, v43.z, v43.w);  // %45 = merge %43, %44 mask=y
    vec4 v46 = vec4(dot(v30.xyz, v41.xyz));  // %46 = dp3 %30, %41
    vec4 v47 = vec4(v45.x, v45.y, v46.z, v45.w);  // %47 = merge %45, %46 mask=z
    vec4 v48 = v47.xyzz;  // %48 = swizzle %47 pattern=xyzz
    vec4 v49 = vec4(0.5, 0.5, 0.5, 0.5);  // %49 = const (0.5, 0.5, 0.5, 0.5)
    vec4 v50 = (v48 * v49 + v49);  // %50 = mad %48, %49, %49
    vec4 v51 = vec4(1.0, 1.0, 1.0, 1.0);  // %51 = const (1.0, 1.0, 1.0, 1.0)
    vec4 v52 = vec4(v50.x, v50.y, v50.z, v51.w);  // %52 = merge %51, %50 mask=xyz
    vec4 v53 = vec4(v52.x, v52.y, v52.z, v49.w);  // %53 = merge %52, %49 mask=w
    vec4 v54 = vec4(dot(v0, v14));  // %54 = dp4 %0, %14
    vec4 v55 = vec4(dot(v0, v16));  // %55 = dp4 %0, %16
    vec4 v56 = vec4(v54.x, v55.y, v54.z, v54.w);  // %56 = merge %54, %55 mask=y
    vec4 v57 = vec4(dot(v0, v19));  // %57 = dp4 %0, %19
    vec4 v58 = vec4(v56.x, v56.y, v57.z, v56.w);  // %58 = merge %56, %57 mask=z
    vec4 v59 = u_vs_c3;  // %59 = input vs_c3
    vec4 v60 = vec4(dot(v0, v59));  // %60 = dp4 %0, %59
    vec4 v61 = vec4(v58.x, v58.y, v58.z, v60.w);  // %61 = merge %58, %60 mask=w
    vec4 v62 = (-v61);  // %62 = neg %61
    vec4 v63 = u_vs_c14;  // %63 = input vs_c14
    vec4 v64 = (v62 + v63);  // %64 = add %62, %63
    vec4 v65 = v64.xyzz;  // %65 = swizzle %64 pattern=xyzz
    vec4 v66 = vec4(dot(v65.xyz, v65.xyz));  // %66 = dp3 %65, %65
    vec4 v67 = vec4(v66.x, v22.y, v22.z, v22.w);  // %67 = merge %22, %66 mask=x
    vec4 v68 = v67.xxxx;  // %68 = swizzle %67 pattern=xxxx
    vec4 v69 = mix(inversesqrt(abs(v68)), vec4(uintBitsToFloat(0x7F800000u)), equal(v68, vec4(0.0)));  // %69 = rsq %68
    vec4 v70 = vec4(v69.x, v67.y, v67.z, v67.w);  // %70 = merge %67, %69 mask=x
    vec4 v71 = v70.xxxx;  // %71 = swizzle %70 pattern=xxxx
    vec4 v72 = (v65 * v71);  // %72 = mul %65, %71
    vec4 v73 = vec4(v72.x, v72.y, v72.z, v64.w);  // %73 = merge %64, %72 mask=xyz
    vec4 v74 = v73.xyzz;  // %74 = swizzle %73 pattern=xyzz
    vec4 v75 = (v74 + v41);  // %75 = add %74, %41
    vec4 v76 = vec4(v75.x, v75.y, v75.z, v73.w);  // %76 = merge %73, %75 mask=xyz
    vec4 v77 = v76.xyzz;  // %77 = swizzle %76 pattern=xyzz
    vec4 v78 = vec4(dot(v77.xyz, v77.xyz));  // %78 = dp3 %77, %77
    vec4 v79 = vec4(v78.x, v70.y, v70.z, v70.w);  // %79 = merge %70, %78 mask=x
    vec4 v80 = v79.xxxx;  // %80 = swizzle %79 pattern=xxxx
    vec4 v81 = mix(inversesqrt(abs(v80)), vec4(uintBitsToFloat(0x7F800000u)), equal(v80, vec4(0.0)));  // %81 = rsq %80
    vec4 v82 = vec4(v81.x, v79.y, v79.z, v79.w);  // %82 = merge %79, %81 mask=x
    vec4 v83 = v82.xxxx;  // %83 = swizzle %82 pattern=xxxx
    vec4 v84 = (v77 * v83);  // %84 = mul %77, %83
    vec4 v85 = vec4(v84.x, v84.y, v84.z, v76.w);  // %85 = merge %76, %84 mask=xyz
    vec4 v86 = vec4(dot(v23.xyz, v85.xyz));  // %86 = dp3 %23, %85
    vec4 v87 = vec4(v86.x, v22.y, v22.z, v22.w);  // %87 = merge %22, %86 mask=x
    vec4 v88 = vec4(dot(v39.xyz, v85.xyz));  // %88 = dp3 %39, %85
    vec4 v89 = vec4(v87.x, v88.y, v87.z, v87.w);  // %89 = merge %87, %88 mask=y
    vec4 v90 = vec4(dot(v30.xyz, v85.xyz));  // %90 = dp3 %30, %85
    vec4 v91 = vec4(v89.x, v89.y, v90.z, v89.w);  // %91 = merge %89, %90 mask=z
    vec4 v92 = v91.xyzz;  // %92 = swizzle %91 pattern=xyzz
    vec4 v93 = (v92 * v49 + v49);  // %93 = mad %92, %49, %49
    vec4 v94 = vec4(v93.x, v93.y, v93.z, v22.w);  // %94 = merge %22, %93 mask=xyz
    vec4 v95 = vec4(v94.x, v94.y, v94.z, v49.w);  // %95 = merge %94, %49 mask=w
    vec4 v96 = attr_texcoord1;  // %96 = input texcoord1
    vec4 v97 = vec4(v96.x, v96.y, v12.z, v12.w);  // %97 = merge %12, %96 mask=xy
    vec4 v98 = clamp(v53, 0.0, 1.0);  // %98 = saturate %53
    vec4 v99 = clamp(v95, 0.0, 1.0);  // %99 = saturate %95
    vec4 out_position = v11;  // output position = %11
    vec4 out_color0 = v98;  // output color0 = %98
    vec4 out_color1 = v99;  // output color1 = %99
    vec4 out_texcoord0 = v97;  // output texcoord0 = %97
    vec4 out_texcoord1 = v97;  // output texcoord1 = %97
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
