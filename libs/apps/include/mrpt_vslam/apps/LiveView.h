#pragma once

#include <functional>
#include <memory>
#include <string>

namespace mrpt::opengl {
class COpenGLScene;
}

namespace mrpt_vslam::apps {

/** The `--gui` window of a driver app: an MRPT 3D window whose scene is redrawn after each step.
 *  Usage: `LiveView view("omni-fastslam"); ... view.show([&](auto& scene) { draw(scene); });`
 *  and, once the outputs are written, `view.waitUntilClosed();` unless `--quiet`. */
class LiveView {
  public:
    /// Opens the window. \throw UsageError when there is no display (DISPLAY, WAYLAND_DISPLAY).
    explicit LiveView(const std::string& title);
    ~LiveView();
    LiveView(const LiveView&) = delete;
    LiveView& operator=(const LiveView&) = delete;

    /// Clears the scene, lets `draw` fill it and repaints.
    void show(const std::function<void(mrpt::opengl::COpenGLScene&)>& draw);

    /// At the end of a run: says so on stdout and returns when the user closes the window.
    void waitUntilClosed();

  private:
    struct Impl;
    std::unique_ptr<Impl> m_impl;
};

}  // namespace mrpt_vslam::apps
