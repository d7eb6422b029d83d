// vksplat_context: a gpu::Context of vksplat's own or over the application's device.
#include <cstring>
#include <memory>

#include "capi/call.hpp"
#include "capi/handles.hpp"

using vksplat::capi::guarded;
using vksplat::capi::out_pointer;
using vksplat::capi::require;

extern "C" {

vksplat_status vksplat_context_create(const vksplat_context_options* options, vksplat_context** context,
                                      vksplat_error* error) {
    return guarded(__func__, error, [&] {
        vksplat_context*& out = out_pointer(context, "context");
        vksplat::gpu::ContextOptions cpp;
        if (options) {
            if (options->device) cpp.device = options->device;
            cpp.validation = options->validation != 0;
            cpp.memory_budget = options->memory_budget;
        }
        out = new vksplat_context(cpp);
    });
}

vksplat_status vksplat_context_adopt(const vksplat_adopted_device* device, vksplat_context** context,
                                     vksplat_error* error) {
    return guarded(__func__, error, [&] {
        vksplat_context*& out = out_pointer(context, "context");
        const vksplat_adopted_device& lent = require(device, "device");
        vksplat::gpu::AdoptedDevice cpp;
        cpp.instance = lent.instance;
        cpp.physical_device = lent.physical_device;
        cpp.device = lent.device;
        cpp.queue_family = lent.queue_family;
        cpp.queue = lent.queue;
        cpp.get_instance_proc_addr = lent.get_instance_proc_addr;
        cpp.int64_atomics_enabled = lent.int64_atomics_enabled != 0;
        cpp.float_atomics_enabled = lent.float_atomics_enabled != 0;
        out = new vksplat_context(cpp);
    });
}

vksplat_status vksplat_context_device_name(const vksplat_context* context, char* name, size_t size,
                                           vksplat_error* error) {
    return guarded(__func__, error, [&] {
        const std::string& device = require(context, "context").context.info().name;
        char& first = require(name, "name");
        if (size == 0) throw std::invalid_argument("size is 0: no room for the name's terminating NUL");
        const size_t length = std::min(device.size(), size - 1);
        std::memcpy(&first, device.data(), length);
        name[length] = '\0';
    });
}

void vksplat_context_destroy(vksplat_context* context) { delete context; }

}  // extern "C"
