/* A PLY file's header counts checked against the file's size before assimp reads it. assimp trusts
 * the counts: it allocates what the header declares (2^31 - 1 vertices in a 300-byte file end in
 * std::bad_alloc) and fills what the body lacks with zeros (a header of 1,000,000 vertices over a
 * body of 3 loads). Each element needs at least a known number of bytes (binary: its fixed-size
 * properties, and each list's count) or of numbers (ASCII: one per property, a list at least its
 * count), so a body shorter than the sum cannot hold what the header says. */
#include "model_internal.h"

#include <ctype.h>
#include <errno.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

/* Real headers are a few hundred bytes; a longer one is refused rather than read on and on. */
#define PLY_HEADER_MAX 65536
#define PLY_ELEMENTS_MAX 64

typedef struct ply_element {
    char name[32];
    unsigned long long count;
    unsigned long long bytes;   /* binary: the least bytes one element takes */
    unsigned long long numbers; /* ASCII: the least numbers one element takes */
} ply_element;

typedef struct ply_header {
    bool ascii;
    int elements;
    ply_element element[PLY_ELEMENTS_MAX];
    long length; /* bytes up to and including the end_header line */
} ply_header;

/* Bytes of a PLY scalar type; unknown names take 1 (assimp will refuse them itself). */
static unsigned type_size(const char *t)
{
    static const struct {
        const char *name;
        unsigned size;
    } types[] = {{"char", 1},  {"uchar", 1},  {"int8", 1},   {"uint8", 1},   {"short", 2},  {"ushort", 2},
                 {"int16", 2}, {"uint16", 2}, {"int", 4},    {"uint", 4},    {"int32", 4},  {"uint32", 4},
                 {"float", 4}, {"float32", 4}, {"double", 8}, {"float64", 8}};
    for (size_t i = 0; i < sizeof types / sizeof types[0]; i++)
        if (strcmp(t, types[i].name) == 0)
            return types[i].size;
    return 1;
}

/* a * b + c, saturating at the largest value instead of wrapping. */
static unsigned long long mul_add(unsigned long long a, unsigned long long b, unsigned long long c)
{
    if (b && a > (~0ULL - c) / b)
        return ~0ULL;
    return a * b + c;
}

/* One header line, split into at most 5 words. */
static int words_of(char *line, char *word[5])
{
    int n = 0;
    for (char *save = NULL, *w = strtok_r(line, " \t", &save); w && n < 5; w = strtok_r(NULL, " \t", &save))
        word[n++] = w;
    return n;
}

static bg_status header_line(bgi_sf_ctx *ctx, const char *path, int number, char *line, ply_header *h)
{
    char *w[5];
    int n = words_of(line, w);
    if (n == 0 || strcmp(w[0], "comment") == 0 || strcmp(w[0], "obj_info") == 0)
        return BG_OK;
    if (strcmp(w[0], "format") == 0 && n >= 2) {
        h->ascii = strcmp(w[1], "ascii") == 0;
        return BG_OK;
    }
    if (strcmp(w[0], "element") == 0) {
        char *end = NULL;
        errno = 0;
        unsigned long long count = n == 3 && isdigit((unsigned char)w[2][0]) ? strtoull(w[2], &end, 10) : 0;
        if (n != 3 || !end || *end || errno != 0)
            return bgi_sf_fail(ctx, BG_ERR_INVALID_ARGUMENT, "model file \"%s\": PLY header line %d: an element "
                               "needs a name and a count that is a whole number", path, number);
        if (h->elements == PLY_ELEMENTS_MAX)
            return bgi_sf_fail(ctx, BG_ERR_LIMIT, "model file \"%s\": the PLY header declares more than %d elements",
                               path, PLY_ELEMENTS_MAX);
        ply_element *e = &h->element[h->elements++];
        memset(e, 0, sizeof *e);
        snprintf(e->name, sizeof e->name, "%s", w[1]);
        e->count = count;
        return BG_OK;
    }
    if (strcmp(w[0], "property") == 0 && h->elements > 0) {
        ply_element *e = &h->element[h->elements - 1];
        bool list = n >= 2 && strcmp(w[1], "list") == 0;
        e->bytes += type_size(list ? (n >= 3 ? w[2] : "") : (n >= 2 ? w[1] : ""));
        e->numbers += 1;
    }
    return BG_OK; /* anything else is assimp's to judge */
}

