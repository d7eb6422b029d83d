#pragma once
// Every function of the C API runs its body through guarded(): whatever the C++ library throws
// becomes a status and a message in the caller's vksplat_error, so no exception crosses the C
// boundary, and the message lives with the call, not in any global.
#include <stdexcept>
#include <string>
#include <string_view>

#include "vksplat/vksplat.h"

namespace vksplat::capi {

// Writes `message` into the caller's error (when there is one), cut to fit.
void set_message(vksplat_error* error, std::string_view message);

// The status and message of the exception being handled. std::invalid_argument, the caller's
// misuse (a NULL handle, a buffer too small), is prefixed with `function`; the library's own
// errors already name the file or thing at fault.
vksplat_status report_current_exception(const char* function, vksplat_error* error) noexcept;

template <typename Body>
vksplat_status guarded(const char* function, vksplat_error* error, Body&& body) noexcept {
    try {
        body();
        set_message(error, "");
        return VKSPLAT_OK;
    } catch (...) {
        return report_current_exception(function, error);
    }
}

// *pointer, or std::invalid_argument "<what> is NULL".
template <typename T>
T& require(T* pointer, const char* what) {
    if (!pointer) throw std::invalid_argument(std::string(what) + " is NULL");
    return *pointer;
}

// Clears the caller's out-pointer first, so that a failed call leaves NULL in it.
template <typename T>
T*& out_pointer(T** out, const char* what) {
    T*& slot = require(out, what);
    slot = nullptr;
    return slot;
}

}  // namespace vksplat::capi
