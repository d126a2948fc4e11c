/* POV-Ray 3.7 export of the paper scenes and timing of POV-Ray as a whole process (pov_export.h).
 *
 * The scene is built with scenes_build and translated from its committed state
 * (src/betelgeuse/scene_internal.h): every number in the .pov is the one our renderers use, so
 * nothing of scenes.c is duplicated here.
 *
 * Coordinates: our world is right-handed, POV-Ray's is left-handed. Mirroring z (S = diag(1, 1, -1))
 * maps one onto the other without mirroring the image: our default camera at +z looking at -z
 * becomes POV-Ray's usual camera at -z looking at +z, with x to the right and y up in both. Every
 * position and transform is written as S applied to ours. */
#include "pov_export.h" /* same directory: bench/lib objects are built without -Ibench */

#include <errno.h>
#include <fcntl.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/types.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

#include "betelgeuse/cpu/cpu_internal.h"
#include "betelgeuse/scene/scene_internal.h"
#include "betelgeuse/common/srgb.h"

enum { POV_PATH_MAX = 4096 };

static const double POV_PI = 3.14159265358979323846;

/* Formats into the caller's message buffer, which may be absent. */
static bool fail(char *message, size_t message_size, const char *format, ...)
{
    if (message && message_size > 0) {
        va_list args;
        va_start(args, format);
        vsnprintf(message, message_size, format, args);
        va_end(args);
    }
    return false;
}

static void clear_message(char *message, size_t message_size)
{
    if (message && message_size > 0)
        message[0] = '\0';
}

/* snprintf that reports truncation instead of silently cutting a path. */
static bool format_path(char *out, size_t size, const char *format, ...)
{
    va_list args;
    va_start(args, format);
    int n = vsnprintf(out, size, format, args);
    va_end(args);
    return n >= 0 && (size_t)n < size;
}

/* ---- finding povray ------------------------------------------------------------------------ */

/* The first executable "povray" on PATH, as execv needs a full path (the child only calls
 * async-signal-safe functions between fork and exec, and execvp is not one). */
static bool find_povray(char *out, size_t size)
{
    const char *path = getenv("PATH");
    if (!path || !*path)
        return false;
    const char *p = path;
    for (;;) {
        const char *end = strchr(p, ':');
        size_t len = end ? (size_t)(end - p) : strlen(p);
        /* An empty PATH entry means the current directory. */
        bool ok = len == 0 ? format_path(out, size, "./povray")
                           : format_path(out, size, "%.*s/povray", (int)len, p);
        struct stat st;
        if (ok && stat(out, &st) == 0 && S_ISREG(st.st_mode) && access(out, X_OK) == 0)
            return true;
        if (!end)
            return false;
        p = end + 1;
    }
}

bool pov_available(void)
{
    char path[POV_PATH_MAX];
    return find_povray(path, sizeof path);
}

/* ---- translation helpers ------------------------------------------------------------------- */

/* Our right-handed point or direction as a POV-Ray vector (z mirrored). %.17g keeps every double. */
static void put_vec(FILE *f, double x, double y, double z)
{
    fprintf(f, "<%.17g, %.17g, %.17g>", x, y, -z);
}

/* Writes an object's placement as POV-Ray's `matrix`: world_pov = S * to_world * A * q for a
 * POV-Ray prototype point q, where A re-labels the prototype's axes (see sphere_axes). POV-Ray
 * multiplies row vectors, so its 12 numbers are the columns of that 3x3 product, then the
 * translation. */
static void put_matrix(FILE *f, const double to_world[4][4], const double a[3][3])
{
    double w[3][3];
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++) {
            double s = 0.0;
            for (int k = 0; k < 3; k++)
                s += to_world[i][k] * a[k][j];
            w[i][j] = i == 2 ? -s : s;
        }
    fprintf(f, "  matrix <");
    for (int j = 0; j < 3; j++)
        fprintf(f, "%.17g, %.17g, %.17g, ", w[0][j], w[1][j], w[2][j]);
    fprintf(f, "%.17g, %.17g, %.17g>\n", to_world[0][3], to_world[1][3], -to_world[2][3]);
}

