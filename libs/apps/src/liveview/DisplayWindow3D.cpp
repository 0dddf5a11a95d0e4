// The module libmrpt_vslam_liveview.so: LiveWindow as an MRPT 3D window (see LiveWindow.h).
#include <mrpt/gui/CDisplayWindow3D.h>

#include "../LiveWindow.h"

namespace mrpt_vslam::apps {
namespace {

class DisplayWindow3D : public LiveWindow {
  public:
    explicit DisplayWindow3D(const char* title)
        : m_window(mrpt::gui::CDisplayWindow3D::Create(title, 1000, 700))
    {
    }
    void show(const std::function<void(mrpt::opengl::COpenGLScene&)>& draw) override
    {
        auto& scene = m_window->get3DSceneAndLock();
        scene->clear();
        draw(*scene);
        m_window->unlockAccess3DScene();
        m_window->forceRepaint();
    }
    bool isOpen() const override { return m_window->isOpen(); }

  private:
    mrpt::gui::CDisplayWindow3D::Ptr m_window;
};

}  // namespace
}  // namespace mrpt_vslam::apps

extern "C" mrpt_vslam::apps::LiveWindow* mrpt_vslam_new_live_window(const char* title)
{
    return new mrpt_vslam::apps::DisplayWindow3D(title);
}
