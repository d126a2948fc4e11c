/* The floor under a tree walk in a fragment shader: what the steps of a walk cost on this GL before
 * any of the walk's own decisions. One MACS pass over a 1024x1024 float output runs a loop of a fixed
 * number of steps per pixel, each step reading what a step of the mesh walk reads (docs/
 * gpu_pipeline.md, "Meshes on the GPU": two texels of a node, a third at a leaf, here every third
 * step) from a 2048x2048 RGBA32F texture, the next address coming from the texel just read, as a
 * miss link does. It is the most favourable case a walk can meet: every pixel takes the same
 * branch at every step (no divergence), and neighbouring pixels read neighbouring texels.
 *
 * Two variants: "fetches" does only the reads (and sums a lane so that none is optimised away);
 * "tests" adds one slab test of a box (interior step) or one edge-function triangle test (leaf)
 * per step, the least arithmetic a real step does. The step counts are those measured for the terrain
 * of bench_mesh at 10^6 triangles (docs/benchmarks.md, "Triangle meshes"): 49 for a primary ray,
 * 124 for a primary and two shadow rays, and 72 for comparison.
 *
 * Usage: bench_walk_floor [out_dir]   (default bench/out; QUICK=1: 256x256, fewer runs)
 * Writes out_dir/walk_floor.csv. */
#include <stdlib.h>
#include <string.h>

#include "lib/bench_util.h"

#define NODE_SIDE 2048
#define RUNS 7
#define QUICK_RUNS 3

static const int step_counts[] = {49, 72, 124};
#define STEP_COUNTS (int)(sizeof step_counts / sizeof step_counts[0])

enum { FETCHES, TESTS, VARIANTS };
static const char *const variant_names[VARIANTS] = {"fetches", "tests"};

/* Texel (x, y) links to (x + 3, y), wrapping: xy is the next texel's coordinate, z a value to sum,
 * w < 0 marks an interior node (a box follows), w > 0 a leaf (a third texel is read). */
static float *node_texels(void)
{
    float *t = malloc((size_t)NODE_SIDE * NODE_SIDE * 4 * sizeof *t);
    if (!t)
        return NULL;
    for (int y = 0; y < NODE_SIDE; y++)
        for (int x = 0; x < NODE_SIDE; x++) {
            float *p = t + ((size_t)y * NODE_SIDE + x) * 4;
            p[0] = ((float)((x + 3) % NODE_SIDE) + 0.5f) / NODE_SIDE;
            p[1] = ((float)y + 0.5f) / NODE_SIDE;
            p[2] = (float)(x & 7);
            p[3] = x % 3 == 0 ? 1.0f : -1.0f;
        }
    return t;
}

/* The step loop: lo and hi are a node's two texels; a leaf reads a third. */
static void write_main(char *buf, size_t size, int steps, int variant)
{
    const char *box = variant == TESTS
                          ? "vec3 t0 = (lo.xyz - o) * inv, t1 = (hi.xyz - o) * inv;\n"
                            "vec3 near = min(t0, t1), far = max(t0, t1);\n"
                            "if (max(max(near.x, near.y), near.z) <= min(min(far.x, far.y), min(far.z, t_max)))\n"
                            "    acc += 1.0;\n"
                          : "acc += lo.z;\n";
    const char *tri = variant == TESTS
                          ? "vec3 e1 = hi.xyz - lo.xyz, e2 = v2.xyz - lo.xyz, q = cross(inv, e2), s = o - lo.xyz;\n"
                            "float det = dot(e1, q), u = dot(s, q) / det;\n"
                            "vec3 r = cross(s, e1);\n"
                            "float v = dot(inv, r) / det, t = dot(e2, r) / det;\n"
                            "if (u >= 0.0 && v >= 0.0 && u + v <= 1.0 && t > 0.0 && t < t_max)\n"
                            "    t_max = t;\n"
                          : "";
    snprintf(buf, size,
             "vec2 c = (floor(macs_uv * vec2(128.0, %d.0)) + 0.5) / %d.0;\n"
             "vec3 o = vec3(macs_uv, 1.0), inv = vec3(0.3, 0.7, 1.1);\n"
             "float acc = 0.0, t_max = 1e30;\n"
             "for (int i = 0; i < %d; i++) {\n"
             "vec4 lo = texture2D(nodes, c), hi = texture2D(nodes, c + vec2(1.0 / %d.0, 0.0));\n"
             "if (lo.w < 0.0) {\n%s} else {\n"
             "vec4 v2 = texture2D(nodes, c + vec2(2.0 / %d.0, 0.0));\nacc += v2.z;\n%s}\n"
             "acc += hi.z;\nc = lo.xy;\n}\n",
             NODE_SIDE - 1, NODE_SIDE, steps, NODE_SIDE, box, NODE_SIDE, tri);
}