/* POV-Ray's spherical image map (map_type 1) puts u = 0 on its +x axis and lets u grow towards +z,
 * with v = 0.5 + asin(y) / pi. Ours (docs/shading.md 4) has u = 0.5 + atan2(x, z) / (2 pi) and
 * the same v. Feeding our prototype the point (x, y, z) = (-q.z, q.y, -q.x) for POV-Ray's prototype
 * point q makes the two u agree exactly (atan2(-q.z, -q.x) = angle(q) - pi), seam included. */
static const double sphere_axes[3][3] = {{0, 0, -1}, {0, 1, 0}, {-1, 0, 0}};
static const double identity_axes[3][3] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}};

/* Fits POV-Ray's diffuse term k (N.L)^brilliance to one isotropic Schlick layer of roughness r with
 * white reflectance: our light term is pi f v' E (docs/shading.md 8), i.e. (a + b pi D) v' E. The
 * fit is least squares on log(g v') against log(v') over views up to 75 degrees, lights up to
 * 87.5 degrees and five relative azimuths, using the library's own D, each sample weighted by its
 * brightness g v' so that the lit part of a surface, which dominates the image, fits best (this
 * lowered the paper scenes' largest error against the CPU reference). It is exact for r = 1
 * (Lambertian: k = 1, brilliance 1); otherwise Schlick's D depends on the view and the half-vector,
 * which POV-Ray's finish cannot express, so this is an approximation. */
static void fit_diffuse(double r, double *k, double *brilliance)
{
    double a, b, c;
    bgi_cpu_schlick_split(r, &a, &b, &c);
    if (b <= 0.0) {
        *k = a;
        *brilliance = 1.0;
        return;
    }
    double sx = 0, sy = 0, sxx = 0, sxy = 0, sw = 0;
    for (int iv = 0; iv <= 5; iv++) {
        double tv = iv * 15.0 * POV_PI / 180.0;
        double view[3] = {sin(tv), 0.0, cos(tv)};
        for (int il = 0; il < 18; il++) {
            double tl = (2.5 + 5.0 * il) * POV_PI / 180.0;
            for (int ia = 0; ia <= 4; ia++) {
                double phi = ia * 45.0 * POV_PI / 180.0;
                double light[3] = {sin(tl) * cos(phi), sin(tl) * sin(phi), cos(tl)};
                double h[3] = {view[0] + light[0], view[1] + light[1], view[2] + light[2]};
                double hl = sqrt(h[0] * h[0] + h[1] * h[1] + h[2] * h[2]);
                double t = h[2] / hl;
                double g = a + b * POV_PI * bgi_cpu_schlick_d(r, 1.0, t > 1.0 ? 1.0 : t, view[2], light[2], 1.0);
                double x = log(light[2]), y = log(g * light[2]);
                double wt = g * light[2];
                sx += wt * x; sy += wt * y; sxx += wt * x * x; sxy += wt * x * y;
                sw += wt;
            }
        }
    }
    double den = sw * sxx - sx * sx;
    *brilliance = (sw * sxy - sx * sy) / den;
    *k = exp((sy - *brilliance * sx) / sw);
}

/* Writes a committed texture back as an sRGB PNG: rows are flipped from GL order (row 0 = v = 0)
 * to file order (top row first) and each linear texel is re-encoded. For an 8-bit sRGB source this
 * gives back the original bytes (decode and encode are inverse, and the steps are far wider than
 * float rounding). */
static bool write_texture(const bg_texture_data *t, const char *path, char *message, size_t message_size)
{
    unsigned char *pixels = malloc((size_t)t->width * t->height * 4);
    if (!pixels)
        return fail(message, message_size, "pov_write_scene: out of memory for a %dx%d texture", t->width, t->height);
    for (int y = 0; y < t->height; y++)
        for (int x = 0; x < t->width; x++) {
            double src[4];
            bgi_texture_texel(t, (size_t)(t->height - 1 - y) * t->width + x, src);
            unsigned char *dst = pixels + ((size_t)y * t->width + x) * 4;
            for (int c = 0; c < 3; c++) {
                double l = src[c] < 0.0 ? 0.0 : src[c] > 1.0 ? 1.0 : src[c];
                dst[c] = (unsigned char)floor(bgi_linear_to_srgb(l) * 255.0 + 0.5);
            }
            dst[3] = 255;
        }
    bg_image image = {t->width, t->height, BG_PIXEL_RGBA8, 0, pixels};
    char png_message[512] = "";
    bg_status st = bg_png_save(path, &image, png_message, sizeof png_message);
    free(pixels);
    if (st != BG_OK)
        return fail(message, message_size, "pov_write_scene: %s",
                    png_message[0] ? png_message : bg_status_string(st));
    return true;
}

