/* A PLY file checked whole before assimp reads it. assimp 5.2's PLY reader trusts what it reads: it
 * allocates what a header declares (2^31 - 1 vertices in a 300-byte file end in std::bad_alloc, a
 * list count in gigabytes), fills a short body with zeros (a header of 1,000,000 vertices over a
 * body of 3 loads), passes face indices on unchecked, and on a header it half understands it hangs,
 * reads past its buffer or fails an assertion that aborts the process (all found by fuzzing). So
 * this reader, which allocates nothing that depends on the file, walks the file first:
 *   - the header strictly: the magic line "ply", one format line, then element, property,
 *     comment and obj_info lines, up to end_header, with known types; any other line is skipped
 *     with a warning, as assimp skips it (old exporters wrote lines such as "Created by ..."),
 *     unless its first word starts like a keyword ("elements", "property2"), which assimp may
 *     half parse;
 *   - the counts against the file's size (each element takes at least one number per property in
 *     ASCII, its fixed-size properties and list counts in binary), before anything is read;
 *   - the body element by element: every ASCII element one line of numbers (assimp reads them
 *     line by line), every list count within the file, every face's vertex indices within the
 *     vertices, and nothing after the last element but white space (ASCII).
 * A file that is not a PLY (no "ply" at its start) is left to assimp. */
#include "model_internal.h"

#include <ctype.h>
#include <stdarg.h>
#include <errno.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>
#include <sys/stat.h>

/* Real headers are a few hundred bytes; a longer one is refused rather than read on and on. */
#define PLY_HEADER_MAX 65536
#define PLY_ELEMENTS_MAX 64
#define PLY_PROPERTIES_MAX 64

typedef enum ply_format { PLY_NONE = 0, PLY_ASCII, PLY_LITTLE, PLY_BIG } ply_format;

typedef struct ply_type {
    const char *name;
    unsigned size;
    bool integer, is_signed;
} ply_type;

static const ply_type ply_types[] = {
    {"char", 1, true, true},    {"int8", 1, true, true},    {"uchar", 1, true, false},  {"uint8", 1, true, false},
    {"short", 2, true, true},   {"int16", 2, true, true},   {"ushort", 2, true, false}, {"uint16", 2, true, false},
    {"int", 4, true, true},     {"int32", 4, true, true},   {"uint", 4, true, false},   {"uint32", 4, true, false},
    {"float", 4, false, true},  {"float32", 4, false, true}, {"double", 8, false, true}, {"float64", 8, false, true},
};

typedef struct ply_property {
    const ply_type *type;  /* a scalar's type, or a list's item type */
    const ply_type *count; /* a list's count type; NULL for a scalar */
    bool indices;          /* a face's vertex_indices: checked against the vertex count */
} ply_property;

typedef struct ply_element {
    char name[32];
    unsigned long long count;
    int properties;
    ply_property property[PLY_PROPERTIES_MAX];
} ply_element;

typedef struct ply {
    bgi_sf_ctx *ctx;
    const char *path;
    FILE *f;
    ply_format format;
    int elements;
    ply_element element[PLY_ELEMENTS_MAX];
    unsigned long long vertices; /* the vertex element's count */
    int skipped;                 /* header lines of no PLY keyword, skipped */
    int first_skipped;           /* the number of the first of them */
    char skipped_word[41];       /* and its first word */
    long header_length;          /* bytes up to and including the end_header line */
} ply;

/* "model file "PATH": reason": every refusal is bad input, named by the file. */
static bg_status fail(ply *p, const char *format, ...) BGI_SF_PRINTF_(2, 3);

static bg_status fail(ply *p, const char *format, ...)
{
    char reason[512];
    va_list ap;
    va_start(ap, format);
    vsnprintf(reason, sizeof reason, format, ap);
    va_end(ap);
    return bgi_sf_fail(p->ctx, BG_ERR_INVALID_ARGUMENT, "model file \"%s\": %s", p->path, reason);
}