/* Times one pass: a warm-up run, then runs runs, each finished before the clock stops. */
static bool time_pass(bench_gpu *gpu, macs_texture *nodes, macs_texture *out, int steps, int variant, int runs,
                      bench_times *times)
{
    static char main_code[4096];
    write_main(main_code, sizeof main_code, steps, variant);
    macs_input_desc input = {"nodes"};
    macs_output_desc output = {"result", "vec4(c, acc, t_max)"};
    macs_pass_desc pd;
    memset(&pd, 0, sizeof pd);
    pd.main = main_code;
    pd.inputs = &input;
    pd.input_count = 1;
    pd.outputs = &output;
    pd.output_count = 1;
    pd.output_textures = &out;
    pd.input_textures = &nodes;
    macs_pass *pass = NULL;
    macs_status st = macs_pass_create(gpu->context, &pd, &pass);
    if (st != MACS_OK) {
        fprintf(stderr, "pass (%d steps, %s): %s: %s\n", steps, variant_names[variant], macs_status_string(st),
                macs_context_error_message(gpu->context));
        return false;
    }
    double ms[RUNS];
    for (int r = -1; r < runs && st == MACS_OK; r++) {
        double t0 = bench_now_ms();
        st = macs_pass_run(pass, NULL);
        macs_context_finish(gpu->context);
        if (r >= 0)
            ms[r] = bench_now_ms() - t0;
    }
    macs_pass_destroy(pass);
    if (st != MACS_OK) {
        fprintf(stderr, "run (%d steps): %s: %s\n", steps, macs_status_string(st), macs_context_error_message(gpu->context));
        return false;
    }
    *times = bench_times_of(ms, runs);
    return true;
}

int main(int argc, char **argv)
{
    bool quick = bench_quick();
    int side = quick ? 256 : 1024, runs = quick ? QUICK_RUNS : RUNS;
    bench_gpu gpu;
    if (!bench_gpu_open(&gpu))
        return 1;
    float *texels = node_texels();
    macs_texture *nodes = NULL, *out = NULL;
    macs_texture_desc nd = {NODE_SIDE, NODE_SIDE, MACS_FORMAT_RGBA32F, MACS_FILTER_NEAREST, MACS_WRAP_DEFAULT, texels, 0};
    macs_texture_desc od = {side, side, MACS_FORMAT_RGBA32F, MACS_FILTER_NEAREST, MACS_WRAP_DEFAULT, NULL, 0};
    int rc = 1;
    if (!texels || macs_texture_create(gpu.context, &nd, &nodes) != MACS_OK ||
        macs_texture_create(gpu.context, &od, &out) != MACS_OK) {
        fprintf(stderr, "textures: %s\n", texels ? macs_context_error_message(gpu.context) : "out of memory");
        goto done;
    }
    FILE *csv = bench_csv_open(bench_out_dir(argc, argv), "walk_floor.csv", "steps,variant,side,runs,median_ms,min_ms,max_ms");
    if (!csv)
        goto done;
    printf("GL: %s; a %dx%d pass per row, %d timed runs after a warm-up\n", gpu.renderer_name, side, side, runs);
    printf("%6s %-8s %10s %20s\n", "steps", "variant", "median ms", "[min-max]");
    rc = 0;
    for (int s = 0; s < STEP_COUNTS && rc == 0; s++)
        for (int v = 0; v < VARIANTS; v++) {
            bench_times t;
            if (!time_pass(&gpu, nodes, out, step_counts[s], v, runs, &t)) {
                rc = 1;
                break;
            }
            printf("%6d %-8s %10.1f      [%.1f-%.1f]\n", step_counts[s], variant_names[v], t.median, t.min, t.max);
            fprintf(csv, "%d,%s,%d,%d,%.3f,%.3f,%.3f\n", step_counts[s], variant_names[v], side, t.runs, t.median,
                    t.min, t.max);
        }
    fclose(csv);
done:
    macs_texture_destroy(out);
    macs_texture_destroy(nodes);
    free(texels);
    bench_gpu_close(&gpu);
    return rc;
}
