#include <mrpt/gui/CDisplayWindow3D.h>
#include <mrpt_vslam/apps/LiveView.h>
#include <mrpt_vslam/core/UsageError.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <thread>

namespace mrpt_vslam::apps {

struct LiveView::Impl {
    mrpt::gui::CDisplayWindow3D::Ptr window;
};

LiveView::LiveView(const std::string& title) : m_impl(std::make_unique<Impl>())
{
    if (!std::getenv("DISPLAY") && !std::getenv("WAYLAND_DISPLAY"))
        throw core::UsageError("--gui needs a display (DISPLAY is not set)");
    m_impl->window = mrpt::gui::CDisplayWindow3D::Create(title, 1000, 700);
}

LiveView::~LiveView() = default;

void LiveView::show(const std::function<void(mrpt::opengl::COpenGLScene&)>& draw)
{
    auto& scene = m_impl->window->get3DSceneAndLock();
    scene->clear();
    draw(*scene);
    m_impl->window->unlockAccess3DScene();
    m_impl->window->forceRepaint();
}

void LiveView::waitUntilClosed()
{
    std::printf("The run is complete: close the 3D window to exit.\n");
    std::fflush(stdout);
    while (m_impl->window->isOpen()) std::this_thread::sleep_for(std::chrono::milliseconds(50));
}

}  // namespace mrpt_vslam::apps