static const ply_type *type_named(const char *name)
{
    for (size_t i = 0; i < sizeof ply_types / sizeof ply_types[0]; i++)
        if (strcmp(name, ply_types[i].name) == 0)
            return &ply_types[i];
    return NULL;
}

/* ---- the header ---- */

/* One header line, split into at most 6 words (7 would be too many for any keyword). */
static int words_of(char *line, char *word[7])
{
    int n = 0;
    for (char *save = NULL, *w = strtok_r(line, " \t", &save); w && n < 7; w = strtok_r(NULL, " \t", &save))
        word[n++] = w;
    return n;
}

static bg_status header_format(ply *p, int number, char **w, int n)
{
    static const char *const names[] = {"ascii", "binary_little_endian", "binary_big_endian"};
    if (p->format != PLY_NONE || p->elements > 0)
        return fail(p, "PLY header line %d: a second format line, or one after the elements", number);
    for (int i = 0; n == 3 && i < 3; i++)
        if (strcmp(w[1], names[i]) == 0 && strcmp(w[2], "1.0") == 0) {
            p->format = (ply_format)(PLY_ASCII + i);
            return BG_OK;
        }
    return fail(p, "PLY header line %d: the format must be ascii, binary_little_endian or binary_big_endian, "
                "version 1.0", number);
}

static bg_status header_element(ply *p, int number, char **w, int n)
{
    char *end = NULL;
    errno = 0;
    unsigned long long count = n == 3 && isdigit((unsigned char)w[2][0]) ? strtoull(w[2], &end, 10) : 0;
    if (n != 3 || !end || *end || errno != 0 || count > 0xffffffffULL || strlen(w[1]) >= sizeof p->element[0].name)
        return fail(p, "PLY header line %d: an element needs a short name and a count of at most 2^32 - 1",
                    number);
    if (p->format == PLY_NONE)
        return fail(p, "PLY header line %d: an element before the format line", number);
    if (p->elements == PLY_ELEMENTS_MAX)
        return fail(p, "the PLY header declares more than %d elements", PLY_ELEMENTS_MAX);
    ply_element *e = &p->element[p->elements++];
    memset(e, 0, sizeof *e);
    snprintf(e->name, sizeof e->name, "%s", w[1]);
    e->count = count;
    if (strcmp(e->name, "vertex") == 0)
        p->vertices = count;
    /* assimp 5.2 reads a file of triangle strips as one triangle, without a word (the Stanford
     * igea.ply): refused by name rather than rendered as a sliver. */
    if (strcmp(e->name, "tristrips") == 0 && count > 0)
        return fail(p, "PLY header line %d: triangle strips (element tristrips) are not read: the model would "
                    "lose all but one triangle; convert the strips to faces", number);
    return BG_OK;
}

static bg_status header_property(ply *p, int number, char **w, int n)
{
    if (p->elements == 0)
        return fail(p, "PLY header line %d: a property before any element", number);
    ply_element *e = &p->element[p->elements - 1];
    if (e->properties == PLY_PROPERTIES_MAX)
        return fail(p, "PLY element \"%s\" has more than %d properties", e->name, PLY_PROPERTIES_MAX);
    ply_property *pr = &e->property[e->properties];
    memset(pr, 0, sizeof *pr);
    bool list = n >= 2 && strcmp(w[1], "list") == 0;
    if (list && n == 5) {
        pr->count = type_named(w[2]);
        pr->type = type_named(w[3]);
        pr->indices = strcmp(e->name, "face") == 0 &&
                      (strcmp(w[4], "vertex_indices") == 0 || strcmp(w[4], "vertex_index") == 0);
        if (!pr->count || !pr->type || !pr->count->integer || (pr->indices && !pr->type->integer))
            return fail(p, "PLY header line %d: a list needs an integer count type and a known item type (an "
                        "integer one for vertex indices)", number);
    } else if (!list && n == 3) {
        pr->type = type_named(w[1]);
        if (!pr->type)
            return fail(p, "PLY header line %d: unknown property type \"%.40s\"", number, w[1]);
    } else {
        return fail(p, "PLY header line %d: a property is \"property TYPE NAME\" or \"property list TYPE TYPE "
                    "NAME\"", number);
    }
    e->properties++;
    return BG_OK;
}

