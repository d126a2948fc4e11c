/* The thin lens (docs/shading.md 1.4): depth of field from the camera's aperture. */
#include "cpu_internal.h"

void bgi_cpu_lens_ray(const bg_camera_data *camera, const bgi_sample_point *sample, double o[3], double d[3])
{
    double uv[2], disc[2];
    bgi_sample_square(sample, BGI_DIMENSION_LENS, uv);
    bgi_sample_disc(uv, disc);
    double a = camera->camera.aperture_radius;
    /* The pinhole ray meets the plane in focus (at focus along forward) at eye + target, target =
     * d focus / along; the new direction is target - offset, taken divided by focus (the same
     * direction) so that a focus distance near the float range cannot overflow on the GPU, which
     * does the same. */
    double along = bg_v3_dot(d, camera->forward), offset[3];
    for (int i = 0; i < 3; i++) {
        offset[i] = a * (disc[0] * camera->right[i] + disc[1] * camera->up[i]);
        o[i] += offset[i];
        d[i] = d[i] / along - offset[i] / camera->focus;
    }
    bg_v3_normalize(d);
}
