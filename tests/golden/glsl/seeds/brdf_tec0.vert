// brdf.fx technique tec0, lowered for geforce3
// pass 1 of 1: p0
#version 330 core
// vertex shader for IR program 6b5638e0af0006ab
in vec4 attr_position;
in vec4 attr_normal;
in vec4 attr_texcoord1;
in vec4 attr_texcoord0;
uniform vec4 u_vs_c4;
uniform vec4 u_vs_c5;
uniform vec4 u_vs_c6;
uniform vec4 u_vs_c7;
uniform vec4 u_vs_c0;
uniform vec4 u_vs_c1;
uniform vec4 u_vs_c2;
uniform vec4 u_vs_c3;
uniform vec4 u_vs_c10;
uniform vec4 u_vs_c16;
uniform vec4 u_vs_c9;
uniform vec2 d3d_pixel_size;  // (2/W, 2/H): one pixel in NDC
out vec4 vary_color0;
out vec4 vary_texcoord0;
out vec4 vary_texcoord1;
out vec4 vary_texcoord2;
out vec4 vary_texcoord3;

void main() {
#line 17
    vec4 v0 = attr_position;  // %0 = input position
    vec4 v1 = u_vs_c4;  // %1 = input vs_c4
    vec4 v2 = vec4(dot(v0, v1));  // %2 = dp4 %0, %1
    vec4 v3 = u_vs_c5;  // %3 = input vs_c5
    vec4 v4 = vec4(dot(v0, v3));  // %4 = dp4 %0, %3
    vec4 v5 = vec4(v2.x, v4.y, v2.z, v2.w);  // %5 = merge %2, %4 mask=y
    vec4 v6 = u_vs_c6;  // %6 = input vs_c6
    vec4 v7 = vec4(dot(v0, v6));  // %7 = dp4 %0, %6
    vec4 v8 = vec4(v5.x, v5.y, v7.z, v5.w);  // %8 = merge %5, %7 mask=z
    vec4 v9 = u_vs_c7;  // %9 = input vs_c7
    vec4 v10 = vec4(dot(v0, v9));  // %10 = dp4 %0, %9
    vec4 v11 = vec4(v8.x, v8.y, v8.z, v10.w);  // %11 = merge %8, %10 mask=w
    vec4 v12 = vec4(0.0, 0.0, 0.0, 1.0);  // %12 = const (0.0, 0.0, 0.0, 1.0)
    vec4 v13 = u_vs_c0;  // %13 = input vs_c0
    vec4 v14 = vec4(dot(v0, v13));  // %14 = dp4 %0, %13
    vec4 v15 = u_vs_c1;  // %15 = input vs_c1
    vec4 v16 = vec4(dot(v0, v15));  // %16 = dp4 %0, %15
    vec4 v17 = vec4(v14.x, v16.y, v14.z, v14.w);  // %17 = merge %14, %16 mask=y
    vec4 v18 = u_vs_c2;  // %18 = input vs_c2
    vec4 v19 = vec4(dot(v0, v18));  // %19 = dp4 %0, %18
    vec4 v20 = vec4(v17.x, v17.y, v19.z, v17.w);  // %20 = merge %17, %19 mask=z
    vec4 v21 = u_vs_c3;  // %21 = input vs_c3
    vec4 v22 = vec4(dot(v0, v21));  // %22 = dp4 %0, %21
    vec4 v23 = vec4(v20.x, v20.y, v20.z, v22.w);  // %23 = merge %20, %22 mask=w
    vec4 v24 = vec4(0.0, 0.0, 0.0, 0.0);  // %24 = const (0.0, 0.0, 0.0, 0.0)
    vec4 v25 = attr_normal;  // %25 = input normal
    vec4 v26 = vec4(dot(v25.xyz, v13.xyz));  // %26 = dp3 %25, %13
    vec4 v27 = vec4(dot(v25.xyz, v15.xyz));  // %27 = dp3 %25, %15
    vec4 v28 = vec4(v26.x, v27.y, v26.z, v26.w);  // %28 = merge %26, %27 mask=y
    vec4 v29 = vec4(dot(v25.xyz, v18.xyz));  // %29 = dp3 %25, %18
    vec4 v30 = vec4(v28.x, v28.y, v29.z, v28.w);  // %30 = merge %28, %29 mask=z
    vec4 v31 = vec4(v30.x, v30.y, v30.z, v24.w);  // %31 = merge %24, %30 mask=xyz
    vec4 v32 = attr_texcoord1;  // %32 = input texcoord1
    vec4 v33 = vec4(dot(v32.xyz, v13.xyz));  // %33 = dp3 %32, %13
    vec4 v34 = vec4(dot(v32.xyz, v15.xyz));  // %34 = dp3 %32, %15
    vec4 v35 = vec4(v33.x, v34.y, v33.z, v33.w);  // %35 = merge %33, %34 mask=y
    vec4 v36 = vec4(dot(v32.xyz, v18.xyz));  // %36 = dp3 %32, %18
    vec4 v37 = vec4(v35.x, v35.y, v36.z, v35.w);  // %37 = merge %35, %36 mask=z
    vec4 v38 = vec4(v37.x, v37.y, v37.z, v24.w);  // %38 = merge %24, %37 mask=xyz
    vec4 v39 = v38.zxyw;  // %39 = swizzle %38 pattern=zxyw
    vec4 v40 = (-v39);  // %40 = neg %39
    vec4 v41 = v31.yzxw;  // %41 = swizzle %31 pattern=yzxw
    vec4 v42 = (v40 * v41);  // %42 = mul %40, %41
    vec4 v43 = v38.yzxw;  // %43 = swizzle %38 pattern=yzxw
    vec4 v44 = (-v43);  // %44 = neg %43
    vec4 v45 = v31.zxyw;  // %45 = swizzle %31 pattern=zxyw
    vec4 v46 = (-v42);  // %46 = neg %42
    vec4 v47 = (v44 * v45 + v46);  // %47 = mad %44, %45, %46
    vec4 v48 = v23.xyzz;  // %48 = swizzle %23 pattern=xyzz
    vec4 v49 = (-v48);  // %49 = neg %48
    vec4 v50 = u_vs_c10;  // %50 = input vs_c10
    vec4 v51 = (v49 + v50);  // %51 = add %49, %50
    vec4 v52 = vec4(v51.x, v51.y, v51.z, v23.w);  // %52 = merge %23, %51 mask=xyz
    vec4 v53 = v52.xyzz;  // %53 = swizzle %52 pattern=xyzz
    vec4 v54 = vec4(dot(v53.xyz, v53.xyz));  // %54 = dp3 %53, %53
    vec4 v55 = vec4(v54.x, v24.y, v24.z, v24.w);  // %55 = merge %24, %54 mask=x
    vec4 v56 = v55.xxxx;  // %56 = swizzle %55 pattern=xxxx
    vec4 v57 = mix(inversesqrt(abs(v56)), vec4(uintBitsToFloat(0x7F800000u)), equal(v56, vec4(0.0)));  // %57 = rsq %56
    vec4 v58 = vec4(v57.x, v55.y, v55.z, v55.w);  // %58 = merge %55, %57 mask=x
    vec4 v59 = v58.xxxx;  // %59 = swizzle %58 pattern=xxxx
    vec4 v60 = (v59 * v53);  // %60 = mul %59, %53
    vec4 v61 = vec4(v60.x, v60.y, v60.z, v52.w);  // %61 = merge %52, %60 mask=xyz
    vec4 v62 = v61.xyzz;  // %62 = swizzle %61 pattern=xyzz
    vec4 v63 = u_vs_c16;  // %63 = input vs_c16
    vec4 v64 = (-v63);  // %64 = neg %63
    vec4 v65 = (v62 + v64);  // %65 = add %62, %64
    vec4 v66 = vec4(v65.x, v65.y, v65.z, v58.w);  // %66 = merge %58, %65 mask=xyz
    vec4 v67 = v66.xyzz;  // %67 = swizzle %66 pattern=xyzz
    vec4 v68 = vec4(dot(v67.xyz, v67.xyz));  // %68 = dp3 %67, %67
    vec4 v69 = vec4(v68.x, v24.y, v24.z, v24.w);  // %69 = merge %24, %68 mask=x
    vec4 v70 = v69.xxxx;  // %70 = swizzle %69 pattern=xxxx
    vec4 v71 = mix(inversesqrt(abs(v70)), vec4(uintBitsToFloat(0x7F800000u)), equal(v70, vec4(0.0)));  // %71 = rsq %70
    vec4 v72 = vec4(v71.x, v69.y, v69.z, v69.w);  // %72 = merge %69, %71 mask=x
    vec4 v73 = v72.xxxx;  // %73 = swizzle %72 pattern=xxxx
    vec4 v74 = (v73 * v67);  // %74 = mul %73, %67
    vec4 v75 = vec4(v74.x, v74.y, v74.z, v66.w);  // %75 = merge %66, %74 mask=xyz
    vec4 v76 = vec4(dot(v61.xyz, v38.xyz));  // %76 = dp3 %61, %38
    vec4 v77 = vec4(v76.x, v12.y, v12.z, v12.w);  // %77 = merge %12, %76 mask=x
    vec4 v78 = vec4(dot(v61.xyz, v47.xyz));  // %78 = dp3 %61, %47
    vec4 v79 = vec4(v77.x, v78.y, v77.z, v77.w);  // %79 = merge %77, %78 mask=y
    vec4 v80 = vec4(dot(v61.xyz, v31.xyz));  // %80 = dp3 %61, %31
    vec4 v81 = vec4(v79.x, v79.y, v80.z, v79.w);  // %81 = merge %79, %80 mask=z
    vec4 v82 = vec4(dot(v64.xyz, v38.xyz));  // %82 = dp3 %64, %38
    vec4 v83 = vec4(v82.x, v12.y, v12.z, v12.w);  // %83 = merge %12, %82 mask=x
    vec4 v84 = vec4(dot(v64.xyz, v47.xyz));  // %84 = dp3 %64, %47
    vec4 v85 = vec4(v83.x, v84.y, v83.z, v83.w);  // %85 = merge %83, %84 mask=y
    vec4 v86 = vec4(dot(v64.xyz, v31.xyz));  // %86 = dp3 %64, %31
    vec4 v87 = vec4(v85.x, v85.y, v86.z, v85.w);  // %87 = merge %85, %86 mask=z
    vec4 v88 = vec4(dot(v75.xyz, v38.xyz));  // %88 = dp3 %75, %38
    vec4 v89 = vec4(v88.x, v12.y, v12.z, v12.w);  // %89 = merge %12, %88 mask=x
    vec4 v90 = vec4(dot(v75.xyz, v47.xyz));  // %90 = dp3 %75, %47
    vec4 v91 = vec4(v89.x, v90.y, v89.z, v89.w);  // %91 = merge %89, %90 mask=y
    vec4 v92 = vec4(dot(v75.xyz, v31.xyz));  // %92 = dp3 %75, %31
    vec4 v93 = vec4(v91.x, v91.y, v92.z, v91.w);  // %93 = merge %91, %92 mask=z
    vec4 v94 = attr_texcoord0;  // %94 = input texcoord0
    vec4 v95 = v94.xyyy;  // %95 = swizzle %94 pattern=xyyy
    vec4 v96 = vec4(v95.x, v95.y, v12.z, v12.w);  // %96 = merge %12, %95 mask=xy
    vec4 v97 = u_vs_c9;  // %97 = input vs_c9
    vec4 v98 = clamp(v97, 0.0, 1.0);  // %98 = saturate %97
    vec4 out_position = v11;  // output position = %11
    vec4 out_color0 = v98;  // output color0 = %98
    vec4 out_texcoord0 = v81;  // output texcoord0 = %81
    vec4 out_texcoord1 = v87;  // output texcoord1 = %87
    vec4 out_texcoord2 = v93;  // output texcoord2 = %93
    vec4 out_texcoord3 = v96;  // output texcoord3 = %96
#line 10000
    vary_color0 = clamp(out_color0, 0.0, 1.0);
    vary_texcoord0 = out_texcoord0;
    vary_texcoord1 = out_texcoord1;
    vary_texcoord2 = out_texcoord2;
    vary_texcoord3 = out_texcoord3;
    vec4 p = out_position;
    // D3D clip space to GL's: half-pixel shift to D3D9 pixel centres, y flipped
    // (GL row r is D3D row r), z in [0, w] to [-w, w].
    gl_Position = vec4(p.x + 0.5 * d3d_pixel_size.x * p.w,
                       -(p.y - 0.5 * d3d_pixel_size.y * p.w),
                       2.0 * p.z - p.w, p.w);
}
