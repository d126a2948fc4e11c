#version 110
// requires:
// The slab and interval-clipping steps shared by the box (docs/shading.md 2.3) and the cylinder's
// caps (2.4), ported from clip() and slab() in src/betelgeuse/intersect.c. The interval is iv
// (lo, hi) with has = (lo bounded, hi bounded) and the outward prototype normals at both ends.

// A bound only replaces the current one when it is strictly tighter, so on a tie the constraint
// applied first keeps its normal (x before y before z; the cylinder's side before its caps).
bool bg_clip(float lo, vec3 normal_lo, float hi, vec3 normal_hi,
             inout vec2 iv, inout bvec2 has, inout vec3 n_lo, inout vec3 n_hi)
{
    if (!has.x || lo > iv.x) {
        iv.x = lo;
        n_lo = normal_lo;
        has.x = true;
    }
    if (!has.y || hi < iv.y) {
        iv.y = hi;
        n_hi = normal_hi;
        has.y = true;
    }
    return iv.x <= iv.y;
}

// The slab -1 <= oi + t di <= 1 along the unit axis; false when the line misses it.
// scale is |d'|inf of the whole direction.
bool bg_slab(float oi, float di, float scale, vec3 axis,
             inout vec2 iv, inout bvec2 has, inout vec3 n_lo, inout vec3 n_hi)
{
    // 2^-60 (float form of the reference's 2^-1000): past this test |ta|, |tb| < 2^60 / scale,
    // far from the float limit, so no Inf can appear.
    if (abs(di) <= scale * 8.6736174e-19 * (1.0 + abs(oi)) || di == 0.0)
        return oi >= -1.0 && oi <= 1.0;
    float ta = (-1.0 - oi) / di;
    float tb = (1.0 - oi) / di;
    // 0 - axis rather than -axis: the reference's normals have +0.0 off the axis, not -0.0.
    vec3 neg = vec3(0.0) - axis;
    if (di > 0.0)
        return bg_clip(ta, neg, tb, axis, iv, has, n_lo, n_hi);
    return bg_clip(tb, axis, ta, neg, iv, has, n_lo, n_hi);
}
