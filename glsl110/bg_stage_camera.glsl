#version 110
// requires:
// Camera ray maps (docs/shading.md section 1). frag is gl_FragCoord.xy, the pixel centre in GL
// window coordinates: GL rows count bottom-up, so (2 frag.y / H - 1) equals the doc's
// (1 - 2 (y + 0.5) / H) for image row y = H - 1 - window row.

void bg_camera_ray(vec2 frag, vec2 size, vec3 eye, vec3 forward, vec3 right, vec3 up, vec2 tan_half,
                   out vec4 origin, out vec4 dir, out vec4 weight)
{
    float sx = (2.0 * frag.x / size.x - 1.0) * tan_half.x;
    float sy = (2.0 * frag.y / size.y - 1.0) * tan_half.y;
    origin = vec4(eye, -1.0);
    dir = vec4(normalize(forward + sx * right + sy * up), -1.0);
    weight = vec4(1.0);
}
