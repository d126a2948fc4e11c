/* Typed readers of JSON values. Each reads the value at the context's current path and names what
 * it wanted and what it got, so a message reads "objects[0].sphere.radius: must be > 0 (got -1)". */
#include "scenefile_internal.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

const bgi_sf_range bgi_sf_any = {-INFINITY, INFINITY, false, false};
const bgi_sf_range bgi_sf_nonneg = {0.0, INFINITY, false, false};
const bgi_sf_range bgi_sf_positive = {0.0, INFINITY, true, false};
const bgi_sf_range bgi_sf_unit = {0.0, 1.0, false, false};

const char *bgi_sf_type_name(const cJSON *v)
{
    if (!v) return "nothing";
    if (cJSON_IsNumber(v)) return "a number";
    if (cJSON_IsString(v)) return "a string";
    if (cJSON_IsBool(v)) return "a boolean";
    if (cJSON_IsNull(v)) return "null";
    if (cJSON_IsArray(v)) return "an array";
    if (cJSON_IsObject(v)) return "an object";
    return "an unknown value";
}

bg_status bgi_sf_check_object(bgi_sf_ctx *ctx, const cJSON *v, const char *const *allowed)
{
    if (!cJSON_IsObject(v))
        return bgi_sf_fail(ctx, BG_ERR_INVALID_ARGUMENT, "must be an object (got %s)", bgi_sf_type_name(v));
    for (const cJSON *c = v->child; c; c = c->next) {
        bool known = false;
        for (int i = 0; allowed[i] && !known; i++)
            known = strcmp(c->string, allowed[i]) == 0;
        if (!known) {
            char list[512] = "";
            size_t len = 0;
            for (int i = 0; allowed[i]; i++) {
                int n = snprintf(list + len, sizeof list - len, "%s%s", i ? ", " : "", allowed[i]);
                if (n < 0 || (size_t)n >= sizeof list - len)
                    break;
                len += (size_t)n;
            }
            size_t at = bgi_sf_push_key(ctx, c->string);
            bg_status st = bgi_sf_fail(ctx, BG_ERR_INVALID_ARGUMENT, "unknown key \"%s\" (known: %s)", c->string,
                                       allowed[0] ? list : "none");
            bgi_sf_pop(ctx, at);
            return st;
        }
        for (const cJSON *d = v->child; d != c; d = d->next)
            if (strcmp(d->string, c->string) == 0) {
                size_t at = bgi_sf_push_key(ctx, c->string);
                bg_status st = bgi_sf_fail(ctx, BG_ERR_INVALID_ARGUMENT, "the key is given twice");
                bgi_sf_pop(ctx, at);
                return st;
            }
    }
    return BG_OK;
}

static bg_status range_fail(bgi_sf_ctx *ctx, bgi_sf_range r, double x)
{
    if (isinf(r.hi))
        return bgi_sf_fail(ctx, BG_ERR_INVALID_ARGUMENT, "must be %s %g (got %g)", r.lo_open ? ">" : ">=", r.lo, x);
    if (isinf(r.lo))
        return bgi_sf_fail(ctx, BG_ERR_INVALID_ARGUMENT, "must be %s %g (got %g)", r.hi_open ? "<" : "<=", r.hi, x);
    return bgi_sf_fail(ctx, BG_ERR_INVALID_ARGUMENT, "must be in %c%g, %g%c (got %g)", r.lo_open ? '(' : '[', r.lo,
                       r.hi, r.hi_open ? ')' : ']', x);
}

bg_status bgi_sf_number(bgi_sf_ctx *ctx, const cJSON *v, bgi_sf_range r, double *out)
{
    if (!cJSON_IsNumber(v))
        return bgi_sf_fail(ctx, BG_ERR_INVALID_ARGUMENT, "must be a number (got %s)", bgi_sf_type_name(v));
    double x = v->valuedouble;
    /* JSON has no infinity or NaN, but a literal such as 1e999 overflows to infinity when read. */
    if (!isfinite(x))
        return bgi_sf_fail(ctx, BG_ERR_INVALID_ARGUMENT, "must be a finite number (got %g, outside the double range)", x);
    if (x < r.lo || x > r.hi || (r.lo_open && x == r.lo) || (r.hi_open && x == r.hi))
        return range_fail(ctx, r, x);
    *out = x;
    return BG_OK;
}

bg_status bgi_sf_int(bgi_sf_ctx *ctx, const cJSON *v, int lo, int hi, int *out)
{
    double x = 0.0;
    BGI_SF_TRY(bgi_sf_number(ctx, v, bgi_sf_any, &x));
    if (x != floor(x))
        return bgi_sf_fail(ctx, BG_ERR_INVALID_ARGUMENT, "must be a whole number (got %g)", x);
    if (x < lo || x > hi)
        return bgi_sf_fail(ctx, BG_ERR_INVALID_ARGUMENT, "must be in %d .. %d (got %g)", lo, hi, x);
    *out = (int)x;
    return BG_OK;
}

bg_status bgi_sf_bool(bgi_sf_ctx *ctx, const cJSON *v, bool *out)
{
    if (!cJSON_IsBool(v))
        return bgi_sf_fail(ctx, BG_ERR_INVALID_ARGUMENT, "must be true or false (got %s)", bgi_sf_type_name(v));
    *out = cJSON_IsTrue(v);
    return BG_OK;
}

