/* Preloaded into a process that uses Embree (LD_PRELOAD), appends
 * $EMBREE_EXTRA_CONFIG to the configuration string of every rtcNewDevice
 * call, e.g. "max_isa=avx2": the embreex package creates its device with no
 * configuration and offers no way to pass one, and Embree 4 reads no
 * configuration file or variable. `replay_vs_embree.sh -i ISA` builds and
 * uses it, to time Embree with the kernels it picks on a machine without
 * AVX-512 (the kind issue 13 names) on one that has it.
 *
 * Python loads extension modules with RTLD_LOCAL, so the real function is
 * not found with RTLD_NEXT: $EMBREE_REAL_LIB names the library that has it. */
#define _GNU_SOURCE
#include <dlfcn.h>
#include <stdio.h>
#include <stdlib.h>

typedef void *(*new_device_fn)(const char *);

static new_device_fn real_new_device(void) {
    static new_device_fn real;
    if (real) return real;
    const char *lib = getenv("EMBREE_REAL_LIB");
    void *handle = lib ? dlopen(lib, RTLD_NOW | RTLD_NOLOAD) : NULL;
    real = (new_device_fn)dlsym(handle ? handle : RTLD_NEXT, "rtcNewDevice");
    if (!real) {
        fprintf(stderr, "embree_max_isa: rtcNewDevice not found (EMBREE_REAL_LIB=%s)\n", lib ? lib : "");
        abort();
    }
    return real;
}

void *rtcNewDevice(const char *config) {
    static char merged[4096];
    const char *extra = getenv("EMBREE_EXTRA_CONFIG");
    if (extra && *extra) {
        snprintf(merged, sizeof merged, "%s%s%s", config ? config : "", config && *config ? "," : "", extra);
        config = merged;
    }
    return real_new_device()(config);
}
