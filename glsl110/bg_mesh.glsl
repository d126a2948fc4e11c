#version 110
// requires: bg_common.glsl
// Mesh objects in the fused plan's tree variant (docs/gpu_pipeline.md, "Meshes"; docs/shading.md
// 2.10): reading the mesh textures and a hit's attributes. The walks of a mesh's own tree are
// generated with the object tree's (gpu/fused_source.c), since they share its step count.
//
// The mesh data are two RGBA32F row-major arrays of texels, each addressed by a texel index, a whole
// float below 2^23, in rows of the same power-of-two width, so that the division that finds a
// texel's row is exact in float: dims = (texels per row, its inverse, 1 / the triangle texture's
// height, 1 / the node texture's height). The node texture holds every mesh's tree in pre-order: an
// interior node as two texels like the object tree's ({min.xyz, -1}, {max.xyz, miss}, miss the node
// texture's index of the node after the subtree), a leaf as three, its triangle's corners in place of
// a box ({v0, triangle}, {v1, miss}, {v2, 0}); the triangle texture six texels per triangle: {v0, u0},
// {v1, u1}, {v2, u2}, {n0, v0}, {n1, v1}, {n2, v2}: the object-space positions and normals of its
// corners (normals 0 where the mesh has none) with the corners' texture coordinates in the w lanes.
// Two textures rather than one: llvmpipe (Mesa 22.3) samples the texels of one RGBA32F texture
// past the first 2^23 wrongly (gpu/fused_tree.c), and a walk that chose between two halves of one
// index range made a frame of a million-triangle terrain 1.6-1.7 times as slow (docs/benchmarks.md,
// "Triangle meshes"); nodes and triangles each have their own texture, so every fetch knows which
// it reads.

// The centre of texel k of a texture of inv_rows = 1 / its height, from q = k / width = row +
// column / width (exact, the width a power of two): q - floor(q) = column / width exactly, so the
// centre (column + 0.5) / width, (row + 0.5) / height comes to the bit without the column's
// difference and product (docs/benchmarks.md, "A leaner walk: what was measured"). The texels
// after k are at q + i / width, exact too, which a walk step uses for a node's second and third.
vec2 bg_mesh_at(vec4 dims, float inv_rows, float q)
{
    float row = floor(q);
    return vec2(q - row + 0.5 * dims.y, (row + 0.5) * inv_rows);
}

vec4 bg_mesh_texel(sampler2D s, vec4 dims, float inv_rows, float k)
{
    return texture2D(s, bg_mesh_at(dims, inv_rows, k * dims.y));
}

// Texel k of the node texture.
vec4 bg_mesh_node(sampler2D nodes, vec4 dims, float k)
{
    return bg_mesh_texel(nodes, dims, dims.w, k);
}

// Texel q * width of the node texture (bg_mesh_at).
vec4 bg_mesh_node_at(sampler2D nodes, vec4 dims, float q)
{
    return texture2D(nodes, bg_mesh_at(dims, dims.w, q));
}

// Texel k of the triangle texture.
vec4 bg_mesh_tri(sampler2D tris, vec4 dims, float k)
{
    return bg_mesh_texel(tris, dims, dims.z, k);
}

