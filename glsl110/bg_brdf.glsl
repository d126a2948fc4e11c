#version 110
// requires: bg_common.glsl
// Schlick's 1994 BRDF, single layer or coat over base (docs/shading.md 6.1-6.4), ported from
// src/betelgeuse/brdf.c. A layer is (c = reflectance, r = roughness, p = isotropy), every value
// already clamped to [0, 1] (section 5). f is the non-Dirac part evaluated against lights; the
// specular share is returned separately as the mirror weight m, traced as a ray.

// S(u) = C + (1 - C)(1 - u)^5. The power is four multiplications, as in the reference: pow is
// commonly exp2(5 log2(k)), which passes through log2(0) = -Inf at u = 1 and rounds differently.
vec3 bg_schlick_s(vec3 c, float u)
{
    float k = 1.0 - clamp(u, 0.0, 1.0);
    float k5 = k * k * k * k * k;
    return c + (1.0 - c) * k5;
}

// (a, b, c) = Lambertian, glossy and specular shares of roughness r (6.3).
vec3 bg_schlick_split(float r)
{
    float b = 4.0 * r * (1.0 - r);
    if (r < 0.5)
        return vec3(0.0, b, 1.0 - b);
    return vec3(1.0 - b, b, 0.0);
}

// D(t, v, v', w) of 6.2, written without dividing by v or v' so that no 0/0 appears at r = 0.
float bg_schlick_d(float r, float p, float t, float v, float vl, float w)
{
    if (!(v > 0.0) || !(vl > 0.0))
        return 0.0;
    float gv = r - r * v + v;
    float gl = r - r * vl + vl;
    float den = 12.5663706143592 * gv * gl;
    // Positive whenever v, v' > 0 in exact arithmetic; in float the product can still underflow
    // for grazing v, v' at a tiny r, which is treated like the grazing case itself.
    if (!(den > 0.0))
        return 0.0;
    float g2 = (v / gv) * (vl / gl);
    // Zenith factor: its denominator vanishes only at r = 0, t = 1, where b = 0 drops D anyway.
    float z_den = 1.0 + r * t * t - t * t;
    float z = z_den > 0.0 ? r / (z_den * z_den) : 0.0;
    // Azimuth factor: 0/0 at p = 0, w = 0. It is exactly 1 for an isotropic layer (p = 1) whatever
    // w is; saying so keeps float rounding out of it, so a scene without anisotropy needs no tangent.
    float a_den = p * p - p * p * w * w + w * w;
    float a = p >= 1.0 ? 1.0 : (a_den > 0.0 ? sqrt(p / a_den) : 0.0);
    return z * a / den + (1.0 - g2) / 3.14159265358979;
}

// a / pi + b D of one layer, without the spectral factor. D is skipped when b = 0 (r = 0 or 1),
// as in the reference: b D is zero there anyway, and mirrors and Lambertian layers save the work.
float bg_layer_directional(float r, float p, float t, float v, float vl, float w)
{
    vec3 abc = bg_schlick_split(r);
    float f = abc.x / 3.14159265358979;
    if (abc.y > 0.0)
        f += abc.y * bg_schlick_d(r, p, t, v, vl, w);
    return f;
}

// The non-Dirac BRDF of one layer: S(u) (a / pi + b D).
vec3 bg_layer_f(vec3 c, float r, float p, float u, float t, float v, float vl, float w)
{
    return bg_schlick_s(c, u) * bg_layer_directional(r, p, t, v, vl, w);
}

// f of 6.4 for the unit normal n (facing the viewer), unit tangent, unit view direction (towards
// the viewer) and unit light direction (towards the light). Zero unless both face the surface.
vec3 bg_brdf(vec3 n, vec3 tangent, vec3 view, vec3 light, vec3 base_c, float base_r, float base_p,
             bool has_coat, vec3 coat_c, float coat_r, float coat_p)
{
    float v = dot(n, view);
    float vl = dot(n, light);
    if (!(v > 0.0) || !(vl > 0.0))
        return vec3(0.0);
    // view = -light has no half vector: no contribution (section 11).
    vec3 h = view + light;
    if (!(bg_maxabs3(h) > 0.0))
        return vec3(0.0);
    h = bg_normalize_or(h, n);
    float t = min(dot(n, h), 1.0);
    float u = dot(view, h);
    // The azimuth of h is undefined when h is along n; w = 1 there is the tangent's own azimuth.
    vec3 hp = h - t * n;
    float w = 1.0;
    if (dot(hp, hp) > 1.0e-24)
        w = dot(bg_normalize_or(hp, tangent), tangent);
    w = clamp(w, -1.0, 1.0);

    vec3 s_base = bg_schlick_s(base_c, u);
    float d_base = bg_layer_directional(base_r, base_p, t, v, vl, w);
    if (!has_coat)
        return s_base * d_base;
    vec3 s_coat = bg_schlick_s(coat_c, u);
    float d_coat = bg_layer_directional(coat_r, coat_p, t, v, vl, w);
    // The coat passes on what it does not reflect, 1 - S'(u), to the base.
    return s_coat * d_coat + (1.0 - s_coat) * s_base * d_base;
}

// m of 6.4: the weight of the mirror ray, whose half vector is n itself, so u = v = cos_i.
vec3 bg_mirror_weight(float v, vec3 base_c, float base_r, bool has_coat, vec3 coat_c, float coat_r)
{
    float c_base = bg_schlick_split(base_r).z;
    vec3 s_base = bg_schlick_s(base_c, v);
    if (!has_coat)
        return c_base * s_base;
    float c_coat = bg_schlick_split(coat_r).z;
    vec3 s_coat = bg_schlick_s(coat_c, v);
    return c_coat * s_coat + (1.0 - s_coat) * c_base * s_base;
}
