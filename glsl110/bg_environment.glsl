#version 110
// requires: bg_common.glsl
// The environment (docs/shading.md 7.1), the twin of src/betelgeuse/cpu/environment_sample.c:
// what a ray that meets nothing sees, and the environment's direction at a camera sample when it
// lights the scene. info = (intensity, width, height, 1.0 with importance tables); the textures come
// as arguments, since the pass declares its samplers (MACS inputs): the image, the marginal table
// (one row of height texels) and the conditional one (width x height), all GL_NEAREST.

// The image's (u, v) in direction d. What a miss sees is info.x times the image there, sampled
// with the image's own filter and wrap, which the caller bakes into its lookup
// (bgi_gpu_texture_lookup: bg_texture_linear for GL_LINEAR, as the CPU's bgi_cpu_texture_sample).
vec2 bg_env_uv(vec3 d, vec4 info)
{
    float y = clamp(d.y, -1.0, 1.0);
    // Straight up or down the azimuth is any: the centre column, as on the CPU.
    float u = abs(d.x) + abs(d.z) > 0.0 ? 0.5 + atan(d.x, -d.z) / 6.283185307 : 0.5;
    float lo = 0.5 / info.z;
    return vec2(u, clamp(1.0 - acos(y) / 3.141592654, lo, 1.0 - lo));
}

// Value k of row `row` of a table texture of size `size`.
float bg_env_table(sampler2D table, float k, float row, vec2 size)
{
    return texture2D(table, vec2((k + 0.5) / size.x, (row + 0.5) / size.y)).r;
}

// The first index of the nondecreasing row (n values) whose value exceeds xi: halving steps from
// 2^13, as the CPU's first_above, unrolled by the compiler (a constant bound).
float bg_env_first_above(sampler2D table, float n, float row, vec2 size, float xi)
{
    float lo = 0.0;
    float step = 8192.0;
    for (int k = 0; k < 14; k++) {
        if (lo + step <= n && bg_env_table(table, lo + step - 1.0, row, size) <= xi)
            lo += step;
        step *= 0.5;
    }
    return lo;
}

// The environment's direction at the unit-square point xi (docs/shading.md 7.1): the unit direction
// l, the density pdf it is drawn with and its texel (i, j); false when there is none.
bool bg_env_direction(vec2 xi, sampler2D marginal, sampler2D conditional, vec4 info, out vec3 l, out float pdf,
                      out vec2 texel)
{
    const float pi = 3.141592654;
    float w = info.y, h = info.z;
    float i, j, u, v;
    l = vec3(0.0);
    pdf = 0.0;
    texel = vec2(0.0);
    if (info.w > 0.5) {
        j = bg_env_first_above(marginal, h, 0.0, vec2(h, 1.0), xi.x);
        float m1 = bg_env_table(marginal, j, 0.0, vec2(h, 1.0));
        float m0 = j > 0.0 ? bg_env_table(marginal, j - 1.0, 0.0, vec2(h, 1.0)) : 0.0;
        i = bg_env_first_above(conditional, w, j, vec2(w, h), xi.y);
        float c1 = bg_env_table(conditional, i, j, vec2(w, h));
        float c0 = i > 0.0 ? bg_env_table(conditional, i - 1.0, j, vec2(w, h)) : 0.0;
        if (!(m1 > m0) || !(c1 > c0))
            return false;
        v = (j + (xi.x - m0) / (m1 - m0)) / h;
        u = (i + (xi.y - c0) / (c1 - c0)) / w;
        float sin_t = sin(pi * v);
        if (!(sin_t > 0.0))
            return false;
        pdf = (m1 - m0) * (c1 - c0) * w * h / (2.0 * pi * pi * sin_t);
    } else {
        float y = 1.0 - 2.0 * xi.x;
        u = xi.y;
        v = 1.0 - acos(y) / pi;
        i = min(floor(u * w), w - 1.0);
        j = clamp(floor(v * h), 0.0, h - 1.0);
        pdf = 1.0 / (4.0 * pi);
    }
    float theta = pi * (1.0 - v), phi = 2.0 * pi * (u - 0.5);
    l = vec3(sin(theta) * sin(phi), cos(theta), -sin(theta) * cos(phi));
    texel = vec2(i, j);
    return true;
}

// The environment as a light at the unit-square point xi: its unit direction l and E_l (false when
// it brings nothing).
bool bg_env_light(vec2 xi, sampler2D env, sampler2D marginal, sampler2D conditional, vec4 info, out vec3 l,
                  out vec3 e)
{
    const float pi = 3.141592654;
    float pdf;
    vec2 texel;
    e = vec3(0.0);
    if (!bg_env_direction(xi, marginal, conditional, info, l, pdf, texel))
        return false;
    e = texture2D(env, vec2((texel.x + 0.5) / info.y, (texel.y + 0.5) / info.z)).rgb * (info.x / (pi * pdf));
    return bg_max3(e) > 0.0;
}

// The density with which bg_env_direction draws the direction d (docs/shading.md 13.3, p_env): the
// importance tables' of the texel d falls in, with the sine of d's unclamped v, or 1 / (4 pi); 0 at
// the poles, which the tables never draw.
float bg_env_pdf(vec3 d, sampler2D marginal, sampler2D conditional, vec4 info)
{
    const float pi = 3.141592654;
    if (info.w < 0.5)
        return 1.0 / (4.0 * pi);
    float w = info.y, h = info.z;
    float u = abs(d.x) + abs(d.z) > 0.0 ? 0.5 + atan(d.x, -d.z) / 6.283185307 : 0.5;
    float v = 1.0 - acos(clamp(d.y, -1.0, 1.0)) / pi;
    float i = min(floor(u * w), w - 1.0), j = clamp(floor(v * h), 0.0, h - 1.0);
    float sin_t = sin(pi * v);
    if (!(sin_t > 0.0))
        return 0.0;
    float m1 = bg_env_table(marginal, j, 0.0, vec2(h, 1.0));
    float m0 = j > 0.0 ? bg_env_table(marginal, j - 1.0, 0.0, vec2(h, 1.0)) : 0.0;
    float c1 = bg_env_table(conditional, i, j, vec2(w, h));
    float c0 = i > 0.0 ? bg_env_table(conditional, i - 1.0, j, vec2(w, h)) : 0.0;
    return (m1 - m0) * (c1 - c0) * w * h / (2.0 * pi * pi * sin_t);
}
