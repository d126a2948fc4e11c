/* The public loaders: read the file, parse it, read every section into the scene and the result,
 * then set the camera and ambient light and commit. Sections are read in a fixed order (textures
 * before the materials that name them, materials before the objects), whatever their order in the
 * file; unknown top-level keys are errors like any other. */
#include "scenefile_internal.h"

#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

/* Larger scene files are refused: the geometry belongs in model files. */
#define SCENE_FILE_MAX ((long)256 << 20)

static void result_init(bg_scenefile_result *out)
{
    memset(out, 0, sizeof *out);
    out->camera = bg_camera_init();
    out->image = (bg_scenefile_image){640, 480, 1};
    out->settings = bg_render_settings_init();
    out->ambient[0] = out->ambient[1] = out->ambient[2] = 1.0;
    bgi_sf_summary_reset(&out->summary);
}

static bg_status bad_call(char *message, size_t size, const char *call, const char *what)
{
    if (message && size > 0)
        snprintf(message, size, "%s: %s is NULL", call, what);
    return BG_ERR_INVALID_ARGUMENT;
}

/* The arguments every entry point takes: its input (named first_name), the scene and the result. */
static bg_status check_call(char *message, size_t size, const char *call, const char *first_name, const void *first,
                            const bg_scene *scene, const bg_scenefile_result *out)
{
    if (!first)
        return bad_call(message, size, call, first_name);
    if (!scene)
        return bad_call(message, size, call, "scene");
    if (!out)
        return bad_call(message, size, call, "out");
    return BG_OK;
}

/* The camera and ambient light go to the scene last, then the commit. */
static bg_status finish(bgi_sf_ctx *ctx)
{
    bg_status st = bg_scene_set_camera(ctx->scene, &ctx->out->camera);
    if (st != BG_OK) {
        size_t at = bgi_sf_push_key(ctx, "camera");
        st = bgi_sf_scene_fail(ctx, st, "the camera");
        bgi_sf_pop(ctx, at);
        return st;
    }
    st = bg_scene_set_ambient(ctx->scene, ctx->out->ambient);
    if (st != BG_OK)
        return bgi_sf_scene_fail(ctx, st, "the ambient light");
    st = bg_scene_commit(ctx->scene);
    if (st != BG_OK)
        return bgi_sf_scene_fail(ctx, st, "the commit");
    return BG_OK;
}

static bg_status section(bgi_sf_ctx *ctx, const cJSON *root, const char *key,
                         bg_status (*read)(bgi_sf_ctx *, const cJSON *))
{
    const cJSON *v = bgi_sf_member(root, key);
    if (!v)
        return BG_OK;
    size_t at = bgi_sf_push_key(ctx, key);
    bg_status st = read(ctx, v);
    bgi_sf_pop(ctx, at);
    return st;
}

static bg_status load_text(bgi_sf_ctx *ctx, const bg_scenefile_desc *desc, const char *text)
{
    static const char *const keys[] = {"camera", "image", "settings", "textures", "materials", "objects",
                                       "lights", NULL};
    BGI_SF_TRY(bgi_sf_check_desc(ctx, desc, false));
    BGI_SF_TRY(bgi_sf_json_scan(ctx, text));
    const char *end = NULL;
    cJSON *root = cJSON_ParseWithOpts(text, &end, 1);
    if (!root) {
        int line, column;
        bgi_sf_line_column(text, end ? end : text, &line, &column);
        char near[24] = "";
        if (end && *end) {
            size_t n = 0;
            while (n < sizeof near - 1 && end[n] && end[n] != '\n')
                n++;
            memcpy(near, end, n);
            near[n] = '\0';
        }
        return bgi_sf_fail(ctx, BG_ERR_INVALID_ARGUMENT, "line %d, column %d: not valid JSON%s%s%s", line, column,
                           *near ? " (near \"" : " (the text ends early)", near, *near ? "\")" : "");
    }
    bg_status st = bgi_sf_check_object(ctx, root, keys);
    if (st == BG_OK)
        st = section(ctx, root, "image", bgi_sf_read_image);
    if (st == BG_OK)
        st = section(ctx, root, "settings", bgi_sf_read_settings);
    if (st == BG_OK)
        st = section(ctx, root, "camera", bgi_sf_read_camera);
    if (st == BG_OK)
        st = section(ctx, root, "textures", bgi_sf_read_textures);
    if (st == BG_OK)
        st = section(ctx, root, "materials", bgi_sf_read_materials);
    if (st == BG_OK)
        st = section(ctx, root, "objects", bgi_sf_read_objects);
    if (st == BG_OK)
        st = section(ctx, root, "lights", bgi_sf_read_lights);
    cJSON_Delete(root);
    if (st == BG_OK) {
        ctx->out->file_cameras = ctx->out->camera_number = ctx->out->camera_from_file ? 1 : 0;
        st = bgi_sf_apply_view(ctx, desc);
    }
    return st == BG_OK ? finish(ctx) : st;
}

