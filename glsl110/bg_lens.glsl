#version 110
// requires: bg_scramble.glsl
// The thin lens (docs/shading.md 1.4), the twin of src/betelgeuse/cpu/lens.c: moves a pinhole ray
// (origin at the eye, unit dir) through the lens point disc (on the unit disc) scaled by aperture,
// towards where the pinhole ray meets the plane in focus, focus ahead along forward.
void bg_lens_ray(vec2 disc, float aperture, float focus, vec3 forward, vec3 right, vec3 up, inout vec4 origin,
                 inout vec4 dir)
{
    // target - offset divided by focus: the same direction, and no overflow for a far focus (1e20).
    vec3 offset = aperture * (disc.x * right + disc.y * up);
    origin.xyz += offset;
    dir.xyz = normalize(dir.xyz / dot(dir.xyz, forward) - offset / focus);
}