static bool is_uniform_white(const bg_color_param *p)
{
    return p->r == 1.0 && p->g == 1.0 && p->b == 1.0;
}

/* One material as a POV-Ray texture block; false (with the reason) for what the translation does
 * not cover. The paper scenes need only: a diffuse-ish single layer, optionally textured by a
 * spherical image on a sphere, with an ambient colour that is a constant or the same texture. */
static bool put_texture(FILE *f, const bg_scene_state *state, const bg_object_data *o, const char *scene_name,
                        char *message, size_t message_size)
{
    const bg_material *m = &state->materials[o->material];
    const bg_schlick_layer *base = &m->base;
    if (m->has_coat || m->transparency.value != 0.0 || m->emission.r != 0.0 || m->emission.g != 0.0 ||
        m->emission.b != 0.0 || base->roughness.texture || base->isotropy.texture || base->roughness.value < 0.5)
        return fail(message, message_size,
                    "scene %s: a material with a coat, transparency, emission, a mirror share or textured "
                    "roughness has no POV-Ray translation here", scene_name);
    uint32_t tex = base->reflectance.texture;
    if (tex && !(o->shape == BG_SHAPE_SPHERE && o->uv_mapping == BG_UV_SPHERICAL && o->uv_scale[0] == 1.0 &&
                 o->uv_scale[1] == 1.0 && is_uniform_white(&base->reflectance)))
        return fail(message, message_size,
                    "scene %s: only a white-scaled spherical texture on a sphere is translated", scene_name);
    if (m->ambient.texture != 0 && m->ambient.texture != tex)
        return fail(message, message_size, "scene %s: an ambient texture other than the colour texture", scene_name);
    if (m->ambient.texture == 0 && tex != 0 && (m->ambient.r != 0.0 || m->ambient.g != 0.0 || m->ambient.b != 0.0))
        return fail(message, message_size, "scene %s: an untextured ambient on a textured material", scene_name);

    /* POV-Ray's finish ambient multiplies the pigment; ours multiplies its own colour, so divide it
     * out (exact; with a texture both already share the same texel). */
    double c[3] = {base->reflectance.r, base->reflectance.g, base->reflectance.b};
    double amb[3] = {m->ambient.r, m->ambient.g, m->ambient.b};
    for (int i = 0; i < 3; i++) {
        if (tex)
            continue;
        if (c[i] > 0.0)
            amb[i] /= c[i];
        else if (amb[i] != 0.0)
            return fail(message, message_size, "scene %s: ambient on a black reflectance channel", scene_name);
    }
    double k, brilliance;
    fit_diffuse(base->roughness.value, &k, &brilliance);

    fprintf(f, "  texture {\n");
    if (tex)
        /* gamma srgb: the PNG holds sRGB bytes, decoded to linear like our BG_TEXTURE_SRGB;
         * interpolate 2 is bilinear, like our GL_LINEAR sampling (texel centres may differ by a
         * fraction of a texel). */
        fprintf(f, "    pigment { image_map { png \"%s_tex%u.png\" gamma srgb map_type 1 interpolate 2 } }\n",
                scene_name, (unsigned)tex);
    else
        fprintf(f, "    pigment { rgb <%.17g, %.17g, %.17g> }\n", c[0], c[1], c[2]);
    if (base->roughness.value == 1.0)
        fprintf(f, "    // Schlick layer of roughness 1: Lambertian, so diffuse 1 is exact except for the\n"
                   "    // spectral factor S(u), which brightens a non-white C at grazing half-angles.\n");
    else
        fprintf(f, "    // Schlick layer of roughness %.17g, isotropy %.17g: no POV-Ray counterpart.\n"
                   "    // Approximated by diffuse k (N.L)^brilliance fitted to our (a + b pi D) v'\n"
                   "    // (bench/lib/pov_export.c); S(u) is taken as C and anisotropy is ignored.\n",
                base->roughness.value, base->isotropy.value);
    fprintf(f,
            "    // Ambient is exact.\n"
            "    finish { ambient rgb <%.17g, %.17g, %.17g> diffuse %.17g brilliance %.17g\n"
            "             specular 0 phong 0 reflection 0 }\n"
            "  }\n",
            amb[0], amb[1], amb[2], k, brilliance);
    return true;
}