bg_status bgi_sf_string(bgi_sf_ctx *ctx, const cJSON *v, const char **out)
{
    if (!cJSON_IsString(v) || !v->valuestring)
        return bgi_sf_fail(ctx, BG_ERR_INVALID_ARGUMENT, "must be a string (got %s)", bgi_sf_type_name(v));
    *out = v->valuestring;
    return BG_OK;
}

bg_status bgi_sf_numbers(bgi_sf_ctx *ctx, const cJSON *v, int n, bgi_sf_range r, double *out)
{
    if (!cJSON_IsArray(v))
        return bgi_sf_fail(ctx, BG_ERR_INVALID_ARGUMENT, "must be an array of %d numbers (got %s)", n,
                           bgi_sf_type_name(v));
    int count = cJSON_GetArraySize(v);
    if (count != n)
        return bgi_sf_fail(ctx, BG_ERR_INVALID_ARGUMENT, "must be an array of %d numbers (got %d elements)", n, count);
    int i = 0;
    for (const cJSON *c = v->child; c; c = c->next, i++) {
        size_t at = bgi_sf_push_index(ctx, (size_t)i);
        bg_status st = bgi_sf_number(ctx, c, r, &out[i]);
        bgi_sf_pop(ctx, at);
        BGI_SF_TRY(st);
    }
    return BG_OK;
}

bg_status bgi_sf_vec3(bgi_sf_ctx *ctx, const cJSON *v, bg_vec3 *out)
{
    double x[3];
    BGI_SF_TRY(bgi_sf_numbers(ctx, v, 3, bgi_sf_any, x));
    *out = bg_vec3_make(x[0], x[1], x[2]);
    return BG_OK;
}

bg_status bgi_sf_rgb(bgi_sf_ctx *ctx, const cJSON *v, bgi_sf_range r, double out[3])
{
    if (cJSON_IsNumber(v)) {
        double x = 0.0;
        BGI_SF_TRY(bgi_sf_number(ctx, v, r, &x));
        out[0] = out[1] = out[2] = x;
        return BG_OK;
    }
    if (!cJSON_IsArray(v))
        return bgi_sf_fail(ctx, BG_ERR_INVALID_ARGUMENT, "must be a number or an array [r, g, b] (got %s)",
                           bgi_sf_type_name(v));
    return bgi_sf_numbers(ctx, v, 3, r, out);
}

bg_status bgi_sf_enum(bgi_sf_ctx *ctx, const cJSON *v, const char *const *names, int *out)
{
    const char *s = NULL;
    BGI_SF_TRY(bgi_sf_string(ctx, v, &s));
    char list[256] = "";
    size_t len = 0;
    for (int i = 0; names[i]; i++) {
        if (strcmp(s, names[i]) == 0) {
            *out = i;
            return BG_OK;
        }
        int n = snprintf(list + len, sizeof list - len, "%s\"%s\"", i ? ", " : "", names[i]);
        if (n > 0 && (size_t)n < sizeof list - len)
            len += (size_t)n;
    }
    return bgi_sf_fail(ctx, BG_ERR_INVALID_ARGUMENT, "\"%s\" is not one of %s", s, list);
}

const cJSON *bgi_sf_member(const cJSON *obj, const char *key)
{
    return cJSON_GetObjectItemCaseSensitive(obj, key);
}

/* Each field reader: absent keeps the default; present is read at PATH.key. */
#define FIELD_(call)                                  \
    const cJSON *v = bgi_sf_member(obj, key);         \
    if (!v)                                           \
        return BG_OK;                                 \
    size_t at = bgi_sf_push_key(ctx, key);            \
    bg_status st = (call);                            \
    bgi_sf_pop(ctx, at);                              \
    return st

bg_status bgi_sf_field_number(bgi_sf_ctx *ctx, const cJSON *obj, const char *key, bgi_sf_range range, double *out)
{
    FIELD_(bgi_sf_number(ctx, v, range, out));
}

bg_status bgi_sf_field_int(bgi_sf_ctx *ctx, const cJSON *obj, const char *key, int lo, int hi, int *out)
{
    FIELD_(bgi_sf_int(ctx, v, lo, hi, out));
}

bg_status bgi_sf_field_bool(bgi_sf_ctx *ctx, const cJSON *obj, const char *key, bool *out)
{
    FIELD_(bgi_sf_bool(ctx, v, out));
}

bg_status bgi_sf_field_vec3(bgi_sf_ctx *ctx, const cJSON *obj, const char *key, bg_vec3 *out)
{
    FIELD_(bgi_sf_vec3(ctx, v, out));
}

bg_status bgi_sf_field_rgb(bgi_sf_ctx *ctx, const cJSON *obj, const char *key, bgi_sf_range range, double out[3])
{
    FIELD_(bgi_sf_rgb(ctx, v, range, out));
}

bg_status bgi_sf_field_enum(bgi_sf_ctx *ctx, const cJSON *obj, const char *key, const char *const *names, int *out)
{
    FIELD_(bgi_sf_enum(ctx, v, names, out));
}
