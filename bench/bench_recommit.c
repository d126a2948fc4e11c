/* What a re-commit costs the next GPU frame: the frame drawn right after the camera, a light, an
 * object's transform or a material's colour changed, against the cached frame (nothing changed since
 * the last one), and after one structural change for contrast (a sphere added with an existing
 * material). A value change should reuse every program the renderer holds, so its first frame should
 * cost what a cached frame costs and compile nothing; the unrolled fused plan compiles for a new
 * object, the tree variant should not.
 *
 * Usage: bench_recommit [out_dir]   (default bench/out; QUICK=1: 256x256 and fewer rounds)
 * Per case (a scene and a plan, a fresh scene and renderer each): one untimed first frame, then rounds
 * in a fixed order: a cached frame, then per kind a re-commit and its first frame; a case whose first
 * cached frame took over BENCH_SLOW_MS gets BENCH_SLOW_RUNS rounds at most. Value kinds alternate
 * between a moved and the built value, so the scene stays what it was; the added spheres stay (there is
 * no removal), a small one more per round along the top of the scene. Ratios are medians of the per-round
 * ratios against the cached frame of the same round. Writes out_dir/recommit.csv. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "betelgeuse/scene/scene_internal.h"
#include "lib/bench_measure.h"
#include "scenes/scenes.h"

/* The rows of a case, in round order; FIRST is the untimed first frame, before the rounds. */
enum kind { CACHED, CAMERA, LIGHT, TRANSFORM, MATERIAL, ADD_SPHERE, KINDS, FIRST = KINDS };
static const char *const kind_names[KINDS + 1] = {"cached",   "camera",     "light",      "transform",
                                                  "material", "add sphere", "first frame"};

#define MAX_ROUNDS 8

/* A scene and a plan. The multipass draws many_spheres with 16 spheres, not 64, and at half size:
 * with 64 a 512x512 frame takes 15-30 s, and with 16 a 256x256 one took 3.4 s here, so its rounds
 * alone would take a minute; quick mode leaves it out. */
typedef struct case_spec {
    scene_id id;
    int spheres; /* SCENE_MANY_SPHERES only */
    bg_gpu_plan plan;
    bool heavy;  /* drawn at half size; left out in quick mode */
} case_spec;
static const case_spec cases[] = {
    {SCENE_GLASS, 0, BG_PLAN_AUTO, false},
    {SCENE_MANY_SPHERES, 64, BG_PLAN_AUTO, false},
    {SCENE_GLASS, 0, BG_PLAN_MULTIPASS, false},
    {SCENE_MANY_SPHERES, 16, BG_PLAN_MULTIPASS, true},
};

/* The values the changes start from, as built. The public API has setters only, so they are read from
 * the committed state. */
typedef struct baseline {
    bg_camera camera;
    bg_vec3 camera_step;  /* a small sideways move */
    bg_light light;       /* light 1 */
    double light_step;
    uint32_t object;      /* the first bounded object: moved, and its material recoloured */
    bg_mat4 transform;
    double object_step;
    uint32_t material;
    bg_material material_values;
    double bounds_min[3], bounds_max[3]; /* of the bounded objects: where added spheres go */
} baseline;

/* One kind's frames over the rounds. */
typedef struct kind_run {
    double frame_ms[MAX_ROUNDS], commit_ms[MAX_ROUNDS];
    int programs_max; /* programs compiled by one of its frames, at most */
    bg_gpu_plan plan; /* the plan its last frame ran */
} kind_run;

typedef struct case_run {
    kind_run kinds[KINDS + 1];
    int rounds;
    uint32_t objects; /* in the scene as built */
} case_run;

static double length_of(bg_vec3 v)
{
    return sqrt(v.x * v.x + v.y * v.y + v.z * v.z);
}

/* Reads the baseline values and picks the object and material to change; false without a bounded
 * object or a light. */
