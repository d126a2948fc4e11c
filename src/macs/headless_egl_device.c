/* EGL device backend (EGL_EXT_platform_device): a display on one device that eglQueryDevicesEXT
 * lists, the way NVIDIA's driver and Mesa's run on a server without a window system. Mesa lists its
 * software device (EGL_MESA_device_software) last, and glvnd lists each vendor's devices in turn, so
 * trying the devices in order tries the hardware first. */
#include <stdio.h>
#include <string.h>

#include "headless_egl.h"
#include "internal.h"

/* The entry points of EGL_EXT_device_enumeration and EGL_EXT_device_query; query_string stays NULL
 * where the query extension is absent (devices are then nameless). */
typedef struct device_api {
    PFNEGLQUERYDEVICESEXTPROC query_devices;
    PFNEGLQUERYDEVICESTRINGEXTPROC query_string;
} device_api;

/* The devices as EGL lists them, in memory of the headless context's allocator. */
typedef struct device_list {
    EGLDeviceEXT *devices;
    EGLint count;
} device_list;

/* EGL_EXT_device_base is the older name of enumeration and query together. */
static bool client_has_device(const macsi_egl_api *egl, const char *extension)
{
    return macsi_egl_client_has(egl, extension) || macsi_egl_client_has(egl, "EGL_EXT_device_base");
}

static macs_status load_api(const macsi_egl_api *egl, device_api *api, char *message, size_t size)
{
    memset(api, 0, sizeof *api);
    if (!macsi_egl_client_has(egl, "EGL_EXT_platform_device") ||
        !client_has_device(egl, "EGL_EXT_device_enumeration")) {
        snprintf(message, size, "EGL_EXT_platform_device or EGL_EXT_device_enumeration is missing from the client "
                 "extensions");
        return MACS_ERR_CONTEXT;
    }
    api->query_devices = (PFNEGLQUERYDEVICESEXTPROC)egl->GetProcAddress("eglQueryDevicesEXT");
    if (!api->query_devices) {
        snprintf(message, size, "eglQueryDevicesEXT not found");
        return MACS_ERR_CONTEXT;
    }
    if (client_has_device(egl, "EGL_EXT_device_query"))
        api->query_string = (PFNEGLQUERYDEVICESTRINGEXTPROC)egl->GetProcAddress("eglQueryDeviceStringEXT");
    return MACS_OK;
}

/* The devices as EGL lists them; a count of 0 is no failure here, the caller says what it meant. */
static macs_status list_devices(const macs_allocator *a, const device_api *api, device_list *list, char *message,
                                size_t size)
{
    list->devices = NULL;
    list->count = 0;
    EGLint count = 0;
    if (!api->query_devices(0, NULL, &count) || count < 1)
        return MACS_OK;
    list->devices = macsi_calloc(a, (size_t)count, sizeof *list->devices);
    if (!list->devices) {
        snprintf(message, size, "out of memory");
        return MACS_ERR_OUT_OF_MEMORY;
    }
    if (!api->query_devices(count, list->devices, &list->count) || list->count < 0)
        list->count = 0;
    return MACS_OK;
}

/* A device string, "" where the device or EGL cannot say. */
static const char *device_string(const device_api *api, EGLDeviceEXT device, EGLint name)
{
    const char *s = api->query_string ? api->query_string(device, name) : NULL;
    return s ? s : "";
}

/* What a person knows the device by: "software" for Mesa's software device, else its DRM device file
 * or render node, else the renderer name the device gives, else "". */
static const char *device_name(const device_api *api, EGLDeviceEXT device)
{
    const char *ext = device_string(api, device, EGL_EXTENSIONS);
    if (macsi_gl_has_extension(ext, "EGL_MESA_device_software"))
        return "software";
    static const struct { const char *extension; EGLint name; } sources[] = {
        {"EGL_EXT_device_drm", EGL_DRM_DEVICE_FILE_EXT},
        {"EGL_EXT_device_drm_render_node", EGL_DRM_RENDER_NODE_FILE_EXT},
        {"EGL_EXT_device_query_name", EGL_RENDERER_EXT},
    };
    for (size_t i = 0; i < sizeof sources / sizeof sources[0]; i++)
        if (macsi_gl_has_extension(ext, sources[i].extension)) {
            const char *name = device_string(api, device, sources[i].name);
            if (name[0])
                return name;
        }
    return "";
}

