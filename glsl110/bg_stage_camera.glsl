#version 110
// requires:
// Camera ray maps (docs/shading.md section 1). frag is gl_FragCoord.xy plus the view's shift, the
// sample point in GL window coordinates of the full frame of size `size` (1.1: the window's offset
// and the sample's offset from the pixel centre): GL rows count bottom-up, so (2 frag.y / H - 1)
// equals the doc's (1 - 2 (y + py) / H) for frame row y = H - 1 - window row.

void bg_camera_ray(vec2 frag, vec2 size, vec3 eye, vec3 forward, vec3 right, vec3 up, vec2 tan_half,
                   out vec4 origin, out vec4 dir, out vec4 weight)
{
    float sx = (2.0 * frag.x / size.x - 1.0) * tan_half.x;
    float sy = (2.0 * frag.y / size.y - 1.0) * tan_half.y;
    origin = vec4(eye, -1.0);
    dir = vec4(normalize(forward + sx * right + sy * up), -1.0);
    weight = vec4(1.0);
}

// The orthographic camera (docs/shading.md 1.5): the same window point, with half the view's world
// extent in extent; rays leave that point of the plane through eye across the view, all along forward.
void bg_camera_ray_parallel(vec2 frag, vec2 size, vec3 eye, vec3 forward, vec3 right, vec3 up, vec2 extent,
                            out vec4 origin, out vec4 dir, out vec4 weight)
{
    float sx = (2.0 * frag.x / size.x - 1.0) * extent.x;
    float sy = (2.0 * frag.y / size.y - 1.0) * extent.y;
    origin = vec4(eye + sx * right + sy * up, -1.0);
    dir = vec4(forward, -1.0);
    weight = vec4(1.0);
}