static bg_status read_file(bgi_sf_ctx *ctx, const char *path, char **out)
{
    FILE *f = NULL;
    BGI_SF_TRY(bgi_sf_open_input(ctx, path, NULL, &f));
    long size = -1;
    if (fseek(f, 0, SEEK_END) == 0)
        size = ftell(f);
    if (size < 0 || fseek(f, 0, SEEK_SET) != 0) {
        fclose(f);
        return bgi_sf_fail(ctx, BG_ERR_IO, "cannot read: %s", strerror(errno));
    }
    if (size > SCENE_FILE_MAX) {
        fclose(f);
        return bgi_sf_fail(ctx, BG_ERR_LIMIT, "the file is %ld bytes, more than a scene file may be (%ld)", size,
                           SCENE_FILE_MAX);
    }
    char *text = malloc((size_t)size + 1);
    if (!text) {
        fclose(f);
        return bgi_sf_fail(ctx, BG_ERR_OUT_OF_MEMORY, "out of memory for %ld bytes", size);
    }
    size_t got = fread(text, 1, (size_t)size, f);
    bool failed = ferror(f) != 0;
    fclose(f);
    if (failed || got != (size_t)size) {
        free(text);
        return bgi_sf_fail(ctx, BG_ERR_IO, "cannot read: %s", failed ? strerror(errno) : "the file changed while read");
    }
    text[got] = '\0';
    if (strlen(text) != got) {
        free(text);
        return bgi_sf_fail(ctx, BG_ERR_INVALID_ARGUMENT, "holds a zero byte: not a JSON text");
    }
    *out = text;
    return BG_OK;
}

bg_status bg_scenefile_load(const char *path, const bg_scenefile_desc *desc, bg_scene *scene,
                            bg_scenefile_result *out, char *message, size_t message_size)
{
    static const char call[] = "bg_scenefile_load";
    bg_status checked = check_call(message, message_size, call, "path", path, scene, out);
    if (checked != BG_OK)
        return checked;
    result_init(out);
    bgi_sf_ctx ctx;
    bgi_sf_ctx_init(&ctx, path, desc, scene, out, message, message_size);
    bgi_sf_set_dir_of(&ctx, path);
    char *text = NULL;
    bg_status st = read_file(&ctx, path, &text);
    if (st == BG_OK)
        st = load_text(&ctx, desc, text);
    free(text);
    bgi_sf_ctx_free(&ctx);
    return st;
}

bg_status bg_scenefile_load_string(const char *text, const bg_scenefile_desc *desc, bg_scene *scene,
                                   bg_scenefile_result *out, char *message, size_t message_size)
{
    static const char call[] = "bg_scenefile_load_string";
    bg_status checked = check_call(message, message_size, call, "text", text, scene, out);
    if (checked != BG_OK)
        return checked;
    result_init(out);
    bgi_sf_ctx ctx;
    bgi_sf_ctx_init(&ctx, desc && desc->name ? desc->name : "<string>", desc, scene, out, message, message_size);
    if (desc && desc->base_dir && *desc->base_dir) {
        size_t n = strlen(desc->base_dir);
        if (n + 2 > sizeof ctx.dir) {
            bg_status st = bgi_sf_fail(&ctx, BG_ERR_INVALID_ARGUMENT, "desc->base_dir is longer than %zu bytes",
                                       sizeof ctx.dir - 2);
            bgi_sf_ctx_free(&ctx);
            return st;
        }
        snprintf(ctx.dir, sizeof ctx.dir, "%s%s", desc->base_dir, desc->base_dir[n - 1] == '/' ? "" : "/");
    }
    bg_status st = load_text(&ctx, desc, text);
    bgi_sf_ctx_free(&ctx);
    return st;
}