static bool read_baseline(const bg_scene *scene, baseline *b)
{
    const bg_scene_state *s = bgi_scene_committed(scene);
    uint32_t first = 0;
    while (s && first < s->object_count && !s->objects[first].bounded)
        first++;
    if (!s || first == s->object_count || s->light_count == 0) {
        fprintf(stderr, "the scene has no bounded object or no light to change\n");
        return false;
    }
    memset(b, 0, sizeof *b);
    const bg_camera_data *c = &s->camera;
    b->camera = c->camera;
    bg_vec3 view = {c->camera.look_at.x - c->camera.position.x, c->camera.look_at.y - c->camera.position.y,
                    c->camera.look_at.z - c->camera.position.z};
    double step = 0.02 * length_of(view);
    b->camera_step = bg_vec3_make(step * c->right[0], step * c->right[1], step * c->right[2]);
    memcpy(b->bounds_min, s->bounds_min, sizeof b->bounds_min);
    memcpy(b->bounds_max, s->bounds_max, sizeof b->bounds_max);
    double size = b->bounds_max[0] - b->bounds_min[0];
    b->light = s->lights[0];
    b->light_step = 0.05 * size;
    const bg_object_data *o = &s->objects[first];
    b->object = first + 1;
    memcpy(b->transform.m, o->to_world, sizeof b->transform.m);
    b->object_step = 0.01 * size;
    b->material = o->material + 1;
    b->material_values = s->materials[o->material];
    return true;
}

/* Adds the round's sphere: small, above the scene's bounded objects, one slot per round along x. */
static bg_status add_sphere(bg_scene *scene, const baseline *b, int round)
{
    double width = b->bounds_max[0] - b->bounds_min[0], radius = 0.04 * width;
    bg_vec3 centre = bg_vec3_make(b->bounds_min[0] + width * (round + 1) / (MAX_ROUNDS + 1), b->bounds_max[1] + radius,
                                  0.5 * (b->bounds_min[2] + b->bounds_max[2]));
    uint32_t id;
    return bg_scene_add_sphere(scene, centre, radius, b->material, &id);
}

/* Sets round's value of a kind: even rounds the moved value, odd rounds the built one. */
static bg_status change(bg_scene *scene, const baseline *b, enum kind kind, int round)
{
    const bool moved = round % 2 == 0;
    switch (kind) {
    case CAMERA: {
        bg_camera c = b->camera;
        if (moved)
            c.position = bg_vec3_make(c.position.x + b->camera_step.x, c.position.y + b->camera_step.y,
                                      c.position.z + b->camera_step.z);
        return bg_scene_set_camera(scene, &c);
    }
    case LIGHT: {
        bg_light l = b->light;
        l.position.x += moved ? b->light_step : 0.0;
        return bg_scene_set_light(scene, 1, &l);
    }
    case TRANSFORM: {
        bg_mat4 t = moved ? bg_mat4_mul(bg_mat4_translate(b->object_step, 0, 0), b->transform) : b->transform;
        return bg_scene_set_transform(scene, b->object, &t);
    }
    case MATERIAL: {
        bg_material m = b->material_values;
        const double tint = moved ? 0.8 : 1.0;
        m.base.reflectance.r *= tint;
        m.base.reflectance.g *= tint;
        return bg_scene_set_material(scene, b->material, &m);
    }
    case ADD_SPHERE: return add_sphere(scene, b, round);
    default: return BG_OK;
    }
}

/* One frame of a kind: its re-commit (timed apart), then the frame. */
static bool kind_frame(bench_gpu_job *job, const baseline *b, enum kind kind, int round, bg_image *image, kind_run *out)
{
    double t0 = bench_now_ms();
    if (kind != CACHED && kind != FIRST &&
        (change(job->scene, b, kind, round) != BG_OK || bg_scene_commit(job->scene) != BG_OK)) {
        fprintf(stderr, "%s: %s\n", kind_names[kind], bg_scene_error_message(job->scene));
        return false;
    }
    double t1 = bench_now_ms();
    if (!bench_gpu_frame(job, image))
        return false;
    out->frame_ms[round] = bench_now_ms() - t1;
    out->commit_ms[round] = t1 - t0;
    if (job->stats.programs_compiled > out->programs_max)
        out->programs_max = job->stats.programs_compiled;
    out->plan = job->stats.plan;
    return true;
}