/* Reads the header up to end_header; h->length stays 0 when the file is not a PLY. */
static bg_status read_header(bgi_sf_ctx *ctx, const char *path, FILE *f, ply_header *h)
{
    memset(h, 0, sizeof *h);
    char line[512];
    /* The magic first, so that other formats (a glTF on one long line) are left alone. */
    if (fread(line, 1, 4, f) != 4 || memcmp(line, "ply", 3) != 0 || (line[3] != '\n' && line[3] != '\r'))
        return BG_OK;
    rewind(f);
    for (int number = 1;; number++) {
        if (!fgets(line, sizeof line, f))
            return bgi_sf_fail(ctx, BG_ERR_INVALID_ARGUMENT, "model file \"%s\": the PLY header has no end_header "
                               "line", path);
        size_t len = strlen(line);
        h->length += (long)len;
        if (len + 1 == sizeof line || h->length > PLY_HEADER_MAX)
            return bgi_sf_fail(ctx, BG_ERR_INVALID_ARGUMENT, "model file \"%s\": the PLY header has a line longer "
                               "than %zu bytes or is longer than %d bytes", path, sizeof line - 2, PLY_HEADER_MAX);
        while (len > 0 && (line[len - 1] == '\n' || line[len - 1] == '\r'))
            line[--len] = '\0';
        if (strcmp(line, "end_header") == 0)
            return BG_OK;
        BGI_SF_TRY(header_line(ctx, path, number, line, h));
    }
}

/* Whitespace-separated words in the rest of f, counted up to want (no need to read further). */
static unsigned long long count_words(FILE *f, unsigned long long want)
{
    unsigned long long words = 0;
    bool in_word = false;
    char buf[65536];
    size_t got;
    while (words < want && (got = fread(buf, 1, sizeof buf, f)) > 0)
        for (size_t i = 0; i < got; i++) {
            bool space = isspace((unsigned char)buf[i]) != 0;
            words += !space && !in_word;
            in_word = !space;
        }
    return words;
}

/* "1000000 vertex and 1 face elements" for the message. */
static void describe(const ply_header *h, char *text, size_t size)
{
    size_t n = 0;
    for (int i = 0; i < h->elements && n < size; i++)
        n += (size_t)snprintf(text + n, size - n, "%s%llu %s", i == 0 ? "" : i + 1 == h->elements ? " and " : ", ",
                              h->element[i].count, h->element[i].name);
    if (n < size)
        snprintf(text + n, size - n, " element%s", h->elements == 1 && h->element[0].count == 1 ? "" : "s");
}

bg_status bgi_sf_check_ply_counts(bgi_sf_ctx *ctx, const char *path, FILE *f)
{
    ply_header h;
    BGI_SF_TRY(read_header(ctx, path, f, &h));
    if (h.length == 0)
        return BG_OK;
    unsigned long long need = 0;
    for (int i = 0; i < h.elements; i++)
        need = mul_add(h.element[i].count, h.ascii ? h.element[i].numbers : h.element[i].bytes, need);
    char counts[256];
    describe(&h, counts, sizeof counts);
    if (h.ascii) {
        unsigned long long have = count_words(f, need);
        if (ferror(f))
            return bgi_sf_fail(ctx, BG_ERR_IO, "model file \"%s\": cannot read: %s", path, strerror(errno));
        if (have < need)
            return bgi_sf_fail(ctx, BG_ERR_INVALID_ARGUMENT, "model file \"%s\": the PLY header declares %s, which "
                               "take at least %llu numbers, but the file holds %llu after the header: it ends early "
                               "or the header's counts are wrong", path, counts, need, have);
        return BG_OK;
    }
    struct stat st;
    if (fstat(fileno(f), &st) != 0)
        return bgi_sf_fail(ctx, BG_ERR_IO, "model file \"%s\": cannot read: %s", path, strerror(errno));
    unsigned long long have = st.st_size > h.length ? (unsigned long long)(st.st_size - h.length) : 0;
    if (have < need)
        return bgi_sf_fail(ctx, BG_ERR_INVALID_ARGUMENT, "model file \"%s\": the PLY header declares %s, which take "
                           "at least %llu bytes, but the file has %llu after the header: it ends early or the "
                           "header's counts are wrong", path, counts, need, have);
    return BG_OK;
}
