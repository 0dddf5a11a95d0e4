#pragma once

#include <functional>

namespace mrpt::opengl {
class COpenGLScene;
}

namespace mrpt_vslam::apps {

/** The window behind LiveView. Its implementation (an MRPT 3D window) lives in the module
 *  libmrpt_vslam_liveview.so, which LiveView loads only for `--gui`: mrpt-gui and the GUI
 *  toolkits under it would otherwise be loaded at every app's start-up. */
class LiveWindow {
  public:
    virtual ~LiveWindow() = default;
    virtual void show(const std::function<void(mrpt::opengl::COpenGLScene&)>& draw) = 0;
    virtual bool isOpen() const = 0;
};

}  // namespace mrpt_vslam::apps

/// The module's one entry point: a new window titled `title` (the caller deletes it).
extern "C" mrpt_vslam::apps::LiveWindow* mrpt_vslam_new_live_window(const char* title);
