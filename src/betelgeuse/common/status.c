/* Status messages, generated from the one list in betelgeuse.h. */
#include "betelgeuse.h"

const char *bg_status_string(bg_status status)
{
    switch (status) {
#define BG_STATUS_CASE_(name, value, message) \
    case name:                                \
        return message;
        BG_STATUS_LIST(BG_STATUS_CASE_)
#undef BG_STATUS_CASE_
    default:
        return "unknown status";
    }
}
