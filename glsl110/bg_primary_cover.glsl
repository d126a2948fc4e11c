#version 110
// requires:
// The conservative footprint of one triangle for primary visibility (gpu/fused/primary.c): a
// triangle drawn over every pixel whose centre the triangle's exact test might hit, which the
// triangle itself does not promise: the fill rule gives a centre on a shared edge to one side only,
// and the corners' float rounding moves the edges a little. Each vertex of the triangle computes the
// whole footprint from all three corners, in the triangle's own order, so that the three agree bit for
// bit, and then takes its own corner of it. Positions are window pixels (GL's origin, pixel centres at
// .5); the caller writes them out with w = 1, since the fragment computes its own depth.
//
// A triangle seen well in front of the eye is grown by a margin: each corner moves out along its
// bisector until both of its edges are `margin` further out (the corner's miter). The margin is a
// quarter pixel, far more than the rasteriser's snapping (GL asks for 4 subpixel bits at least), plus
// the projection's float error, which grows as a corner nears the eye plane. A sliver (a corner
// sharper than about 14 degrees, whose miter would reach far out), a triangle crossing the eye plane or
// one whose error would exceed two pixels is covered instead by a right triangle over its bounding
// rectangle, clipped to the view: the part in front of the eye, where a crossing edge's points run out
// to infinity towards the side its crossing point lies on.

// Window position and w of camera-relative point p, as the camera stage's ray maps it back.
vec3 bg_cover_project(vec3 p, vec3 forward, vec3 right, vec3 up, vec2 tan_half, vec2 size, vec2 shift, bool ortho)
{
    float w = ortho ? 1.0 : dot(p, forward);
    vec2 s = vec2(dot(p, right), dot(p, up)) / tan_half;
    return vec3((s / w + 1.0) * 0.5 * size - shift, w);
}

// The bounding rectangle (lo.xy, hi.zw) of the part of segment a-b (camera-relative, projected to
// qa, qb) in front of the eye, grown into box.
vec4 bg_cover_segment(vec3 a, vec3 b, vec3 qa, vec3 qb, vec3 right, vec3 up, vec4 box)
{
    if (qa.z > 0.0)
        box = vec4(min(box.xy, qa.xy), max(box.zw, qa.xy));
    if ((qa.z > 0.0) != (qb.z > 0.0)) {
        vec3 p = a + (b - a) * (qa.z / (qa.z - qb.z));
        vec2 s = vec2(dot(p, right), dot(p, up));
        if (s.x >= 0.0)
            box.z = 1e30;
        if (s.x <= 0.0)
            box.x = -1e30;
        if (s.y >= 0.0)
            box.w = 1e30;
        if (s.y <= 0.0)
            box.y = -1e30;
    }
    return box;
}

// The outward unit normal of edge a -> b of a triangle of orientation side (1 counter-clockwise).
vec2 bg_cover_normal(vec2 a, vec2 b, float side)
{
    vec2 e = normalize(b - a);
    return side * vec2(e.y, -e.x);
}

// Corner `corner` (0, 1, 2) of the footprint of the triangle whose camera-relative corners are
// p0, p1, p2; viewport is the output's size. An empty footprint is a point outside the view.
vec2 bg_cover_corner(vec3 p0, vec3 p1, vec3 p2, float corner, vec3 forward, vec3 right, vec3 up, vec2 tan_half,
                     vec2 size, vec2 shift, vec2 viewport, bool ortho)
{
    vec3 q0 = bg_cover_project(p0, forward, right, up, tan_half, size, shift, ortho);
    vec3 q1 = bg_cover_project(p1, forward, right, up, tan_half, size, shift, ortho);
    vec3 q2 = bg_cover_project(p2, forward, right, up, tan_half, size, shift, ortho);
    bool front = q0.z > 0.0 && q1.z > 0.0 && q2.z > 0.0;
    // The projection's error: a few float ulps of each coordinate before the division by w.
    float reach = max(length(p0) / max(abs(q0.z), 1e-30),
                      max(length(p1) / max(abs(q1.z), 1e-30), length(p2) / max(abs(q2.z), 1e-30)));
    float margin = 0.25 + 4e-6 * reach * max(size.x / tan_half.x, size.y / tan_half.y);
    float area = (q1.x - q0.x) * (q2.y - q0.y) - (q2.x - q0.x) * (q1.y - q0.y);
    if (front && margin < 2.0 && abs(area) > 1e-3) {
        float side = area > 0.0 ? 1.0 : -1.0;
        vec2 n01 = bg_cover_normal(q0.xy, q1.xy, side);
        vec2 n12 = bg_cover_normal(q1.xy, q2.xy, side);
        vec2 n20 = bg_cover_normal(q2.xy, q0.xy, side);
        float k0 = 1.0 + dot(n20, n01);
        float k1 = 1.0 + dot(n01, n12);
        float k2 = 1.0 + dot(n12, n20);
        // 1 + n.n' = 2 sin^2(angle / 2): the miter is margin / sin(angle / 2).
        if (min(k0, min(k1, k2)) > 0.03) {
            if (corner < 0.5)
                return q0.xy + margin * (n20 + n01) / k0;
            if (corner < 1.5)
                return q1.xy + margin * (n01 + n12) / k1;
            return q2.xy + margin * (n12 + n20) / k2;
        }
    }
    vec4 box = vec4(1e30, 1e30, -1e30, -1e30);
    box = bg_cover_segment(p0, p1, q0, q1, right, up, box);
    box = bg_cover_segment(p1, p2, q1, q2, right, up, box);
    box = bg_cover_segment(p2, p0, q2, q0, right, up, box);
    if (box.x > box.z || box.y > box.w)
        return vec2(-1e4); // nothing in front of the eye
    vec2 lo = max(box.xy - min(margin, 1e4) - 1.0, vec2(-2.0));
    vec2 hi = min(box.zw + min(margin, 1e4) + 1.0, viewport + 2.0);
    if (lo.x > hi.x || lo.y > hi.y)
        return vec2(-1e4); // beside the view
    // The right triangle with legs twice the rectangle's sides holds the rectangle.
    vec2 d = 2.0 * (hi - lo);
    if (corner < 0.5)
        return lo;
    return corner < 1.5 ? lo + vec2(d.x, 0.0) : lo + vec2(0.0, d.y);
}
