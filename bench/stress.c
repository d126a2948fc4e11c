/* make stress: every float32 stress case (examples/scenes/stress_cases.h) on the GPU path and the
 * double-precision CPU reference. Per case: the error against the reference of the same case, the
 * non-finite values of both float outputs, the acne pixels, and for a shared scene moved in scale or
 * offset, the drift against the reference of the scene at the origin. A table on stdout, the rows
 * in <dir>/stress.csv (dir = argv[1], default bench/out), progress on stderr, and a summary of which
 * cases hold and which degrade, by how much and why. QUICK=1 runs the quick subset. A case whose
 * scene or render is refused is reported, not fatal; the exit status is 0 unless the program
 * itself fails (no GPU session, no memory, no CSV). */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* No test context here: the thresholds take no profile (tests/gpu_thresholds.h). */
#define GPU_THRESHOLDS_NO_PROFILES
#include "../tests/stress_verdict.h"
#include "lib/bench_util.h"
#include "scenes/image_metrics.h"
#include "scenes/scenes.h"
#include "scenes/stress_cases.h"

enum { W = STRESS_WIDTH, H = STRESS_HEIGHT };

/* What one case measured. */
typedef struct outcome {
    bool rendered;          /* both renderers produced images */
    char failure[256];      /* why not, when !rendered */
    image_metrics m;        /* GPU against the CPU reference of the same case */
    image_acne acne;
    size_t nan_gpu, nan_cpu;
    bool placed;
    image_metrics drift;    /* GPU against the CPU reference of the scene at the origin */
    image_metrics cpu_drift;/* CPU against the CPU reference at the origin: the oracle's own drift */
    bool holds;
    char why[256];
    double ms;
} outcome;

/* The CPU reference of each shared scene at the origin, rendered once. */
static bg_image origin_ref[SCENE_COUNT];

static const bg_image *origin_of(const stress_case *c)
{
    bg_image *img = &origin_ref[c->scene];
    if (img->pixels)
        return img;
    bg_scene *s = NULL;
    if (bg_scene_create(NULL, &s) != BG_OK || stress_case_build_origin(c, s) != BG_OK ||
        !bench_image_alloc(img, W, H, BG_PIXEL_RGBA8)) {
        bg_scene_destroy(s);
        return NULL;
    }
    bg_render_settings set = stress_case_settings(c);
    bg_status st = bg_render_cpu(s, &set, img);
    bg_scene_destroy(s);
    if (st != BG_OK) {
        bench_image_free(img);
        return NULL;
    }
    return img;
}

static bool gpu_render(bench_gpu *gpu, bg_scene *s, const bg_render_settings *set, bg_image *img, outcome *o)
{
    bg_status st = bg_render_gpu(gpu->renderer, s, set, img);
    if (st == BG_OK)
        return true;
    snprintf(o->failure, sizeof o->failure, "GPU render refused: %s: %s", bg_status_string(st),
             bg_renderer_error_message(gpu->renderer));
    bg_renderer_clear_error(gpu->renderer);
    return false;
}