/* The first frame, then the rounds. */
static bool time_case(bench_gpu_job *job, const baseline *b, bg_image *image, const char *label, case_run *run)
{
    if (!kind_frame(job, b, FIRST, 0, image, &run->kinds[FIRST]))
        return false;
    for (int r = 0; r < run->rounds; r++) {
        bench_progress("%s, round %d of %d", label, r + 1, run->rounds);
        for (int k = 0; k < KINDS; k++)
            if (!kind_frame(job, b, (enum kind)k, r, image, &run->kinds[k]))
                return false;
        if (r == 0 && run->kinds[CACHED].frame_ms[0] > BENCH_SLOW_MS && run->rounds > BENCH_SLOW_RUNS)
            run->rounds = BENCH_SLOW_RUNS;
    }
    return true;
}

/* The median of a kind's frame times over the cached frames of the same rounds. */
static double ratio_to_cached(const case_run *run, int kind, int rounds)
{
    double ratios[MAX_ROUNDS];
    for (int r = 0; r < rounds; r++)
        ratios[r] = run->kinds[kind].frame_ms[r] / run->kinds[CACHED].frame_ms[r];
    return bench_times_of(ratios, rounds).median;
}

static const char *case_name(const case_spec *spec, char *buffer, size_t size)
{
    if (spec->id == SCENE_MANY_SPHERES)
        snprintf(buffer, size, "%s %d", scenes_name(spec->id), spec->spheres);
    else
        snprintf(buffer, size, "%s", scenes_name(spec->id));
    return buffer;
}

static const char *plan_asked_name(bg_gpu_plan plan)
{
    return plan == BG_PLAN_AUTO ? "auto" : bench_plan_name(plan);
}

#define TABLE_FORMAT(x) "%-16s %4" x " %-9s %-10s %-11s | %-26s | %8s | %9s | %s\n"

static void print_header(const bench_gpu *gpu, int rounds)
{
    printf("== Frame time after a re-commit, against the cached frame\n");
    bench_print_setup(stdout, gpu, rounds);
    printf("Rounds: a cached frame, then each kind's re-commit and first frame; cells: n frames, ms median\n"
           "[min-max] (the frame alone; commit ms apart); x cached: median of the per-round ratios; programs:\n"
           "programs compiled by one frame, at most. 'first frame': the untimed frame before the rounds\n");
    printf(TABLE_FORMAT("s"), "scene", "size", "asked", "ran", "kind", "frame: n ms [min-max]", "x cached", "commit ms",
           "programs");
}

/* A kind's table row and CSV row; the first frame has one frame and its commit was the scene's build. */
static void report_kind(FILE *csv, const case_spec *spec, int size, const case_run *run, int kind)
{
    const kind_run *k = &run->kinds[kind];
    const int n = kind == FIRST ? 1 : run->rounds;
    double frames[MAX_ROUNDS], commits[MAX_ROUNDS];
    memcpy(frames, k->frame_ms, sizeof frames);
    memcpy(commits, k->commit_ms, sizeof commits);
    bench_times t = bench_times_of(frames, n), c = bench_times_of(commits, n);
    double ratio = kind == FIRST ? t.median / run->kinds[CACHED].frame_ms[0] : ratio_to_cached(run, kind, n);
    char name[64], cell[64], commit[16] = "-";
    case_name(spec, name, sizeof name);
    snprintf(cell, sizeof cell, "%2d %8.1f [%.1f-%.1f]", n, t.median, t.min, t.max);
    if (kind != FIRST && kind != CACHED)
        snprintf(commit, sizeof commit, "%.3f", c.median);
    char ratio_text[16], programs[16];
    snprintf(ratio_text, sizeof ratio_text, "%.2f", ratio);
    snprintf(programs, sizeof programs, "%d", k->programs_max);
    printf(TABLE_FORMAT("d"), name, size, plan_asked_name(spec->plan), bench_plan_name(k->plan), kind_names[kind], cell,
           ratio_text, commit, programs);
    fflush(stdout);
    fprintf(csv, "%s,%d,%u,%d,%s,%s,%s,%d,%.3f,%.3f,%.3f,%.4f,%s,%d\n", scenes_name(spec->id), spec->spheres,
            run->objects, size, plan_asked_name(spec->plan), bench_plan_name(k->plan), kind_names[kind], n, t.median,
            t.min, t.max, ratio, kind != FIRST && kind != CACHED ? commit : "", k->programs_max);
}