/* A point light. Ours gives col I / (kc + kl d + kq d^2); POV-Ray's fade gives
 * col' 2 / (1 + (d / fade_distance)^fade_power). No attenuation, linear only and quadratic only
 * map exactly (col' = col I / (2 kc), fade_distance kc / kl or sqrt(kc / kq)); both linear and
 * quadratic are approximated by power 2 matched at the light's distance to the scene's centre. */
static bool put_light(FILE *f, const bg_scene_state *state, const bg_light *l, const char *scene_name,
                      char *message, size_t message_size)
{
    if (l->type != BG_LIGHT_POINT || l->spot_cutoff_degrees != 180.0)
        return fail(message, message_size, "scene %s: only point lights without a cone are translated", scene_name);
    double kc = l->attenuation[0], kl = l->attenuation[1], kq = l->attenuation[2];
    if (kc <= 0.0)
        return fail(message, message_size, "scene %s: a light without constant attenuation has no POV-Ray fade",
                    scene_name);
    double scale = l->intensity / kc;
    fprintf(f, "light_source {\n  ");
    put_vec(f, l->position.x, l->position.y, l->position.z);
    if (kl == 0.0 && kq == 0.0) {
        fprintf(f, "\n  color rgb <%.17g, %.17g, %.17g>\n  // attenuation (%g, 0, 0): none, exact\n}\n",
                l->color[0] * scale, l->color[1] * scale, l->color[2] * scale, kc);
        return true;
    }
    double power, distance;
    const char *note = "exact";
    if (kq == 0.0) {
        power = 1.0;
        distance = kc / kl;
    } else if (kl == 0.0) {
        power = 2.0;
        distance = sqrt(kc / kq);
    } else {
        double centre[3] = {0, 0, 0};
        if (state->has_bounded_objects)
            for (int i = 0; i < 3; i++)
                centre[i] = 0.5 * (state->bounds_min[i] + state->bounds_max[i]);
        double dx = l->position.x - centre[0], dy = l->position.y - centre[1], dz = l->position.z - centre[2];
        double d0 = sqrt(dx * dx + dy * dy + dz * dz);
        if (d0 <= 0.0)
            d0 = 1.0;
        power = 2.0;
        distance = d0 * sqrt(kc / (kl * d0 + kq * d0 * d0));
        note = "approximate: power 2 matched at the distance to the scene's centre";
    }
    fprintf(f, "\n  color rgb <%.17g, %.17g, %.17g>\n  fade_distance %.17g fade_power %.17g\n"
               "  // attenuation (%g, %g, %g): %s\n}\n",
            l->color[0] * scale * 0.5, l->color[1] * scale * 0.5, l->color[2] * scale * 0.5, distance, power,
            kc, kl, kq, note);
    return true;
}

