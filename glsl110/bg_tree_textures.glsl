#version 110
// requires:
// The renderer's tree textures (gpu/fused/tree_textures.c): reading the object tree's nodes and
// objects from two RGBA32F textures, which the fused plan's tree variant walks (docs/gpu_pipeline.md,
// "Object tree"), and testing a box, which the mesh walks of every plan do too (bg_tree_inverse,
// bg_tree_box). The walks themselves are generated per scene (gpu/fused/fused_source.c,
// gpu/shared/mesh_source.c), since a leaf calls the intersection code of the shapes the tree holds.
//
// The textures come as arguments, since the pass declares its samplers (MACS inputs). The nodes'
// texture holds two texels per node, {min.xyz, object} and {max.xyz, miss}, camera-relative and
// rounded outward; object is the leaf's object index (-1 for an interior node), miss the node after
// the node's subtree. The objects' texture holds BG_OBJECT_TEXELS texels per object: the three rows of its
// camera-relative world-to-object transform, then {shape, material, uv mapping, casts shadows},
// {uv scale, 0, 0} and the three rows of the linear part of its object-to-world transform. Both
// textures hold a power-of-two number of items per row, so the division that finds an item's row
// is exact in float: dims = (items per row, its inverse, 1 / texture width, 1 / texture height).

const float BG_OBJECT_TEXELS = 8.0;

// The centre of texel 0 of item `index`, the texels of one item lying side by side in one row, so
// that its texel f is at + vec2(f * dims.z, 0.0). With k items per row and `per` texels per item,
// q = index / k = row + column / k is exact (k a power of two), and q - floor(q) = column / k is
// the item's first texel over the width (column * per / (k * per)), also exact: the same texel
// centres as (column * per + f + 0.5) / width and (row + 0.5) / height, to the bit, in fewer
// operations (docs/benchmarks.md, "A leaner walk: what was measured"). Every term of the first
// coordinate is a multiple of 1 / (2 width) well within float's 24 bits, so each sum is exact.
vec2 bg_tree_at(vec4 dims, float index)
{
    float q = index * dims.y;
    float row = floor(q);
    return vec2(q - row + 0.5 * dims.z, (row + 0.5) * dims.w);
}

// The texel `field` of item `index` of a texture of `per` texels per item (per is implied by dims,
// and kept to name the layout at the call).
vec4 bg_tree_fetch(sampler2D s, vec4 dims, float per, float index, float field)
{
    return texture2D(s, bg_tree_at(dims, index) + vec2(field * dims.z, 0.0));
}

// The world-to-object transform of object i as a mat4 (columns), from its three stored rows.
mat4 bg_tree_to_object(sampler2D objects, vec4 dims, float i)
{
    vec2 at = bg_tree_at(dims, i);
    vec4 r0 = texture2D(objects, at);
    vec4 r1 = texture2D(objects, at + vec2(dims.z, 0.0));
    vec4 r2 = texture2D(objects, at + vec2(2.0 * dims.z, 0.0));
    return mat4(vec4(r0.x, r1.x, r2.x, 0.0), vec4(r0.y, r1.y, r2.y, 0.0), vec4(r0.z, r1.z, r2.z, 0.0),
                vec4(r0.w, r1.w, r2.w, 1.0));
}

// The normal matrix of a to_object matrix: the transpose of its linear part (scene/commit.c keeps
// normal_to_world so, and the unrolled variant uploads the same floats).
mat3 bg_tree_normal_matrix(mat4 m)
{
    return mat3(vec3(m[0].x, m[1].x, m[2].x), vec3(m[0].y, m[1].y, m[2].y), vec3(m[0].z, m[1].z, m[2].z));
}

// The three stored rows of the object's object-to-world linear part as a mat3 (columns).
mat3 bg_tree_to_world3(sampler2D objects, vec4 dims, float i)
{
    vec2 at = bg_tree_at(dims, i);
    vec4 r0 = texture2D(objects, at + vec2(5.0 * dims.z, 0.0));
    vec4 r1 = texture2D(objects, at + vec2(6.0 * dims.z, 0.0));
    vec4 r2 = texture2D(objects, at + vec2(7.0 * dims.z, 0.0));
    return mat3(vec3(r0.x, r1.x, r2.x), vec3(r0.y, r1.y, r2.y), vec3(r0.z, r1.z, r2.z));
}

// The reciprocal direction of a slab test, every component finite: a zero or tiny component
// becomes +-1e30, which places the slab's distances beyond every t the walk uses when the origin
// lies outside the slab and around the whole ray when it lies inside, as the exact test would.
vec3 bg_tree_inverse(vec3 d)
{
    vec3 s = vec3(greaterThanEqual(d, vec3(0.0))) * 2.0 - 1.0;
    return s / max(abs(d), vec3(1e-30));
}

// Whether the ray o + t d, t in [0, t_max], meets the box [lo, hi]. Each slab distance is a
// correctly rounded difference times a reciprocal, a few ulps from the exact value relative to
// itself, so widening the exit by 2^-16 of itself keeps every box the exact test enters (GPU
// division is not correctly rounded, hence more than the ulps of IEEE float).
bool bg_tree_box(vec3 o, vec3 inv, float t_max, vec3 lo, vec3 hi)
{
    vec3 t0 = (lo - o) * inv;
    vec3 t1 = (hi - o) * inv;
    vec3 near = min(t0, t1);
    vec3 far = max(t0, t1);
    float enter = max(max(near.x, near.y), max(near.z, 0.0));
    float exit = min(min(far.x, far.y), min(far.z, t_max));
    return enter <= exit * 1.0000152587890625;
}
