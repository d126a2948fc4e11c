/* The binary PLY reader of ply_mesh.h. The header is read line by line against the one layout it
 * takes; the data's size is checked against the header's counts before anything is allocated, so a
 * header that promises millions of vertices in a short file costs nothing. */
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "ply_mesh.h"

#define PLY_MAX_VERTICES (1u << 24)
#define LINE_MAX_CHARS 256
#define HEADER_MAX_LINES 256

/* Reads one header line without its "\n" (or "\r\n"); false at the end of the file or for a line
 * longer than LINE_MAX_CHARS. */
static bool read_line(FILE *f, char line[LINE_MAX_CHARS + 1], bool *too_long)
{
    size_t n = 0;
    int c;
    *too_long = false;
    while ((c = fgetc(f)) != EOF && c != '\n') {
        if (n == LINE_MAX_CHARS) {
            *too_long = true;
            return false;
        }
        line[n++] = (char)c;
    }
    if (c == EOF)
        return false;
    if (n > 0 && line[n - 1] == '\r')
        n--;
    line[n] = '\0';
    return true;
}

/* "element <name> <count>" with a decimal count; false for anything else. */
static bool element_line(const char *line, const char *name, unsigned long *count)
{
    size_t k = strlen(name);
    if (strncmp(line, "element ", 8) != 0 || strncmp(line + 8, name, k) != 0 || line[8 + k] != ' ')
        return false;
    const char *digits = line + 9 + k;
    if (*digits < '0' || *digits > '9')
        return false;
    char *end;
    errno = 0;
    *count = strtoul(digits, &end, 10);
    return *end == '\0' && errno == 0;
}

static uint32_t le32(const unsigned char *b)
{
    return (uint32_t)b[0] | (uint32_t)b[1] << 8 | (uint32_t)b[2] << 16 | (uint32_t)b[3] << 24;
}

/* The header steps after "ply" and the format line, in order. */
enum { STEP_VERTEX, STEP_X, STEP_Y, STEP_Z, STEP_FACE, STEP_LIST, STEP_END, STEP_DONE };

static const char *const step_wanted[] = {
    "element vertex <count>", "property float x", "property float y", "property float z",
    "element face <count>", "property list uchar uint vertex_indices", "end_header",
};

/* Reads the header up to and including end_header; the counts come back in vertices and faces. */
static bg_status read_header(FILE *f, const char *path, unsigned long *vertices, unsigned long *faces, char *why,
                             size_t why_size)
{
    char line[LINE_MAX_CHARS + 1];
    bool too_long;
    int step = -2; /* -2: "ply", -1: the format line */
    for (int number = 1; step != STEP_DONE; number++) {
        if (number > HEADER_MAX_LINES)
            return mesh_fail(why, why_size, BG_ERR_INVALID_ARGUMENT, "%s: bad header: no end_header in %d lines", path,
                             HEADER_MAX_LINES);
        if (!read_line(f, line, &too_long)) {
            if (too_long)
                return mesh_fail(why, why_size, BG_ERR_INVALID_ARGUMENT,
                                 "%s: bad header: line %d is longer than %d characters", path, number, LINE_MAX_CHARS);
            if (ferror(f))
                return mesh_fail(why, why_size, BG_ERR_IO, "%s: cannot read: %s", path, strerror(errno));
            return mesh_fail(why, why_size, BG_ERR_IO, "%s: truncated: the file ends inside the header (line %d)",
                             path, number);
        }
        if (step == -2) {
            if (strcmp(line, "ply") != 0)
                return mesh_fail(why, why_size, BG_ERR_INVALID_ARGUMENT,
                                 "%s: bad header: not a PLY file (line 1 is not \"ply\")", path);
            step++;
            continue;
        }
        if (strncmp(line, "comment", 7) == 0 && (line[7] == ' ' || line[7] == '\0'))
            continue;
        if (strncmp(line, "obj_info", 8) == 0 && (line[8] == ' ' || line[8] == '\0'))
            continue;
        bool ok;
        switch (step) {
        case -1:
            if (strncmp(line, "format ", 7) == 0 && strcmp(line, "format binary_little_endian 1.0") != 0)
                return mesh_fail(why, why_size, BG_ERR_INVALID_ARGUMENT,
                                 "%s: bad header: line %d is \"%s\"; only format binary_little_endian 1.0 is read",
                                 path, number, line);
            ok = strcmp(line, "format binary_little_endian 1.0") == 0;
            break;
        case STEP_VERTEX: ok = element_line(line, "vertex", vertices); break;
        case STEP_X: ok = strcmp(line, "property float x") == 0; break;
        case STEP_Y: ok = strcmp(line, "property float y") == 0; break;
        case STEP_Z: ok = strcmp(line, "property float z") == 0; break;
        case STEP_FACE: ok = element_line(line, "face", faces); break;
        case STEP_LIST:
            ok = strcmp(line, "property list uchar uint vertex_indices") == 0 ||
                 strcmp(line, "property list uchar int vertex_indices") == 0 ||
                 strcmp(line, "property list uchar uint vertex_index") == 0 ||
                 strcmp(line, "property list uchar int vertex_index") == 0;
            break;
        default: ok = strcmp(line, "end_header") == 0; break;
        }
        if (!ok)
            return mesh_fail(why, why_size, BG_ERR_INVALID_ARGUMENT, "%s: bad header: line %d is \"%s\", expected \"%s\"",
                             path, number, line, step < 0 ? "format binary_little_endian 1.0" : step_wanted[step]);
        step++;
    }
    if (*vertices > PLY_MAX_VERTICES || *faces > MESH_MAX_TRIANGLES)
        return mesh_fail(why, why_size, BG_ERR_LIMIT,
                         "%s: %lu vertices and %lu faces; this reader takes at most %u vertices and %u faces", path,
                         *vertices, *faces, PLY_MAX_VERTICES, (unsigned)MESH_MAX_TRIANGLES);
    return BG_OK;
}