static bool write_pov(FILE *f, const bg_scene_state *s, const bg_render_settings *settings, const char *name,
                      char *message, size_t message_size)
{
    const bg_camera *cam = &s->camera.camera;
    fprintf(f,
            "// Scene \"%s\" (examples/scenes/scenes.c) for POV-Ray 3.7, written by bench/lib/pov_export.c\n"
            "// from the scene's committed state. Our right-handed coordinates appear with z negated.\n"
            "#version 3.7;\n"
            "// Linear colours throughout, like ours; the sRGB output encoding is set on the command\n"
            "// line (File_Gamma=sRGB). max_trace_level counts the camera ray, our max_depth does not.\n"
            "global_settings {\n"
            "  assumed_gamma 1.0\n"
            "  max_trace_level %d\n"
            "  adc_bailout %.17g\n"
            "  ambient_light rgb <%.17g, %.17g, %.17g>\n"
            "}\n"
            "background { rgb <%.17g, %.17g, %.17g> }\n\n",
            name, settings->max_depth + 1, settings->min_weight, s->ambient[0], s->ambient[1], s->ambient[2],
            settings->background[0], settings->background[1], settings->background[2]);
    /* Our fov is vertical; POV-Ray's angle is horizontal across the right vector, so both follow
     * the image's aspect ratio through image_width and image_height. */
    fprintf(f, "// Vertical field of view %.17g degrees, as ours.\ncamera {\n  perspective\n  location ",
            cam->fov_y_degrees);
    put_vec(f, cam->position.x, cam->position.y, cam->position.z);
    fprintf(f, "\n  right x*image_width/image_height\n  up y\n  sky ");
    put_vec(f, cam->up.x, cam->up.y, cam->up.z);
    fprintf(f, "\n  angle 2*degrees(atan(tan(radians(%.17g/2))*image_width/image_height))\n  look_at ",
            cam->fov_y_degrees);
    put_vec(f, cam->look_at.x, cam->look_at.y, cam->look_at.z);
    fprintf(f, "\n}\n\n");

    for (uint32_t i = 0; i < s->light_count; i++)
        if (!put_light(f, s, &s->lights[i], name, message, message_size))
            return false;
    fprintf(f, "\n");

    for (uint32_t i = 0; i < s->object_count; i++) {
        const bg_object_data *o = &s->objects[i];
        const double (*axes)[3];
        if (o->shape == BG_SHAPE_SPHERE) {
            fprintf(f, "sphere { <0, 0, 0>, 1\n");
            axes = sphere_axes;
        } else if (o->shape == BG_SHAPE_PLANE) {
            /* Our plane is a thin sheet lit from either side; POV-Ray's plane is a half-space whose
             * surface is lit the same way, and nothing here looks at its inside. */
            fprintf(f, "plane { <0, 1, 0>, 0\n");
            axes = identity_axes;
        } else {
            return fail(message, message_size, "scene %s: object %u is neither a sphere nor a plane", name,
                        (unsigned)(i + 1));
        }
        if (!put_texture(f, s, o, name, message, message_size))
            return false;
        put_matrix(f, o->to_world, axes);
        if (!o->casts_shadows)
            fprintf(f, "  no_shadow\n");
        fprintf(f, "}\n");
    }
    return true;
}

bool pov_write_scene(scene_id id, const char *dir, char *pov_path, size_t pov_path_size, char *message,
                     size_t message_size)
{
    clear_message(message, message_size);
    if (!dir || !*dir || !pov_path || pov_path_size == 0)
        return fail(message, message_size, "pov_write_scene: dir and pov_path are required");
    pov_path[0] = '\0';
    if (id != SCENE_PAPER_EARTH && id != SCENE_PAPER_EARTH_SHADOW)
        return fail(message, message_size, "pov_write_scene: scene %s is not one of the paper scenes",
                    scenes_name(id) ? scenes_name(id) : "(unknown id)");
    struct stat st;
    if (stat(dir, &st) != 0 || !S_ISDIR(st.st_mode))
        return fail(message, message_size, "pov_write_scene: %s is not a directory", dir);
    const char *name = scenes_name(id);
    char path[POV_PATH_MAX];
    if (!format_path(path, sizeof path, "%s/%s.pov", dir, name) || strlen(path) >= pov_path_size)
        return fail(message, message_size, "pov_write_scene: the path of %s/%s.pov does not fit", dir, name);

    bg_scene *scene = NULL;
    bg_status bst = bg_scene_create(NULL, &scene);
    if (bst == BG_OK)
        bst = scenes_build(id, scene);
    if (bst != BG_OK) {
        fail(message, message_size, "pov_write_scene: building %s failed: %s", name,
             scene && bg_scene_error_message(scene)[0] ? bg_scene_error_message(scene) : bg_status_string(bst));
        bg_scene_destroy(scene);
        return false;
    }
    const bg_scene_state *s = bgi_scene_committed(scene);
    bg_render_settings settings = bg_render_settings_init();
    bool ok = true;

    /* Every texture a material uses, once, next to the .pov (POV-Ray runs in that directory). */
    for (uint32_t t = 1; ok && t <= s->texture_count; t++) {
        bool used = false;
        for (uint32_t m = 0; m < s->material_count; m++)
            used = used || s->materials[m].base.reflectance.texture == t;
        char tex_path[POV_PATH_MAX];
        if (!used)
            continue;
        if (!format_path(tex_path, sizeof tex_path, "%s/%s_tex%u.png", dir, name, (unsigned)t))
            ok = fail(message, message_size, "pov_write_scene: a texture path in %s does not fit", dir);
        else
            ok = write_texture(&s->textures[t - 1], tex_path, message, message_size);
    }

    if (ok) {
        FILE *f = fopen(path, "w");
        if (!f) {
            ok = fail(message, message_size, "pov_write_scene: cannot create %s: %s", path, strerror(errno));
        } else {
            ok = write_pov(f, s, &settings, name, message, message_size);
            bool write_error = ferror(f) != 0;
            if (fclose(f) != 0 || write_error) {
                if (ok)
                    fail(message, message_size, "pov_write_scene: writing %s failed", path);
                ok = false;
            }
        }
    }
    bg_scene_destroy(scene);
    if (!ok)
        return false;
    memcpy(pov_path, path, strlen(path) + 1);
    return true;
}

