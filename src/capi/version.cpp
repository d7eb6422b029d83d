// The C API's status names and version: answers that need no handle and cannot fail.
#include "vksplat/version.hpp"
#include "vksplat/vksplat.h"

extern "C" {

const char* vksplat_status_name(vksplat_status status) {
    switch (status) {
        case VKSPLAT_OK: return "VKSPLAT_OK";
        case VKSPLAT_INVALID_ARGUMENT: return "VKSPLAT_INVALID_ARGUMENT";
        case VKSPLAT_INVALID_INPUT: return "VKSPLAT_INVALID_INPUT";
        case VKSPLAT_GPU_ERROR: return "VKSPLAT_GPU_ERROR";
        case VKSPLAT_OUT_OF_MEMORY: return "VKSPLAT_OUT_OF_MEMORY";
        case VKSPLAT_INTERNAL_ERROR: return "VKSPLAT_INTERNAL_ERROR";
    }
    return "unknown status";
}

const char* vksplat_version(void) { return vksplat::kVersion; }

}  // extern "C"
