#version 110
// requires:
// Duff, Burgess, Christensen, Hery, Kensler, Liani and Villemin (2017): an orthonormal pair a, b
// across the unit vector w, without a branch on a near-zero component; the twin of
// bgi_cpu_basis_across (src/betelgeuse/cpu/cpu_internal.h).
void bg_basis_across(vec3 w, out vec3 a, out vec3 b)
{
    float s = w.z >= 0.0 ? 1.0 : -1.0;
    float k = -1.0 / (s + w.z);
    float m = w.x * w.y * k;
    a = vec3(1.0 + s * w.x * w.x * k, s * m, -s * w.x);
    b = vec3(m, s + w.y * w.y * k, -w.y);
}