/* ---- running povray ------------------------------------------------------------------------ */

/* POV-Ray's reason for failing: the last log line mentioning an error, else the last non-empty
 * line, without the progress carriage returns. */
static void log_last_line(const char *log_path, char *out, size_t size)
{
    out[0] = '\0';
    FILE *f = fopen(log_path, "r");
    if (!f)
        return;
    char line[512];
    bool have_error = false;
    while (fgets(line, sizeof line, f)) {
        char *cr = strrchr(line, '\r');
        char *text = cr ? cr + 1 : line;
        text[strcspn(text, "\n")] = '\0';
        bool is_error = strstr(text, "rror") != NULL;
        if (*text && strcmp(text, "Render failed") != 0 && (is_error || !have_error))
            snprintf(out, size, "%s", text);
        have_error = have_error || is_error;
    }
    fclose(f);
}

static double now_ms(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return ts.tv_sec * 1e3 + ts.tv_nsec / 1e6;
}

bool pov_render(const char *pov_path, int width, int height, int threads, const char *out_png, double *ms,
                char *message, size_t message_size)
{
    clear_message(message, message_size);
    if (!pov_path || !*pov_path || !out_png || !*out_png || !ms)
        return fail(message, message_size, "pov_render: pov_path, out_png and ms are required");
    *ms = 0.0;
    if (width < 1 || width > 16384 || height < 1 || height > 16384)
        return fail(message, message_size, "pov_render: image size %dx%d outside 1 .. 16384", width, height);
    if (threads < 1 || threads > 512)
        return fail(message, message_size, "pov_render: %d threads outside 1 .. 512", threads);
    char exe[POV_PATH_MAX];
    if (!find_povray(exe, sizeof exe))
        return fail(message, message_size, "pov_render: no povray executable on PATH");
    if (access(pov_path, R_OK) != 0)
        return fail(message, message_size, "pov_render: cannot read %s: %s", pov_path, strerror(errno));

    /* POV-Ray resolves image_map files against its working directory, so it runs in the .pov's
     * directory; the output path is made absolute first so it still means what the caller meant. */
    char dir[POV_PATH_MAX], out_abs[POV_PATH_MAX], log_path[POV_PATH_MAX], cwd[POV_PATH_MAX];
    const char *slash = strrchr(pov_path, '/');
    const char *base = slash ? slash + 1 : pov_path;
    bool fits = slash ? format_path(dir, sizeof dir, "%.*s", (int)(slash - pov_path + (slash == pov_path)), pov_path)
                      : format_path(dir, sizeof dir, ".");
    size_t stem = strlen(pov_path);
    if (stem > 4 && strcmp(pov_path + stem - 4, ".pov") == 0)
        stem -= 4;
    fits = fits && format_path(log_path, sizeof log_path, "%.*s.log", (int)stem, pov_path);
    if (out_png[0] == '/')
        fits = fits && format_path(out_abs, sizeof out_abs, "%s", out_png);
    else
        fits = fits && getcwd(cwd, sizeof cwd) && format_path(out_abs, sizeof out_abs, "%s/%s", cwd, out_png);
    char arg_in[POV_PATH_MAX + 8], arg_out[POV_PATH_MAX + 8], arg_w[32], arg_h[32], arg_t[48];
    fits = fits && format_path(arg_in, sizeof arg_in, "+I%s", base) &&
           format_path(arg_out, sizeof arg_out, "+O%s", out_abs);
    if (!fits)
        return fail(message, message_size, "pov_render: a path is too long");
    /* POV-Ray only says it could not write the image among its statistics; say it clearly. */
    char out_dir[POV_PATH_MAX];
    const char *out_slash = strrchr(out_abs, '/');
    format_path(out_dir, sizeof out_dir, "%.*s", (int)(out_slash - out_abs + (out_slash == out_abs)), out_abs);
    struct stat out_st;
    if (stat(out_dir, &out_st) != 0 || !S_ISDIR(out_st.st_mode) || access(out_dir, W_OK) != 0)
        return fail(message, message_size, "pov_render: %s is not a writable directory", out_dir);
    snprintf(arg_w, sizeof arg_w, "+W%d", width);
    snprintf(arg_h, sizeof arg_h, "+H%d", height);
    snprintf(arg_t, sizeof arg_t, "Work_Threads=%d", threads);
    /* -A no antialiasing, -D no display window, -P no pause, +FN8 8-bit PNG without alpha (-UA),
     * File_Gamma=sRGB to encode like our RGBA8 output, -V quiet progress. */
    char *const argv[] = {exe, arg_in, arg_out, arg_w, arg_h, "-A", "-D", "-P", "-UA", "+FN8",
                          "File_Gamma=sRGB", "-V", arg_t, NULL};

    int log_fd = open(log_path, O_WRONLY | O_CREAT | O_TRUNC, 0644);
    if (log_fd < 0)
        return fail(message, message_size, "pov_render: cannot create %s: %s", log_path, strerror(errno));
    int null_fd = open("/dev/null", O_RDONLY);
    if (null_fd < 0) {
        close(log_fd);
        return fail(message, message_size, "pov_render: cannot open /dev/null: %s", strerror(errno));
    }
    remove(out_abs); /* so a stale image cannot pass for this run's output */

    double start = now_ms();
    pid_t pid = fork();
    if (pid < 0) {
        close(log_fd);
        close(null_fd);
        return fail(message, message_size, "pov_render: fork failed: %s", strerror(errno));
    }
    if (pid == 0) {
        /* Only async-signal-safe calls until exec; 126/127 tell the parent what went wrong. */
        if (chdir(dir) != 0)
            _exit(126);
        if (dup2(null_fd, STDIN_FILENO) < 0 || dup2(log_fd, STDOUT_FILENO) < 0 || dup2(log_fd, STDERR_FILENO) < 0)
            _exit(126);
        execv(exe, argv);
        _exit(127);
    }
    close(log_fd);
    close(null_fd);
    int status = 0;
    pid_t waited;
    do
        waited = waitpid(pid, &status, 0);
    while (waited < 0 && errno == EINTR);
    double elapsed = now_ms() - start;
    if (waited < 0)
        return fail(message, message_size, "pov_render: waiting for povray failed: %s", strerror(errno));

    char why[512];
    log_last_line(log_path, why, sizeof why);
    if (WIFSIGNALED(status))
        return fail(message, message_size, "pov_render: povray was killed by signal %d (log %s)",
                    WTERMSIG(status), log_path);
    if (!WIFEXITED(status))
        return fail(message, message_size, "pov_render: povray ended abnormally (log %s)", log_path);
    int code = WEXITSTATUS(status);
    if (code == 126)
        return fail(message, message_size, "pov_render: cannot enter %s or redirect povray's output", dir);
    if (code == 127)
        return fail(message, message_size, "pov_render: cannot execute %s", exe);
    if (code != 0)
        return fail(message, message_size, "pov_render: povray exited with %d on %s: %s (log %s)", code,
                    pov_path, why[0] ? why : "no reason given", log_path);
    /* POV-Ray 3.7 exits 0 on some parse errors ("Render failed"), so the image is the proof. */
    if (access(out_abs, R_OK) != 0)
        return fail(message, message_size, "pov_render: povray wrote no image for %s: %s (log %s)", pov_path,
                    why[0] ? why : "no reason given", log_path);
    *ms = elapsed;
    return true;
}
