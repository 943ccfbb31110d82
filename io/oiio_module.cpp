#include "io/oiio_module.h"

#include <dlfcn.h>

#include <cstdlib>
#include <filesystem>
#include <mutex>
#include <vector>

#include "io/io_errors.h"

namespace ssrt::io_detail {

namespace {

namespace fs = std::filesystem;

// Where the module may be, in the order tried.
std::vector<fs::path> candidates() {
    if (const char* path = std::getenv("SSRT_OIIO_MODULE"); path && *path) return {path};
    std::vector<fs::path> out;
    std::error_code ec;
    const fs::path program = fs::read_symlink("/proc/self/exe", ec);
    if (!ec) {
        out.push_back(program.parent_path() / kOiioModuleFile);
        out.push_back(program.parent_path() / ".." / SSRT_INSTALL_LIBDIR / "ssrt" /
                      kOiioModuleFile);
    }
    out.push_back(fs::path(SSRT_OIIO_MODULE_BUILD_DIR) / kOiioModuleFile);
    return out;
}

// Loads the first candidate that exists; the module stays loaded for the process's life.
const OiioModule* load(std::string& error) {
    std::string tried;
    for (const fs::path& path : candidates()) {
        std::error_code ec;
        if (!fs::exists(path, ec)) {
            tried += (tried.empty() ? "" : ", ") + path.lexically_normal().string();
            continue;
        }
        void* handle = ::dlopen(path.c_str(), RTLD_NOW | RTLD_LOCAL);
        if (!handle) {
            error = "cannot load OpenImageIO's module " + path.string() + ": " + ::dlerror();
            return nullptr;
        }
        using Entry = const OiioModule* (*)();
        const auto entry = reinterpret_cast<Entry>(::dlsym(handle, kOiioModuleEntry));
        if (!entry) {
            error = path.string() + " is not ssrt's OpenImageIO module";
            return nullptr;
        }
        return entry();
    }
    error = std::string("this format needs OpenImageIO, through ssrt's module ") + kOiioModuleFile +
            ", which is not installed (looked for " + tried + ")";
    return nullptr;
}

}  // namespace

const OiioModule& oiioModule() {
    static std::once_flag once;
    static const OiioModule* module = nullptr;
    static std::string error;
    std::call_once(once, [] { module = load(error); });
    if (!module) failDecode(error);
    return *module;
}

}  // namespace ssrt::io_detail