static bg_status header_line(ply *p, int number, char *line)
{
    char *w[7];
    int n = words_of(line, w);
    if (n > 0 && (strcmp(w[0], "comment") == 0 || strcmp(w[0], "obj_info") == 0))
        return BG_OK;
    if (n > 0 && strcmp(w[0], "format") == 0)
        return header_format(p, number, w, n);
    if (n > 0 && strcmp(w[0], "element") == 0)
        return header_element(p, number, w, n);
    if (n > 0 && strcmp(w[0], "property") == 0)
        return header_property(p, number, w, n);
    static const char *const keywords[] = {"format", "element", "property", "comment", "obj_info", "end_header"};
    for (size_t k = 0; n > 0 && k < sizeof keywords / sizeof keywords[0]; k++)
        if (strncmp(w[0], keywords[k], strlen(keywords[k])) == 0)
            return fail(p, "PLY header line %d: \"%.40s\" is not a PLY header keyword (format, element, property, "
                        "comment, obj_info, end_header)", number, w[0]);
    if (p->skipped++ == 0) {
        p->first_skipped = number;
        snprintf(p->skipped_word, sizeof p->skipped_word, "%s", n > 0 ? w[0] : "");
    }
    return BG_OK;
}

/* One warning for every skipped header line, naming the first. */
static void warn_skipped(ply *p)
{
    if (p->skipped == 0)
        return;
    bgi_sf_warn(p->ctx, "model file \"%s\": PLY header line %d (\"%s\") is not a PLY header keyword and was "
                "skipped%s", p->path, p->first_skipped, p->skipped_word,
                p->skipped > 1 ? ", with the other lines of no keyword" : "");
}

/* The header up to end_header; f is left at the body's first byte. */
static bg_status read_header(ply *p)
{
    char line[512];
    for (int number = 1;; number++) {
        long at = ftell(p->f);
        if (!fgets(line, sizeof line, p->f))
            return fail(p, "the PLY header has no end_header line");
        long end = ftell(p->f);
        size_t len = at >= 0 && end > at ? (size_t)(end - at) : strlen(line);
        p->header_length = end;
        if (memchr(line, '\0', len))
            return fail(p, "PLY header line %d holds a NUL byte", number);
        if ((len + 1 == sizeof line && line[len - 1] != '\n') || end > PLY_HEADER_MAX)
            return fail(p, "the PLY header has a line longer than %zu bytes or is longer than %d bytes",
                        sizeof line - 2, PLY_HEADER_MAX);
        while (len > 0 && (line[len - 1] == '\n' || line[len - 1] == '\r'))
            line[--len] = '\0';
        if (number == 1) {
            if (strcmp(line, "ply") != 0 && strcmp(line, "PLY") != 0)
                return fail(p, "the first line of a PLY file must be \"ply\"");
        } else if (strcmp(line, "end_header") == 0) {
            for (int i = 0; i < p->elements; i++)
                if (p->element[i].count > 0 && p->element[i].properties == 0)
                    return fail(p, "PLY element \"%s\" has %llu instances but no properties", p->element[i].name,
                                p->element[i].count);
            if (p->format == PLY_NONE)
                return fail(p, "the PLY header has no format line");
            warn_skipped(p);
            return BG_OK;
        } else {
            BGI_SF_TRY(header_line(p, number, line));
        }
    }
}

/* ---- the counts against the size ---- */

/* a * b + c, saturating at the largest value instead of wrapping. */
static unsigned long long mul_add(unsigned long long a, unsigned long long b, unsigned long long c)
{
    if (b && a > (~0ULL - c) / b)
        return ~0ULL;
    return a * b + c;
}

/* "1000000 vertex and 1 face elements", for the message. */
static void describe(const ply *p, char *text, size_t size)
{
    size_t n = 0;
    for (int i = 0; i < p->elements && n < size; i++)
        n += (size_t)snprintf(text + n, size - n, "%s%llu %s", i == 0 ? "" : i + 1 == p->elements ? " and " : ", ",
                              p->element[i].count, p->element[i].name);
    if (n < size)
        snprintf(text + n, size - n, " element%s", p->elements == 1 && p->element[0].count == 1 ? "" : "s");
}