// The world attributes of a hit on triangle texels `at` with barycentric weights bary (of v0, v1,
// v2), front true when the ray met the side (v1 - v0) x (v2 - v0) faces: g the geometric normal
// turned towards the ray, n the shading normal (interpolated where the mesh has normals, on the
// side of g the ray sees), the interpolated uv, dP/du in object space (0 without a uv direction),
// and the offset a ray leaving the point starts at along g: `ulps` float ulps of the magnitude of
// the point's terms (the camera-relative point, and the transformed vertex coordinates).
void bg_mesh_attributes(sampler2D tris, vec4 dims, float at, vec3 bary, bool front, mat3 normal_to_world,
                        mat3 to_world3, vec3 p, vec3 d, float ulps, out vec3 g, out vec3 n, out vec2 uv,
                        out vec3 dpdu, out float offset)
{
    vec4 a0 = bg_mesh_tri(tris, dims, at);
    vec4 a1 = bg_mesh_tri(tris, dims, at + 1.0);
    vec4 a2 = bg_mesh_tri(tris, dims, at + 2.0);
    vec4 b0 = bg_mesh_tri(tris, dims, at + 3.0);
    vec4 b1 = bg_mesh_tri(tris, dims, at + 4.0);
    vec4 b2 = bg_mesh_tri(tris, dims, at + 5.0);
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

// Texel k (a whole float) of a copy's coverage mask, four values to a triangle texel from first.
float bg_mesh_mask_value(sampler2D tris, vec4 dims, float first, float k)
{
    float texel = floor(k * 0.25);
    vec4 v = bg_mesh_tri(tris, dims, first + texel);
    float lane = k - 4.0 * texel;
    return lane < 0.5 ? v.x : lane < 1.5 ? v.y : lane < 2.5 ? v.z : v.w;
}

// The texel index along one axis after the wrap (clamp 1.0: clamp to the edge, else repeat). i is
// floor(x) or floor(x) + 1 for x in [-0.5, size - 0.5], so in [-1, size]: one whole-number step
// wraps it exactly, where i - size * floor(i / size) could meet a division that rounds size / size
// below 1 (GLSL allows an approximate one) and read texel size.
float bg_mesh_mask_wrap(float i, float size, float clamp_mode)
{
    if (clamp_mode > 0.5)
        return clamp(i, 0.0, size - 1.0);
    return i < 0.0 ? i + size : (i >= size ? i - size : i);
}

// The coverage mask at uv as the CPU reference samples a texture (cpu/texture_sample.c): GL_NEAREST
// or GL_LINEAR, done by hand on the copied channel, since the mask lives in the triangle texture.
// at = (first mask texel, width, height, nearest), wrap.z = 1.0 for clamp.
float bg_mesh_mask(sampler2D tris, vec4 dims, vec4 at, vec2 uv, float clamp_mode)
{
    vec2 size = at.yz;
    vec2 s = clamp_mode > 0.5 ? clamp(uv, 0.0, 1.0) : uv - floor(uv);
    if (at.w > 0.5) {
        vec2 i = min(floor(s * size), size - 1.0);
        return bg_mesh_mask_value(tris, dims, at.x, i.y * size.x + i.x);
    }
    vec2 xy = s * size - 0.5;
    vec2 f = floor(xy);
    vec2 a = xy - f;
    float i0 = bg_mesh_mask_wrap(f.x, size.x, clamp_mode);
    float i1 = bg_mesh_mask_wrap(f.x + 1.0, size.x, clamp_mode);
    float j0 = bg_mesh_mask_wrap(f.y, size.y, clamp_mode);
    float j1 = bg_mesh_mask_wrap(f.y + 1.0, size.y, clamp_mode);
    float t00 = bg_mesh_mask_value(tris, dims, at.x, j0 * size.x + i0);
    float t10 = bg_mesh_mask_value(tris, dims, at.x, j0 * size.x + i1);
    float t01 = bg_mesh_mask_value(tris, dims, at.x, j1 * size.x + i0);
    float t11 = bg_mesh_mask_value(tris, dims, at.x, j1 * size.x + i1);
    return (1.0 - a.x) * (1.0 - a.y) * t00 + a.x * (1.0 - a.y) * t10 + (1.0 - a.x) * a.y * t01 + a.x * a.y * t11;
}

// Whether the point of weights b on triangle tri of the copy whose first triangle texel is first is
// there for rays (docs/shading.md 2.11): the copy's filter record, three texels before its first
// triangle (gpu/shared/meshes.c), its first texel r0 read once per walk, drops a front-only triangle's back (the side its object-space
// winding points away from) and a cut-out's points of coverage below the cut-off.
bool bg_mesh_keeps(sampler2D tris, vec4 dims, vec4 r0, float first, float tri, vec3 b, bool front)
{
    float flags = r0.x;
    if (flags == 0.0)
        return true;
    if (mod(flags, 2.0) == 1.0 && !front)
        return false;
    if (flags < 4.0)
        return true;
    float coverage = r0.z;
    if (flags >= 8.0) {
        vec4 at = bg_mesh_tri(tris, dims, first - 2.0);
        vec4 r2 = bg_mesh_tri(tris, dims, first - 1.0);
        float k = first + 6.0 * tri;
        vec2 t0 = vec2(bg_mesh_tri(tris, dims, k).w, bg_mesh_tri(tris, dims, k + 3.0).w);
        vec2 t1 = vec2(bg_mesh_tri(tris, dims, k + 1.0).w, bg_mesh_tri(tris, dims, k + 4.0).w);
        vec2 t2 = vec2(bg_mesh_tri(tris, dims, k + 2.0).w, bg_mesh_tri(tris, dims, k + 5.0).w);
        vec2 uv = (b.x * t0 + b.y * t1 + b.z * t2) * r2.xy;
        coverage *= bg_mesh_mask(tris, dims, at, uv, r2.z);
    }
    return coverage >= r0.y;
}

// Whether the copy whose first triangle texel is first is open (BG_SIDES_BOTH): both sides lit as
// fronts and light passing straight through, as a plane's (its filter record's last lane).
bool bg_mesh_open(sampler2D tris, vec4 dims, float first)
{
    return bg_mesh_tri(tris, dims, first - 1.0).w > 0.5;
}
