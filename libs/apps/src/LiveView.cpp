#include <dlfcn.h>
#include <mrpt_vslam/apps/LiveView.h>
#include <mrpt_vslam/core/UsageError.h>
#include <mrpt_vslam/core/Version.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <thread>

#include "LiveWindow.h"

namespace mrpt_vslam::apps {
namespace {
/// The window module, beside the project's shared libraries (build tree or install).
std::string liveViewModulePath()
{
    const std::string name = "libmrpt_vslam_liveview.so";
    Dl_info info{};
    if (!dladdr(reinterpret_cast<void*>(&core::projectVersion), &info) || !info.dli_fname)
        return name;
    const std::string core_library = info.dli_fname;
    const auto slash = core_library.rfind('/');
    return slash == std::string::npos ? name : core_library.substr(0, slash + 1) + name;
}
}  // namespace

struct LiveView::Impl {
    std::unique_ptr<LiveWindow> window;
};

LiveView::LiveView(const std::string& title) : m_impl(std::make_unique<Impl>())
{
    const auto set = [](const char* variable) {
        const char* value = std::getenv(variable);
        return value && *value;
    };
    if (!set("DISPLAY") && !set("WAYLAND_DISPLAY"))
        throw core::UsageError("--gui needs a display (DISPLAY is not set)");
    const std::string path = liveViewModulePath();
    void* module = dlopen(path.c_str(), RTLD_NOW | RTLD_LOCAL);  // never closed: see ~LiveView
    if (!module) throw core::UsageError(std::string("--gui: ") + dlerror());
    using NewWindow = LiveWindow* (*)(const char*);
    const auto newWindow = reinterpret_cast<NewWindow>(dlsym(module, "mrpt_vslam_new_live_window"));
    if (!newWindow) throw core::UsageError("--gui: " + path + " has no window");
    m_impl->window.reset(newWindow(title.c_str()));
}

LiveView::~LiveView() = default;  // the module stays loaded: MRPT's GUI thread lives in it

void LiveView::show(const std::function<void(mrpt::opengl::COpenGLScene&)>& draw)
{
    m_impl->window->show(draw);
}

void LiveView::waitUntilClosed()
{
    std::printf("The run is complete: close the 3D window to exit.\n");
    std::fflush(stdout);
    while (m_impl->window->isOpen()) std::this_thread::sleep_for(std::chrono::milliseconds(50));
}

}  // namespace mrpt_vslam::apps