/* A camera looking at the centre of the bounds from the front, a little from above and the right,
 * far enough that the bounding sphere fits the vertical field of view (and the horizontal one of an
 * image at least as wide as tall). */
static void frame_bounds(bg_scenefile_result *out)
{
    const bg_scenefile_summary *s = &out->summary;
    bg_vec3 c = bg_vec3_make(0.5 * (s->bounds_min.x + s->bounds_max.x), 0.5 * (s->bounds_min.y + s->bounds_max.y),
                             0.5 * (s->bounds_min.z + s->bounds_max.z));
    double dx = s->bounds_max.x - s->bounds_min.x, dy = s->bounds_max.y - s->bounds_min.y,
           dz = s->bounds_max.z - s->bounds_min.z;
    double r = 0.5 * sqrt(dx * dx + dy * dy + dz * dz);
    if (!(r > 0) || !isfinite(r))
        r = 1.0;
    double fov = out->camera.fov_y_degrees;
    double aspect = (double)out->image.width / out->image.height;
    double half = 0.5 * fov * 3.14159265358979323846 / 180.0;
    double limit = aspect < 1 ? atan(tan(half) * aspect) : half;
    double d = 1.05 * r / sin(limit);
    bg_vec3 dir = bgi_sf_normalize(bg_vec3_make(0.35, 0.3, 1.0));
    out->camera.look_at = c;
    out->camera.position = bg_vec3_make(c.x + d * dir.x, c.y + d * dir.y, c.z + d * dir.z);
    out->camera.up = bg_vec3_make(0, 1, 0);
}

bg_status bg_scenefile_load_model(const char *path, const bg_scenefile_desc *desc, bg_scene *scene,
                                  bg_scenefile_result *out, char *message, size_t message_size)
{
    static const char call[] = "bg_scenefile_load_model";
    bg_status checked = check_call(message, message_size, call, "path", path, scene, out);
    if (checked != BG_OK)
        return checked;
    result_init(out);
    bgi_sf_ctx ctx;
    bgi_sf_ctx_init(&ctx, path, desc, scene, out, message, message_size);
    bg_status st = bgi_sf_check_desc(&ctx, desc, true);
    bgi_sf_model_desc m = {path, bg_mat4_identity(), 0, true, BGI_SF_NORMALS_FILE, 0.0, true, 0};
    if (desc) {
        m.transform = bgi_sf_up_transform(desc->up_axis);
        m.smooth_angle = desc->smooth_angle_degrees;
        m.camera = desc->camera;
    }
    if (st == BG_OK)
        st = bgi_sf_load_model(&ctx, &m);
    /* A field of view asked for is the one the framing camera fits the model into. */
    if (st == BG_OK && desc && desc->fov_y_degrees != 0)
        out->camera.fov_y_degrees = desc->fov_y_degrees;
    if (st == BG_OK && !out->camera_from_file)
        frame_bounds(out);
    if (st == BG_OK)
        st = bgi_sf_apply_view(&ctx, desc);
    if (st == BG_OK && !out->lights_from_file) {
        /* One white light above and to the right of the camera, so that shapes read and shadows fall
         * behind them; a little ambient light keeps the shadows from being black. */
        bg_light l = bg_light_init();
        bg_vec3 p = out->camera.position, c = out->camera.look_at;
        double d = sqrt((p.x - c.x) * (p.x - c.x) + (p.y - c.y) * (p.y - c.y) + (p.z - c.z) * (p.z - c.z));
        l.position = bg_vec3_make(p.x + 0.5 * d, p.y + 0.8 * d, p.z);
        uint32_t id;
        st = bg_scene_add_light(scene, &l, &id);
        if (st != BG_OK)
            st = bgi_sf_scene_fail(&ctx, st, "the default light");
        else
            out->summary.lights++;
    }
    if (st == BG_OK)
        st = finish(&ctx);
    bgi_sf_ctx_free(&ctx);
    return st;
}

bg_status bg_scenefile_load_any(const char *path, const bg_scenefile_desc *desc, bg_scene *scene,
                                bg_scenefile_result *out, char *message, size_t message_size)
{
    size_t n = path ? strlen(path) : 0;
    if (n >= 5 && strcasecmp(path + n - 5, ".json") == 0)
        return bg_scenefile_load(path, desc, scene, out, message, message_size);
    if (!path)
        return bad_call(message, message_size, "bg_scenefile_load_any", "path");
    return bg_scenefile_load_model(path, desc, scene, out, message, message_size);
}