/* Runs one case into o; false only when the program itself cannot go on (memory). */
static bool run_case(bench_gpu *gpu, const stress_case *c, outcome *o)
{
    memset(o, 0, sizeof *o);
    double t0 = bench_now_ms();
    bg_image cpu8, cpuf, gpu8, gpuf;
    if (!bench_image_alloc(&cpu8, W, H, BG_PIXEL_RGBA8) || !bench_image_alloc(&cpuf, W, H, BG_PIXEL_RGBA32F) ||
        !bench_image_alloc(&gpu8, W, H, BG_PIXEL_RGBA8) || !bench_image_alloc(&gpuf, W, H, BG_PIXEL_RGBA32F))
        return false;
    bg_scene *s = NULL;
    bg_render_settings set = stress_case_settings(c);
    bg_status st = bg_scene_create(NULL, &s);
    if (st == BG_OK)
        st = stress_case_build(c, s);
    if (st != BG_OK) {
        snprintf(o->failure, sizeof o->failure, "scene refused: %s: %s", bg_status_string(st),
                 s ? bg_scene_error_message(s) : "");
    } else if ((st = bg_render_cpu(s, &set, &cpu8)) != BG_OK || (st = bg_render_cpu(s, &set, &cpuf)) != BG_OK) {
        snprintf(o->failure, sizeof o->failure, "CPU render refused: %s", bg_status_string(st));
    } else if (gpu_render(gpu, s, &set, &gpu8, o) && gpu_render(gpu, s, &set, &gpuf, o)) {
        o->rendered = true;
        image_metrics_compare(&cpu8, &gpu8, GPU_SILHOUETTE_THRESHOLD, &o->m);
        image_metrics_acne(&cpu8, &gpu8, GPU_SILHOUETTE_THRESHOLD, &o->acne);
        o->nan_gpu = image_metrics_count_nonfinite(&gpuf);
        o->nan_cpu = image_metrics_count_nonfinite(&cpuf);
        o->holds = stress_holds(c, &o->m, &o->acne, o->nan_gpu, o->why, sizeof o->why);
        if (stress_case_is_placed(c)) {
            const bg_image *ref = origin_of(c);
            if (ref) {
                o->placed = true;
                image_metrics_compare(ref, &gpu8, GPU_SILHOUETTE_THRESHOLD, &o->drift);
                image_metrics_compare(ref, &cpu8, GPU_SILHOUETTE_THRESHOLD, &o->cpu_drift);
            }
        }
    }
    if (!o->rendered)
        snprintf(o->why, sizeof o->why, "%s", o->failure);
    bg_scene_destroy(s);
    bench_image_free(&cpu8);
    bench_image_free(&cpuf);
    bench_image_free(&gpu8);
    bench_image_free(&gpuf);
    o->ms = bench_now_ms() - t0;
    return true;
}

static double worst3(const double v[3])
{
    double m = v[0] > v[1] ? v[0] : v[1];
    return m > v[2] ? m : v[2];
}

static void print_header(void)
{
    printf("%-40s %-5s %7s %4s %7s %7s %5s %9s %6s %13s %7s  %s\n", "case", "class", "PSNR", "max", "mean", "over%",
           "i.max", "NaN/Inf", "acne", "drift PSNR/im", "cpu.im", "verdict");
}

static void print_row(const stress_case *c, const outcome *o)
{
    const char *cls = c->class_ == STRESS_MUST_HOLD ? "must" : "sweep";
    if (!o->rendered) {
        printf("%-40s %-5s %s\n", c->name, cls, o->failure);
        return;
    }
    char nan[32], drift[32], cpu[16];
    snprintf(nan, sizeof nan, "%zu/%zu", o->nan_gpu, o->nan_cpu);
    if (o->placed) {
        snprintf(drift, sizeof drift, "%.1f/%.0f", o->drift.all.psnr_db, worst3(o->drift.interior.max_abs));
        snprintf(cpu, sizeof cpu, "%.0f", worst3(o->cpu_drift.interior.max_abs));
    } else {
        snprintf(drift, sizeof drift, "-");
        snprintf(cpu, sizeof cpu, "-");
    }
    printf("%-40s %-5s %7.2f %4.0f %7.4f %7.3f %5.0f %9s %6ld %13s %7s  %s\n", c->name, cls, o->m.all.psnr_db,
           worst3(o->m.all.max_abs), worst3(o->m.all.mean_abs), 100.0 * o->m.all.over_share,
           worst3(o->m.interior.max_abs), nan, o->acne.pixels, drift, cpu, o->holds ? "holds" : "DEGRADES");
}

