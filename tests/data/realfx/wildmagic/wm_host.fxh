// Ours (the effects project), not Wild Magic's: the values Wild Magic 5's renderer hands its
// shaders' uniform parameters (its ShaderFloat classes PVWMatrixConstant, WMatrixConstant,
// CameraModelPositionConstant, Material*Constant, Light*Constant), as effect parameters bound
// by semantic, so a D3DX host supplies them. Wild Magic multiplies column vectors
// (mul(PVWMatrix, p)), so its matrices are the transposes of Direct3D's row-vector ones.
// Model space is world space here (the scene's meshes have an identity world matrix).
// The material and the light's ambient/specular are our choice (a sample application's).

float4x4 PVWMatrix : WORLDVIEWPROJECTIONTRANSPOSE;
float4x4 WMatrix : WORLDTRANSPOSE;
float3 CameraModelPosition : CAMERAPOSITION;

float3 MaterialEmissive = {0.0, 0.0, 0.0};
float3 MaterialAmbient = {0.2, 0.2, 0.25};
float4 MaterialDiffuse = {0.9, 0.6, 0.3, 1.0};
float4 MaterialSpecular = {0.5, 0.5, 0.5, 24.0};   // alpha: the specular exponent

float3 LightModelPosition : LIGHTPOSITION;
float3 LightModelDirection : LIGHTDIRECTION;
float3 LightAmbient = {0.25, 0.25, 0.25};
float3 LightDiffuse : LIGHTCOLOR = {1.0, 1.0, 1.0};
float3 LightSpecular = {1.0, 1.0, 1.0};
// Wild Magic's Light: attenuation (constant, linear, quadratic, intensity), spot cutoff
// (angle, cos angle, sin angle, exponent); an angle of 0.5 radians
float4 LightAttenuation = {1.0, 0.0, 0.0, 1.0};
float4 LightSpotCutoff = {0.5, 0.87758256, 0.47942554, 1.0};

// Two directional lights for DLight2MatTex: the scene's, and a dim one from below.
float3 Light0ModelDirection : LIGHTDIRECTION;
float3 Light1ModelDirection = {0.0, 1.0, 0.0};
float3 Light1Diffuse = {0.3, 0.3, 0.5};

texture BaseTexture;    // a stand-in checker unless the scene or --set gives one
texture SecondTexture;
