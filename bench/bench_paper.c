/* The paper's table: its two scenes at 512x512 and 1024x1024 on the GPU path (its fused plan and its
 * multipass plan, each forced), the CPU reference and,
 * when povray is installed, POV-Ray 3.7 rendering the same scenes as a whole process.
 *
 * Usage: bench_paper [out_dir]   (default bench/out; QUICK=1 for fewer runs)
 * Per case: a warm-up and `runs` timed renders back to back for each renderer, in one process and one
 * after the other, so each ratio compares medians measured side by side. Writes out_dir/paper.csv. */
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "lib/bench_measure.h"
#include "lib/pov_export.h"
#include "scenes/scenes.h"

typedef struct pov_case {
    bool ran;
    bench_times times;
    bench_times startup; /* a 1x1 render of the same file: process start-up and parsing */
    bench_error error; /* POV-Ray's image against the CPU reference: a different shading model */
} pov_case;

/* Times POV-Ray on one scene and size: one warm-up run (file cache), then `runs` timed runs. */
static bool time_pov(scene_id id, const char *dir, int size, int runs, const bg_image *reference, pov_case *out)
{
    char pov[1024], png[1100], message[512];
    memset(out, 0, sizeof *out);
    if (!pov_write_scene(id, dir, pov, sizeof pov, message, sizeof message)) {
        fprintf(stderr, "POV-Ray export: %s\n", message);
        return false;
    }
    snprintf(png, sizeof png, "%s/%s_pov_%d.png", dir, scenes_name(id), size);
    int threads = (int)sysconf(_SC_NPROCESSORS_ONLN);
    char tiny[1100];
    snprintf(tiny, sizeof tiny, "%s/%s_pov_1.png", dir, scenes_name(id));
    double t[64], t1[64], ms = 0.0;
    bool ok = runs <= 64 && pov_render(pov, size, size, threads, png, &ms, message, sizeof message);
    for (int r = 0; r < runs && ok; r++) {
        ok = pov_render(pov, size, size, threads, png, &ms, message, sizeof message) &&
             pov_render(pov, 1, 1, threads, tiny, &t1[r], message, sizeof message);
        t[r] = ms;
    }
    if (!ok) {
        fprintf(stderr, "POV-Ray: %s\n", message);
        return false;
    }
    out->ran = true;
    out->times = bench_times_of(t, runs);
    out->startup = bench_times_of(t1, runs);
    bg_image image;
    if (bench_image_alloc(&image, size, size, BG_PIXEL_RGBA8)) {
        if (bg_png_load(png, &image, message, sizeof message) == BG_OK)
            out->error = bench_error_of(reference, &image);
        bench_image_free(&image);
    }
    return true;
}