static void csv_row(FILE *f, const stress_case *c, const outcome *o)
{
    fprintf(f, "\"%s\",%s,%d,%d,%d", c->name, c->class_ == STRESS_MUST_HOLD ? "must_hold" : "sweep", o->rendered,
            W, H);
    if (o->rendered)
        fprintf(f, ",%.3f,%.0f,%.5f,%.5f,%.0f,%zu,%zu,%ld,%ld,%ld", o->m.all.psnr_db, worst3(o->m.all.max_abs),
                worst3(o->m.all.mean_abs), o->m.all.over_share, worst3(o->m.interior.max_abs), o->nan_gpu, o->nan_cpu,
                o->acne.pixels, o->acne.shadowed, o->acne.speckles);
    else
        fprintf(f, ",,,,,,,,,,");
    if (o->placed)
        fprintf(f, ",%.3f,%.0f,%.0f", o->drift.all.psnr_db, worst3(o->drift.interior.max_abs),
                worst3(o->cpu_drift.interior.max_abs));
    else
        fprintf(f, ",,,");
    fprintf(f, ",%s,\"%s\",%.1f\n", o->holds ? "holds" : "degrades", o->holds ? "" : o->why, o->ms);
}

int main(int argc, char **argv)
{
    const char *dir = bench_out_dir(argc, argv);
    bool quick = bench_quick();
    bench_gpu gpu;
    if (!bench_gpu_open(&gpu))
        return 1;
    FILE *csv = bench_csv_open(dir, "stress.csv",
                               "case,class,rendered,width,height,psnr_db,max,mean,over_share,interior_max,nonfinite_gpu,"
                               "nonfinite_cpu,acne,acne_shadowed,acne_speckles,drift_psnr_db,drift_interior_max,"
                               "cpu_drift_interior_max,verdict,why,ms");
    size_t n = stress_case_count();
    outcome *out = calloc(n, sizeof *out);
    if (!csv || !out) {
        if (csv)
            fclose(csv);
        free(out);
        bench_gpu_close(&gpu);
        return 1;
    }
    bench_progress("stress: %zu cases%s on %s, %dx%d", n, quick ? " (QUICK subset)" : "", gpu.renderer_name, W, H);
    printf("float32 stress: GPU (%s) against the double-precision CPU reference, %dx%d, errors in 1/255 of sRGB\n",
           gpu.renderer_name, W, H);
    printf("i.max = largest error off silhouettes; NaN/Inf = non-finite values GPU/CPU; drift = GPU against the CPU\n"
           "image of the scene at the origin (PSNR / i.max); cpu.im = the CPU's own drift (i.max)\n\n");
    print_header();
    int ran = 0, held = 0, must_failed = 0;
    for (size_t i = 0; i < n; i++) {
        const stress_case *c = stress_case_at(i);
        if (quick && !c->quick)
            continue;
        bench_progress("%zu/%zu %s", i + 1, n, c->name);
        if (!run_case(&gpu, c, &out[i])) {
            fprintf(stderr, "out of memory\n");
            return 1;
        }
        print_row(c, &out[i]);
        fflush(stdout);
        csv_row(csv, c, &out[i]);
        ran++;
        held += out[i].holds;
        must_failed += c->class_ == STRESS_MUST_HOLD && !out[i].holds;
    }
    fclose(csv);

    printf("\nSummary: %d of %d cases hold (within the normal thresholds of tests/gpu_thresholds.h, no acne, no\n"
           "NaN/Inf); %d must-hold case(s) failed.\n",
           held, ran, must_failed);
    printf("Degrading cases, by how much and why (the first bound broken; what the case stresses):\n");
    for (size_t i = 0; i < n; i++) {
        const stress_case *c = stress_case_at(i);
        if ((quick && !c->quick) || out[i].holds)
            continue;
        printf("  %-40s %s\n  %-40s   stresses: %s", c->name, out[i].why, "", c->stresses);
        if (out[i].placed)
            printf("; drift from the origin image PSNR %.1f dB, CPU's own drift i.max %.0f",
                   out[i].drift.all.psnr_db, worst3(out[i].cpu_drift.interior.max_abs));
        printf("\n");
    }
    printf("CSV: %s/stress.csv\n", dir);
    for (int i = 0; i < SCENE_COUNT; i++)
        bench_image_free(&origin_ref[i]);
    free(out);
    bench_gpu_close(&gpu);
    bench_progress("done");
    return 0;
}
