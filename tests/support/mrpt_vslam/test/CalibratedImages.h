#pragma once

// Images that carry a camera calibration, for the apps' tests of their camera model.
#include <gtest/gtest.h>
#include <mrpt/img/TCamera.h>
#include <mrpt/obs/CObservationImage.h>
#include <mrpt_vslam/test/RewrittenRawlog.h>
#include <mrpt_vslam/test/RunCommand.h>
#include <mrpt_vslam/test/RunFiles.h>

#include <Eigen/Dense>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <string>

namespace mrpt_vslam::test {

/** The Kannala-Brandt calibration of a radial camera whose radius at θ from the axis is
 *  `radius(θ)` [px], as a camera calibration would give it: f and f·k1..f·k4 by linear least
 *  squares on r(θ) = f (θ + k1 θ³ + k2 θ⁵ + k3 θ⁷ + k4 θ⁹) up to `max_theta` [rad]; square
 *  pixels, principal point (cx, cy). */
inline mrpt::img::TCamera kannalaBrandtCalibration(const std::function<double(double)>& radius,
                                                   double max_theta, uint32_t width,
                                                   uint32_t height, double cx, double cy)
{
    constexpr int kSamples = 200;
    Eigen::MatrixXd powers(kSamples, 5);
    Eigen::VectorXd r(kSamples);
    for (int i = 0; i < kSamples; i++) {
        const double theta = max_theta * (i + 1) / kSamples;
        for (int k = 0; k < 5; k++) powers(i, k) = std::pow(theta, 2 * k + 1);
        r[i] = radius(theta);
    }
    const Eigen::VectorXd fk = powers.colPivHouseholderQr().solve(r);
    mrpt::img::TCamera camera;
    camera.ncols = width;
    camera.nrows = height;
    camera.setIntrinsicParamsFromValues(fk[0], fk[0], cx, cy);
    camera.setDistortionKannalaBrandt(fk[1] / fk[0], fk[2] / fk[0], fk[3] / fk[0], fk[4] / fk[0]);
    return camera;
}

/** `source` with its images only, each carrying `calibration` as its `cameraParams`, as a camera
 *  driver records them (rewriteRawlog(): format #1, labels emptied); `change(k, c)` may alter
 *  the k-th image's. */
inline void rewriteImagesWithCalibration(
    const std::string& source, const std::string& rawlog, const mrpt::img::TCamera& calibration,
    const std::function<void(size_t, mrpt::img::TCamera&)>& change = {})
{
    size_t image = 0;
    rewriteRawlog(source, rawlog, false, true, [&](mrpt::obs::CObservation& o) {
        auto* img = dynamic_cast<mrpt::obs::CObservationImage*>(&o);
        if (!img) return false;
        img->cameraParams = calibration;
        if (change) change(image, img->cameraParams);
        image++;
        return true;
    });
}

/** Expects the run into `out` (`r`: its command's result) stopped at frame `frame`, whose image
 *  carries a calibration other than the first image's: a non-zero exit naming the frame and
 *  the cause, and no run.json marked completed. */
inline void expectStoppedByChangedCalibration(const TCommandResult& r, const std::string& out,
                                              size_t frame)
{
    EXPECT_NE(r.exit_code, 0);
    EXPECT_NE(r.out.find("frame " + std::to_string(frame) + ":"), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("is not the first image's"), std::string::npos) << r.out;
    EXPECT_FALSE(std::filesystem::exists(out + "/run.json") &&
                 readJson(out + "/run.json")["completed"].get<bool>());
}

}  // namespace mrpt_vslam::test
