/* A pass over the JSON text before cJSON parses it, for the two things cJSON gets wrong without a
 * word: it stops at a fixed nesting depth and then reports only "not valid JSON" at some column, and
 * it decodes an escaped NUL (\u0000) into its C string, where the name or path silently ends (a
 * texture "real.png\u0000.evil" would load real.png). The pass follows strings and escapes the way
 * a JSON reader must, so brackets and "\u0000" inside strings, or an escaped backslash before "u",
 * are told apart; anything else malformed is left to cJSON's own message. */
#include "scenefile_internal.h"

void bgi_sf_line_column(const char *text, const char *at, int *line, int *column)
{
    *line = 1;
    *column = 1;
    for (const char *p = text; p < at && *p; p++) {
        if (*p == '\n') {
            ++*line;
            *column = 1;
        } else {
            ++*column;
        }
    }
}

static bg_status fail_at(bgi_sf_ctx *ctx, const char *text, const char *at, const char *reason)
{
    int line, column;
    bgi_sf_line_column(text, at, &line, &column);
    return bgi_sf_fail(ctx, BG_ERR_INVALID_ARGUMENT, "line %d, column %d: %s", line, column, reason);
}

/* The escape at p (just after its backslash) is \u0000. */
static bool is_escaped_nul(const char *p)
{
    return p[0] == 'u' && p[1] == '0' && p[2] == '0' && p[3] == '0' && p[4] == '0';
}

bg_status bgi_sf_json_scan(bgi_sf_ctx *ctx, const char *text)
{
    int depth = 0;
    bool in_string = false;
    for (const char *p = text; *p; p++) {
        if (in_string) {
            if (*p == '"') {
                in_string = false;
            } else if (*p == '\\') {
                if (is_escaped_nul(p + 1))
                    return fail_at(ctx, text, p, "a string holds an escaped NUL (\\u0000), which no name, key or "
                                                 "file name may hold");
                if (p[1])
                    p++; /* the escaped character, whatever it is, cannot end the string */
            }
        } else if (*p == '"') {
            in_string = true;
        } else if (*p == '[' || *p == '{') {
            if (++depth > CJSON_NESTING_LIMIT) {
                char reason[128];
                snprintf(reason, sizeof reason, "arrays and objects are nested deeper than %d levels, the limit of "
                         "the JSON reader", CJSON_NESTING_LIMIT);
                return fail_at(ctx, text, p, reason);
            }
        } else if (*p == ']' || *p == '}') {
            depth--;
        }
    }
    return BG_OK;
}