/* The least the body can be: bytes in binary, numbers in ASCII. */
static unsigned long long least_body(const ply *p)
{
    unsigned long long need = 0;
    for (int i = 0; i < p->elements; i++) {
        unsigned long long one = 0;
        for (int k = 0; k < p->element[i].properties; k++) {
            const ply_property *pr = &p->element[i].property[k];
            one += p->format == PLY_ASCII ? 1 : pr->count ? pr->count->size : pr->type->size;
        }
        need = mul_add(p->element[i].count, one, need);
    }
    return need;
}

/* Whitespace-separated words from the body on, counted up to want. */
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

static bg_status check_size(ply *p)
{
    unsigned long long need = least_body(p), have;
    char counts[256];
    describe(p, counts, sizeof counts);
    if (p->format == PLY_ASCII) {
        have = count_words(p->f, need);
        if (fseek(p->f, p->header_length, SEEK_SET) != 0 || ferror(p->f))
            return bgi_sf_fail(p->ctx, BG_ERR_IO, "model file \"%s\": cannot read: %s", p->path, strerror(errno));
        if (have < need)
            return bgi_sf_fail(p->ctx, BG_ERR_INVALID_ARGUMENT, "model file \"%s\": the PLY header declares %s, "
                               "which take at least %llu numbers, but the file holds %llu after the header: it ends "
                               "early or the header's counts are wrong", p->path, counts, need, have);
        return BG_OK;
    }
    struct stat st;
    if (fstat(fileno(p->f), &st) != 0)
        return bgi_sf_fail(p->ctx, BG_ERR_IO, "model file \"%s\": cannot read: %s", p->path, strerror(errno));
    have = st.st_size > p->header_length ? (unsigned long long)(st.st_size - p->header_length) : 0;
    if (have < need)
        return bgi_sf_fail(p->ctx, BG_ERR_INVALID_ARGUMENT, "model file \"%s\": the PLY header declares %s, which "
                           "take at least %llu bytes, but the file has %llu after the header: it ends early or the "
                           "header's counts are wrong", p->path, counts, need, have);
    return BG_OK;
}

/* ---- the body ---- */

/* The next value of the body as a number (an ASCII word on the element's line, or size bytes in the
 * file's byte order); false at the end of the line or the file, or on a word that is not a number
 * of the type. An ASCII element is one line: assimp reads it line by line, so a value on the next
 * line would be read by the two differently. */
static bool next_value(ply *p, const ply_type *t, double *out)
{
    if (p->format == PLY_ASCII) {
        char word[64];
        int c, n = 0;
        while ((c = getc(p->f)) == ' ' || c == '\t' || c == '\r')
            ;
        for (; c != EOF && !isspace(c); c = getc(p->f))
            if (n < (int)sizeof word - 1)
                word[n++] = (char)c;
        if (c != EOF)
            ungetc(c, p->f);
        word[n] = '\0';
        char *end = NULL;
        errno = 0;
        *out = t->integer ? (double)strtoll(word, &end, 10) : strtod(word, &end);
        return n > 0 && n < (int)sizeof word - 1 && end && *end == '\0' && (!t->integer || errno == 0);
    }
    unsigned char b[8];
    if (fread(b, 1, t->size, p->f) != t->size)
        return false;
    if (!t->integer) {
        *out = 0; /* a float's bits are never checked, only skipped */
        return true;
    }
    unsigned long long v = 0;
    for (unsigned i = 0; i < t->size; i++)
        v |= (unsigned long long)b[p->format == PLY_LITTLE ? i : t->size - 1 - i] << (8 * i);
    if (t->is_signed && (v >> (8 * t->size - 1)))
        *out = -(double)((~v + 1) & ((1ULL << (8 * t->size)) - 1)); /* two's complement */
    else
        *out = (double)v;
    return true;
}

