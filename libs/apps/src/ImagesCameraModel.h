#pragma once

#include <mrpt/core/bits_math.h>
#include <mrpt/core/format.h>
#include <mrpt/img/TCamera.h>
#include <mrpt/typemeta/TEnumType.h>
#include <mrpt_vslam/core/RadialCalibration.h>
#include <mrpt_vslam/core/RunReport.h>

#include <cstdio>
#include <optional>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace mrpt_vslam::apps {

/// The values of the ini key `camera_model`: whether the images' calibration is used.
inline const std::vector<std::pair<std::string, bool>> kCameraModelChoices = {{"auto", true},
                                                                              {"config", false}};

/** Where an app's camera model comes from (ini key `camera_model`, doc/camera-model.md, "From a
 *  camera's calibration"): with `auto`, the calibration the first image carries
 *  (`CObservationImage::cameraParams` with focal lengths) fitted as the app's model, and every
 *  later image must carry the same; with `config`, or images without a calibration (only an
 *  image size, as vslam-sim writes them), the model of [Camera]. `Model` has width, height and
 *  max_theta [rad], the field of view the fit is asked for. */
template <class Model>
class ImagesCameraModel {
  public:
    using TFit = core::TCameraFit<Model>;
    using FitFunction = TFit (*)(const mrpt::img::TCamera&, double);

    /// \param from_images camera_model = auto; \param config [Camera]'s model; \param fit the
    /// app's model fitted to a calibration (core::fitPajdlaBakstein(), fitUnifiedSphere())
    ImagesCameraModel(bool from_images, const Model& config, FitFunction fit)
        : m_fromImages(from_images), m_config(config), m_fitFunction(fit)
    {
    }

    /** The model of an image with `calibration`; the first image decides.
     *  \throw std::runtime_error when its calibration cannot be fitted, or is not the first
     *  image's. */
    const Model& of(const mrpt::img::TCamera& calibration)
    {
        if (m_images) {
            if (!(calibration == m_images->first)) {
                throw std::runtime_error(
                    "its calibration (cameraParams) is not the first image's; set camera_model "
                    "= config to use [Camera] for every image");
            }
            return m_images->second.camera;
        }
        // a calibration has focal lengths; the image size alone is none
        if (!m_fromImages || m_decided || !(calibration.fx() > 0)) {
            m_decided = true;
            return m_config;
        }
        m_decided = true;
        try {
            m_images.emplace(calibration, m_fitFunction(calibration, m_config.max_theta));
        } catch (const std::invalid_argument& e) {
            throw std::runtime_error(
                std::string("its calibration (cameraParams) cannot be used: ") + e.what() +
                "; set camera_model = config to use [Camera]");
        }
        return m_images->second.camera;
    }

    /// The model in use; nullptr before the first image.
    const Model* model() const
    {
        if (m_images) return &m_images->second.camera;
        return m_decided ? &m_config : nullptr;
    }
    /// What a warning tells the user to check: "[Camera]", or "the images' calibration".
    std::string name() const { return m_images ? "the images' calibration" : "[Camera]"; }
    /// The fit, when the images' calibration is the model.
    const TFit* fit() const { return m_images ? &m_images->second : nullptr; }

    /** run.json → results.camera_model: source, the model's `parameters`, size and field of
     *  view; for a fit, the calibration's distortion model and the fit's largest errors. Prints
     *  its line as `app` unless `quiet`. Nothing before the first image.
     *  \return the line, e.g. for a warning on the fit's error */
    std::string report(core::RunReport& report, const std::string& app,
                       const std::string& model_name,
                       const std::vector<std::pair<const char*, double>>& parameters,
                       bool quiet) const
    {
        if (!model()) return {};
        std::string json = std::string("{\"source\": \"") + (m_images ? "images" : "config") + "\"";
        std::string values;
        for (const auto& [key, value] : parameters) {
            json += mrpt::format(", \"%s\": %.17g", key, value);
            values += mrpt::format("%s%s = %.6g", values.empty() ? "" : ", ", key, value);
        }
        json += mrpt::format(", \"max_theta_deg\": %.17g, \"width\": %d, \"height\": %d",
                             mrpt::RAD2DEG(model()->max_theta), model()->width, model()->height);
        std::string line = "camera model from the config ([Camera])";
        if (m_images) {
            const auto& [calibration, fit] = *m_images;
            const std::string distortion =
                mrpt::typemeta::TEnumType<mrpt::img::DistortionModel>::value2name(
                    calibration.distortion);
            json += mrpt::format(
                ", \"calibration\": \"%s\", \"fit_max_error_px\": %.4f, \"fit_max_error_deg\": "
                "%.4f",
                distortion.c_str(), fit.max_error_px, fit.max_error_deg);
            line = mrpt::format(
                "camera model from the images' calibration (%s, fx %.1f px): the %s model %s, "
                "within %.2f px (%.2f deg) up to %.1f deg from the axis",
                distortion.c_str(), calibration.fx(), model_name.c_str(), values.c_str(),
                fit.max_error_px, fit.max_error_deg, mrpt::RAD2DEG(model()->max_theta));
        }
        report.setResultJson("camera_model", json + "}");
        if (!quiet) std::printf("%s: %s\n", app.c_str(), line.c_str());
        return line;
    }

  private:
    bool m_fromImages;
    Model m_config;
    FitFunction m_fitFunction;
    bool m_decided = false;  ///< an image was seen
    std::optional<std::pair<mrpt::img::TCamera, TFit>> m_images;
};

}  // namespace mrpt_vslam::apps
