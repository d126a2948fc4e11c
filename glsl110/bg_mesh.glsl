#version 110
// requires: bg_common.glsl
// Mesh objects in the fused plan's tree variant (docs/gpu_pipeline.md, "Meshes"; docs/shading.md
// 2.10): reading the mesh texture and a hit's attributes. The walks of a mesh's own tree are
// generated with the object tree's (gpu/fused_source.c), since they share its step count.
//
// The mesh texture is one RGBA32F row-major array of texels addressed by a texel index, a whole
// float below 2^24; its width is a power of two, so the division that finds a texel's row is exact
// in float: dims = (texels per row, its inverse, 1 / width, 1 / height). Each mesh holds its tree's
// nodes, two texels each as in the object tree ({min.xyz, triangle or -1}, {max.xyz, miss}, miss the
// texel index of the node after the subtree), then six texels per triangle: {v0, u0}, {v1, u1},
// {v2, u2}, {n0, v0}, {n1, v1}, {n2, v2}: the object-space positions and normals of its corners
// (normals 0 where the mesh has none) with the corners' texture coordinates in the w lanes.

// The texel at index k. With BG_MESH_SPLIT defined (the generator does, for mesh data past 2^23
// texels) it is in s below 2^23 and in hi from there on (llvmpipe reads the texels of one texture
// past 2^23 wrongly: gpu/fused_tree.c), both textures with the rows 1 / dims.w; without, every
// texel is in s. The choice made the whole frame about 1.7 times as slow on llvmpipe (measured:
// `betelgeuse render` of the bunny at 1024x1024, compile included, median 2.6 s against 1.5 s), so
// scenes that fit one texture do not pay for it.
vec4 bg_mesh_fetch(sampler2D s, sampler2D hi, vec4 dims, float k)
{
#ifdef BG_MESH_SPLIT
    bool upper = k >= 8388608.0;
    float j = upper ? k - 8388608.0 : k;
#else
    float j = k;
#endif
    float row = floor(j * dims.y);
    float column = j - row * dims.x;
    vec2 at = vec2((column + 0.5) * dims.z, (row + 0.5) * dims.w);
#ifdef BG_MESH_SPLIT
    vec4 texel;
    if (upper)
        texel = texture2D(hi, at);
    else
        texel = texture2D(s, at);
    return texel;
#else
    return texture2D(s, at);
#endif
}

// The world attributes of a hit on triangle texels `at` with barycentric weights bary (of v0, v1,
// v2), front true when the ray met the side (v1 - v0) x (v2 - v0) faces: g the geometric normal
// turned towards the ray, n the shading normal (interpolated where the mesh has normals, on the
// side of g the ray sees), the interpolated uv, dP/du in object space (0 without a uv direction),
// and the offset a ray leaving the point starts at along g: `ulps` float ulps of the magnitude of
// the point's terms (the camera-relative point, and the transformed vertex coordinates).
void bg_mesh_attributes(sampler2D s, sampler2D hi, vec4 dims, float at, vec3 bary, bool front, mat3 normal_to_world,
                        mat3 to_world3, vec3 p, vec3 d, float ulps, out vec3 g, out vec3 n, out vec2 uv,
                        out vec3 dpdu, out float offset)
{
    vec4 a0 = bg_mesh_fetch(s, hi, dims, at);
    vec4 a1 = bg_mesh_fetch(s, hi, dims, at + 1.0);
    vec4 a2 = bg_mesh_fetch(s, hi, dims, at + 2.0);
    vec4 b0 = bg_mesh_fetch(s, hi, dims, at + 3.0);
    vec4 b1 = bg_mesh_fetch(s, hi, dims, at + 4.0);
    vec4 b2 = bg_mesh_fetch(s, hi, dims, at + 5.0);
    vec3 e1 = a1.xyz - a0.xyz;
    vec3 e2 = a2.xyz - a0.xyz;
    g = bg_normalize_or(normal_to_world * cross(e1, e2), -d);
    if (!front)
        g = -g;
    n = g;
    vec3 ns = bary.x * b0.xyz + bary.y * b1.xyz + bary.z * b2.xyz;
    if (dot(ns, ns) > 0.0) {
        vec3 w = normalize(normal_to_world * ns);
        float side = front ? 1.0 : -1.0;
        if (side * dot(w, g) < 0.0)
            side = -side;
        n = side * w;
    }
    vec2 t0 = vec2(a0.w, b0.w);
    vec2 t1 = vec2(a1.w, b1.w);
    vec2 t2 = vec2(a2.w, b2.w);
    uv = bary.x * t0 + bary.y * t1 + bary.z * t2;
    vec2 q1 = t1 - t0;
    vec2 q2 = t2 - t0;
    float det = q1.x * q2.y - q2.x * q1.y;
    dpdu = det != 0.0 ? (q2.y * e1 - q1.y * e2) / det : vec3(0.0);
    vec3 big = max(abs(a0.xyz), max(abs(a1.xyz), abs(a2.xyz)));
    mat3 m = mat3(abs(to_world3[0]), abs(to_world3[1]), abs(to_world3[2]));
    offset = ulps * 1.1920928955078125e-7 * bg_max3(abs(p) + m * big);
}
