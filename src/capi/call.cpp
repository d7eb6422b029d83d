#include "capi/call.hpp"

#include <algorithm>
#include <cstring>
#include <filesystem>
#include <new>

#include "vksplat/error.hpp"

namespace vksplat::capi {

void set_message(vksplat_error* error, std::string_view message) {
    if (!error) return;
    const size_t length = std::min(message.size(), sizeof error->message - 1);
    std::memcpy(error->message, message.data(), length);
    error->message[length] = '\0';
}

vksplat_status report_current_exception(const char* function, vksplat_error* error) noexcept {
    // Building a message can itself run out of memory: then the status alone goes back.
    try {
        try {
            throw;
        } catch (const InputError& e) {
            set_message(error, e.what());
            return VKSPLAT_INVALID_INPUT;
        } catch (const std::filesystem::filesystem_error& e) {
            set_message(error, e.what());  // names the path
            return VKSPLAT_INVALID_INPUT;
        } catch (const GpuError& e) {
            set_message(error, e.what());
            return VKSPLAT_GPU_ERROR;
        } catch (const std::invalid_argument& e) {
            set_message(error, std::string(function) + ": " + e.what());
            return VKSPLAT_INVALID_ARGUMENT;
        } catch (const std::bad_alloc&) {
            set_message(error, std::string(function) + ": out of host memory");
            return VKSPLAT_OUT_OF_MEMORY;
        } catch (const std::exception& e) {
            set_message(error, std::string(function) + ": " + e.what());
            return VKSPLAT_INTERNAL_ERROR;
        } catch (...) {
            set_message(error, std::string(function) + ": an exception of unknown type");
            return VKSPLAT_INTERNAL_ERROR;
        }
    } catch (...) {
        set_message(error, "");
        return VKSPLAT_OUT_OF_MEMORY;
    }
}

}  // namespace vksplat::capi