/* The end of an ASCII element's line: nothing but spaces before the line end (or the file's). */
static bool line_ends(ply *p)
{
    int c;
    while ((c = getc(p->f)) == ' ' || c == '\t' || c == '\r')
        ;
    return c == '\n' || c == EOF;
}

/* One list: its count within what the file can still hold, then its items (indices checked). */
static bg_status read_list(ply *p, const ply_element *e, unsigned long long index, const ply_property *pr,
                           unsigned long long left)
{
    double count, v;
    if (!next_value(p, pr->count, &count))
        return fail(p, "PLY %s element %llu: a list count that is not a number, or its line or the file ends early", e->name,
                    index);
    /* An ASCII item takes at least two bytes (a digit and a space), a binary one its size. */
    double room = p->format == PLY_ASCII ? (double)left : (double)(left / pr->type->size);
    /* A face of fewer than 3 vertices is no polygon; assimp's triangulation aborts the process on
     * one with none (found by fuzzing). */
    if (pr->indices && count < 3)
        return fail(p, "PLY %s element %llu: a face of %.0f vertices (a face needs at least 3)", e->name, index,
                    count);
    if (count < 0 || count > room)
        return fail(p, "PLY %s element %llu: a list count of %.0f, more than the file can still hold", e->name, index,
                    count);
    for (unsigned long long i = 0; i < (unsigned long long)count; i++) {
        if (!next_value(p, pr->type, &v))
            return fail(p, "PLY %s element %llu: a list item that is not a number, or its line or the file ends early", e->name,
                        index);
        if (pr->indices && !(v >= 0 && v < (double)p->vertices)) {
            return fail(p, "PLY %s element %llu: vertex index %.0f is out of range (the file has %llu vertices)",
                        e->name, index, v, p->vertices);
        }
    }
    return BG_OK;
}

static bg_status read_body(ply *p, unsigned long long size)
{
    for (int i = 0; i < p->elements; i++) {
        const ply_element *e = &p->element[i];
        for (unsigned long long k = 0; k < e->count; k++)
            for (int j = 0; j < e->properties; j++) {
                const ply_property *pr = &e->property[j];
                double v;
                if (pr->count) {
                    long at = ftell(p->f);
                    unsigned long long left = at >= 0 && (unsigned long long)at < size ? size - (unsigned long long)at
                                                                                       : 0;
                    BGI_SF_TRY(read_list(p, e, k, pr, left));
                } else if (!next_value(p, pr->type, &v)) {
                    return fail(p, "PLY %s element %llu: a value that is not a number, or its line or the file "
                                "ends early", e->name, k);
                }
                if (j + 1 == e->properties && p->format == PLY_ASCII && !line_ends(p))
                    return fail(p, "PLY %s element %llu: more values on its line than its properties (an ASCII "
                                "element is one line)", e->name, k);
            }
    }
    if (p->format == PLY_ASCII) {
        int c;
        while ((c = getc(p->f)) != EOF && isspace(c))
            ;
        if (c != EOF)
            return fail(p, "more data after the last element than the header declares");
    }
    return BG_OK;
}

bg_status bgi_sf_check_ply(bgi_sf_ctx *ctx, const char *path, FILE *f)
{
    char magic[3];
    bool is_ply = fread(magic, 1, 3, f) == 3 && strncasecmp(magic, "ply", 3) == 0;
    rewind(f);
    if (!is_ply)
        return BG_OK;
    ply *p = calloc(1, sizeof *p);
    if (!p)
        return bgi_sf_fail(ctx, BG_ERR_OUT_OF_MEMORY, "out of memory reading \"%s\"", path);
    p->ctx = ctx;
    p->path = path;
    p->f = f;
    struct stat st;
    bg_status s = read_header(p);
    if (s == BG_OK)
        s = check_size(p);
    if (s == BG_OK && fstat(fileno(f), &st) != 0)
        s = bgi_sf_fail(ctx, BG_ERR_IO, "model file \"%s\": cannot read: %s", path, strerror(errno));
    if (s == BG_OK)
        s = read_body(p, (unsigned long long)st.st_size);
    free(p);
    return s;
}