#define CSV_HEADER                                                                                            \
    "scene,spheres,objects,size,plan_asked,plan_ran,kind,frames,median_ms,min_ms,max_ms,over_cached,"        \
    "commit_median_ms,programs_compiled_max"

/* One case on a fresh scene and a renderer of its own, so that no case finds another's programs or
 * textures in its caches beyond what the context's program cache shares. */
static bool run_case(bench_gpu *gpu, const case_spec *spec, int size, int rounds, FILE *csv)
{
    scene_params params;
    memset(&params, 0, sizeof params);
    params.spheres = spec->spheres;
    bg_renderer_desc desc;
    memset(&desc, 0, sizeof desc);
    bg_scene *scene = bench_scene(spec->id, &params);
    bg_renderer *renderer = scene ? bench_gpu_renderer(gpu, desc) : NULL;
    case_run *run = calloc(1, sizeof *run);
    bg_image image = {0};
    baseline b;
    bool ok = renderer && run && bench_image_alloc(&image, size, size, BG_PIXEL_RGBA8) && read_baseline(scene, &b);
    if (ok) {
        char name[64], label[96];
        snprintf(label, sizeof label, "recommit: %s %s %dx%d", case_name(spec, name, sizeof name),
                 plan_asked_name(spec->plan), size, size);
        bench_progress("%s: first frame", label);
        run->rounds = rounds;
        run->objects = bgi_scene_committed(scene)->object_count;
        bench_gpu_job job = {.renderer = renderer, .scene = scene, .settings = bg_render_settings_init()};
        job.settings.gpu_plan = spec->plan;
        ok = time_case(&job, &b, &image, label, run);
        if (!ok)
            fprintf(stderr, "%s failed\n", label);
    }
    for (int k = 0; ok && k <= KINDS; k++)
        report_kind(csv, spec, size, run, k == 0 ? FIRST : k - 1);
    bench_image_free(&image);
    free(run);
    bg_renderer_destroy(renderer);
    bg_scene_destroy(scene);
    return ok;
}

/* Every case the mode asks for, in order; 0 when all ran. */
static int run_cases(bench_gpu *gpu, FILE *csv)
{
    const bool quick = bench_quick();
    const int size = quick ? 256 : 512, rounds = quick ? 3 : 5;
    print_header(gpu, rounds);
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++)
        if (!(quick && cases[i].heavy) && !run_case(gpu, &cases[i], cases[i].heavy ? size / 2 : size, rounds, csv))
            return 1;
    if (quick)
        printf("quick mode: many_spheres 16 on the multipass left out (a 256x256 frame takes seconds)\n");
    return 0;
}

int main(int argc, char **argv)
{
    bench_gpu gpu;
    if (!bench_gpu_open(&gpu))
        return 1;
    FILE *csv = bench_csv_open(bench_out_dir(argc, argv), "recommit.csv", CSV_HEADER);
    int status = csv ? run_cases(&gpu, csv) : 1;
    if (csv)
        fclose(csv);
    bench_gpu_close(&gpu);
    return status;
}