/* Checks that the data after the header can hold the counts' vertices and triangles. */
static bg_status check_size(FILE *f, const char *path, unsigned long vertices, unsigned long faces, char *why,
                            size_t why_size)
{
    long start = ftell(f);
    if (start < 0 || fseek(f, 0, SEEK_END) != 0)
        return mesh_fail(why, why_size, BG_ERR_IO, "%s: cannot read: %s", path, strerror(errno));
    long end = ftell(f);
    if (end < 0 || fseek(f, start, SEEK_SET) != 0)
        return mesh_fail(why, why_size, BG_ERR_IO, "%s: cannot read: %s", path, strerror(errno));
    unsigned long long have = (unsigned long long)(end - start);
    unsigned long long vertex_bytes = 12ull * vertices, face_bytes = 13ull * faces;
    if (have < vertex_bytes)
        return mesh_fail(why, why_size, BG_ERR_IO, "%s: truncated: the vertex data ends after %llu of %lu vertices",
                         path, have / 12, vertices);
    if (have < vertex_bytes + face_bytes)
        return mesh_fail(why, why_size, BG_ERR_IO,
                         "%s: truncated: the face data ends after %llu of %lu triangles", path,
                         (have - vertex_bytes) / 13, faces);
    return BG_OK;
}

static bg_status read_data(FILE *f, const char *path, mesh *m, char *why, size_t why_size)
{
    unsigned char b[13];
    for (uint32_t v = 0; v < m->vertex_count; v++) {
        if (fread(b, 1, 12, f) != 12)
            return mesh_fail(why, why_size, BG_ERR_IO, "%s: truncated: the vertex data ends after %u of %u vertices",
                             path, (unsigned)v, (unsigned)m->vertex_count);
        for (int k = 0; k < 3; k++) {
            uint32_t bits = le32(b + 4 * k);
            float x;
            memcpy(&x, &bits, sizeof x);
            if (!isfinite(x))
                return mesh_fail(why, why_size, BG_ERR_INVALID_ARGUMENT, "%s: vertex %u has a coordinate that is not finite",
                                 path, (unsigned)v);
            m->positions[3 * v + k] = x;
        }
    }
    for (uint32_t t = 0; t < m->triangle_count; t++) {
        if (fread(b, 1, 1, f) != 1)
            return mesh_fail(why, why_size, BG_ERR_IO, "%s: truncated: the face data ends after %u of %u triangles",
                             path, (unsigned)t, (unsigned)m->triangle_count);
        if (b[0] != 3)
            return mesh_fail(why, why_size, BG_ERR_INVALID_ARGUMENT,
                             "%s: face %u has %u vertices; only triangles are read", path, (unsigned)t, (unsigned)b[0]);
        if (fread(b + 1, 1, 12, f) != 12)
            return mesh_fail(why, why_size, BG_ERR_IO, "%s: truncated: the face data ends after %u of %u triangles",
                             path, (unsigned)t, (unsigned)m->triangle_count);
        for (int k = 0; k < 3; k++) {
            /* Read as unsigned: a negative int index becomes a huge one, out of range alike. */
            uint32_t index = le32(b + 1 + 4 * k);
            if (index >= m->vertex_count)
                return mesh_fail(why, why_size, BG_ERR_INVALID_ARGUMENT,
                                 "%s: face %u: vertex index %u is out of range (%u vertices)", path, (unsigned)t,
                                 (unsigned)index, (unsigned)m->vertex_count);
            m->indices[3 * t + k] = index;
        }
    }
    if (fgetc(f) != EOF)
        return mesh_fail(why, why_size, BG_ERR_INVALID_ARGUMENT, "%s: unexpected data after the last face", path);
    return BG_OK;
}

bg_status ply_mesh_read(const char *path, mesh *out, char *why, size_t why_size)
{
    if (!out || !path)
        return mesh_fail(why, why_size, BG_ERR_INVALID_ARGUMENT, "ply_mesh_read: %s is NULL", out ? "path" : "out");
    memset(out, 0, sizeof *out);
    FILE *f = fopen(path, "rb");
    if (!f)
        return mesh_fail(why, why_size, BG_ERR_IO, "%s: cannot open: %s", path, strerror(errno));
    unsigned long vertices = 0, faces = 0;
    bg_status st = read_header(f, path, &vertices, &faces, why, why_size);
    if (st == BG_OK)
        st = check_size(f, path, vertices, faces, why, why_size);
    if (st == BG_OK)
        st = mesh_alloc(out, (uint32_t)vertices, (uint32_t)faces, false, false, path, why, why_size);
    if (st == BG_OK)
        st = read_data(f, path, out, why, why_size);
    fclose(f);
    if (st != BG_OK)
        mesh_free(out);
    return st;
}
