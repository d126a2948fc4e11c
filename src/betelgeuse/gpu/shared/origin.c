/* The GPU's world frame is moved to the camera (docs/gpu_pipeline.md, "Camera-relative frame").
 *
 * A float keeps 24 bits of a position, so a scene 1e4 units from the origin loses positions to steps
 * of 1e-3 wherever they are stored as floats: the eye, each object's inverse transform (whose
 * translation column holds -1e4-sized terms that cancel against the ray origin inside the shader)
 * and the light positions. The stress cases measured a sphere's silhouette moving by a twentieth of
 * a pixel at offset 1e4 and its texture tearing at 1e6 (bench/stress.c). Subtracting the camera
 * position in double on the host, before anything becomes a float, leaves the GPU numbers that are
 * as small as the scene's extent around the camera: the image no longer depends on where the scene
 * is, only on how large it is. Directions, normals and distances do not change, so nothing else
 * (dmax, scissor rectangles, shading) sees the move. */
#include "shared.h"

static const double *origin_of(const bg_scene_state *state)
{
    return &state->camera.camera.position.x;
}

void bgi_gpu_origin_to_object(const bg_scene_state *state, uint32_t object, float m16[16])
{
    const double *o = origin_of(state);
    const double(*m)[4] = state->objects[object].to_object;
    /* to_object applied to (q + o), q the camera-relative point: the linear part is unchanged and
     * the translation gains L o, summed in double so that the large terms cancel exactly enough. */
    for (int r = 0; r < 4; r++) {
        double t = m[r][3];
        if (r < 3)
            t += m[r][0] * o[0] + m[r][1] * o[1] + m[r][2] * o[2];
        for (int c = 0; c < 3; c++)
            m16[c * 4 + r] = (float)m[r][c];
        m16[12 + r] = (float)t;
    }
}

void bgi_gpu_origin_point(const bg_scene_state *state, const bg_vec3 *p, float out[3])
{
    const double *o = origin_of(state);
    out[0] = (float)(p->x - o[0]);
    out[1] = (float)(p->y - o[1]);
    out[2] = (float)(p->z - o[2]);
}