/* Keeps which device the context is on, in the headless context's own copies. */
static macs_status record_device(macs_headless *h, const device_api *api, const device_list *list, int index)
{
    EGLDeviceEXT device = list->devices[index];
    h->device_index = index;
    h->device_count = list->count;
    h->device_name = macsi_strdup(&h->allocator, device_name(api, device));
    h->device_extensions = macsi_strdup(&h->allocator, device_string(api, device, EGL_EXTENSIONS));
    return h->device_name && h->device_extensions ? MACS_OK : MACS_ERR_OUT_OF_MEMORY;
}

static macs_status create_on_device(macs_headless *h, const macsi_egl_api *egl, EGLDeviceEXT device, char *message,
                                    size_t size)
{
    EGLDisplay display;
    macs_status st = macsi_egl_platform_display(egl, EGL_PLATFORM_DEVICE_EXT, device, &display, message, size);
    if (st == MACS_OK)
        st = macsi_egl_create_on(h, egl, display, message, size);
    return st;
}

/* Appends "device i (name): reason" to the reasons so far. */
static void note_failure(char *message, size_t size, int index, const char *name, const char *why)
{
    size_t used = strlen(message);
    if (used + 1 < size)
        snprintf(message + used, size - used, "%sdevice %d%s%s%s: %s", used ? "; " : "", index, name[0] ? " (" : "",
                 name, name[0] ? ")" : "", why);
}

/* index < 0: every device in turn until one gives a context; else that device only. */
static macs_status create_on_list(macs_headless *h, const macsi_egl_api *egl, const device_api *api,
                                  const device_list *list, int index, char *message, size_t size)
{
    if (index >= list->count) {
        /* A device the caller named that is not there is the caller's to fix, unless there is none. */
        snprintf(message, size, "desc.device_index %d does not exist: EGL lists %d device%s", index,
                 (int)list->count, list->count == 1 ? "" : "s");
        return list->count > 0 ? MACS_ERR_INVALID_ARGUMENT : MACS_ERR_CONTEXT;
    }
    if (list->count < 1) {
        snprintf(message, size, "eglQueryDevicesEXT lists no device");
        return MACS_ERR_CONTEXT;
    }
    int first = index < 0 ? 0 : index, last = index < 0 ? (int)list->count - 1 : index;
    message[0] = '\0';
    for (int i = first; i <= last; i++) {
        char why[512] = "";
        macs_status st = create_on_device(h, egl, list->devices[i], why, sizeof why);
        if (st == MACS_OK) {
            st = record_device(h, api, list, i);
            if (st != MACS_OK) {
                macsi_egl_destroy(h);
                snprintf(message, size, "out of memory");
            }
            return st;
        }
        note_failure(message, size, i, device_name(api, list->devices[i]), why);
        if (st != MACS_ERR_CONTEXT)
            return st;
    }
    return MACS_ERR_CONTEXT;
}

static macs_status create_with(macs_headless *h, const macsi_egl_api *egl, int index, char *message, size_t size)
{
    device_api api;
    device_list list;
    macs_status st = load_api(egl, &api, message, size);
    if (st == MACS_OK)
        st = list_devices(&h->allocator, &api, &list, message, size);
    if (st != MACS_OK)
        return st;
    st = create_on_list(h, egl, &api, &list, index, message, size);
    macsi_free(&h->allocator, list.devices);
    return st;
}

macs_status macsi_egl_device_create(macs_headless *h, int index, char *message, size_t size)
{
    macsi_egl_api egl;
    macs_status st = macsi_egl_api_load(&egl, message, size);
    if (st != MACS_OK)
        return st;
    st = create_with(h, &egl, index, message, size);
    macsi_egl_api_unload(&egl);
    return st;
}