int main(int argc, char **argv)
{
    const char *dir = bench_out_dir(argc, argv);
    const bool quick = bench_quick();
    const int runs = quick ? 3 : 7;
    bench_gpu gpu;
    if (!bench_gpu_open(&gpu))
        return 1;
    const bool pov = pov_available();
    FILE *csv = bench_csv_open(dir, "paper.csv",
                               "scene,size,gpu_median_ms,gpu_min_ms,gpu_max_ms,multipass_median_ms,multipass_min_ms,multipass_max_ms,cpu_median_ms,cpu_min_ms,cpu_max_ms,"
                               "pov_median_ms,pov_min_ms,pov_max_ms,cpu_over_gpu,pov_over_gpu,multipass_over_gpu," BENCH_ERROR_CSV_HEADER
                               ",pov_startup_median_ms,pov_psnr_db,pov_mean_abs");
    if (!csv) {
        bench_gpu_close(&gpu);
        return 1;
    }
    printf("== Paper scenes: GPU path, CPU reference%s\n", pov ? ", POV-Ray 3.7 (whole process)" : "");
    bench_print_setup(stdout, &gpu, runs);
    if (!pov)
        printf("povray not installed: the POV-Ray columns are empty\n");
    printf("GPU: the fused plan; MP: the multipass plan (both forced); ratios against the fused plan\n");
    printf("%-19s %5s | %-22s | %-22s | %-22s | %-22s | %7s %7s %7s | %s\n", "scene", "size", "GPU ms median [min-max]",
           "MP ms median [min-max]", "CPU ms median [min-max]", "POV ms median [min-max]", "MP/GPU", "CPU/GPU",
           "POV/GPU", "GPU error vs CPU");

    const scene_id ids[2] = {SCENE_PAPER_EARTH, SCENE_PAPER_EARTH_SHADOW};
    const int sizes[2] = {512, 1024};
    int status = 0, pov_cases = 0;
    double pov_startup_sum = 0.0, pov_worst_psnr = IMAGE_METRICS_PSNR_IDENTICAL;
    for (int s = 0; s < 2 && !status; s++) {
        bg_scene *scene = bench_scene(ids[s], NULL);
        status = !scene;
        for (int z = 0; z < 2 && !status; z++) {
            int n = sizes[z];
            bg_image gi, ci;
            if (!bench_image_alloc(&gi, n, n, BG_PIXEL_RGBA8) || !bench_image_alloc(&ci, n, n, BG_PIXEL_RGBA8)) {
                status = 1;
                break;
            }
            bg_render_settings settings = bg_render_settings_init();
            settings.gpu_plan = BG_PLAN_FUSED;
            bg_render_settings multipass = settings;
            multipass.gpu_plan = BG_PLAN_MULTIPASS;
            bench_times tg, tm, tc;
            pov_case pc;
            memset(&pc, 0, sizeof pc);
            bench_progress("paper: %s %dx%d", scenes_name(ids[s]), n, n);
            status = !bench_time_gpu(gpu.renderer, scene, &multipass, &gi, runs, &tm) ||
                     !bench_time_gpu(gpu.renderer, scene, &settings, &gi, runs, &tg) ||
                     !bench_time_cpu(scene, &settings, &ci, runs, &tc);
            if (!status && pov)
                status = !time_pov(ids[s], dir, n, runs, &ci, &pc);
            if (!status) {
                bench_error e = bench_error_of(&ci, &gi);
                char pov_text[64] = "-", pov_ratio[16] = "-", text[128];
                if (pc.ran) {
                    pov_cases++;
                    pov_startup_sum += pc.startup.median;
                    if (pc.error.psnr_db < pov_worst_psnr)
                        pov_worst_psnr = pc.error.psnr_db;
                    snprintf(pov_text, sizeof pov_text, "%7.1f [%.1f-%.1f]", pc.times.median, pc.times.min,
                             pc.times.max);
                    snprintf(pov_ratio, sizeof pov_ratio, "%.2f", pc.times.median / tg.median);
                }
                printf("%-19s %5d | %7.1f [%6.1f-%6.1f] | %7.1f [%6.1f-%6.1f] | %7.1f [%6.1f-%6.1f] | %-22s | %7.2f %7.2f "
                       "%7s | %s\n",
                       scenes_name(ids[s]), n, tg.median, tg.min, tg.max, tm.median, tm.min, tm.max, tc.median, tc.min,
                       tc.max, pov_text, tm.median / tg.median, tc.median / tg.median, pov_ratio,
                       bench_error_text(&e, text, sizeof text));
                fflush(stdout);
                fprintf(csv, "%s,%d,%.3f,%.3f,%.3f,%.3f,%.3f,%.3f,%.3f,%.3f,%.3f,", scenes_name(ids[s]), n, tg.median,
                        tg.min, tg.max, tm.median, tm.min, tm.max, tc.median, tc.min, tc.max);
                if (pc.ran)
                    fprintf(csv, "%.1f,%.1f,%.1f,%.3f,%.3f,%.3f,", pc.times.median, pc.times.min, pc.times.max,
                            tc.median / tg.median, pc.times.median / tg.median, tm.median / tg.median);
                else
                    fprintf(csv, ",,,%.3f,,%.3f,", tc.median / tg.median, tm.median / tg.median);
                bench_error_csv(csv, &e);
                if (pc.ran)
                    fprintf(csv, ",%.1f,%.2f,%.3f\n", pc.startup.median, pc.error.psnr_db, pc.error.mean_abs);
                else
                    fprintf(csv, ",,,\n");
            }
            bench_image_free(&gi);
            bench_image_free(&ci);
        }
        bg_scene_destroy(scene);
    }
    if (pov && !status && pov_cases > 0)
        printf("POV-Ray times are whole processes; a 1x1 render of the same file (start-up and parsing) took\n"
               "%.0f ms (median over every case). POV-Ray's image against our CPU reference: PSNR %.1f dB at worst, the\n"
               "same geometry, camera, texture and lights with its own shading model (a diffuse fit to Schlick's),\n"
               "so it shows the scenes match, not an accuracy.\n",
               pov_startup_sum / pov_cases, pov_worst_psnr);
    fclose(csv);
    bench_gpu_close(&gpu);
    return status;
}
