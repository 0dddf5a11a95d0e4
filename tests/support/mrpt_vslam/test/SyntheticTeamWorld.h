#pragma once

#include <mrpt/bayes/CParticleFilter.h>
#include <mrpt/maps/CLandmarksMap.h>
#include <mrpt/math/wrap2pi.h>
#include <mrpt/obs/CActionCollection.h>
#include <mrpt/obs/CActionRobotMovement2D.h>
#include <mrpt/obs/CObservationVisualLandmarks.h>
#include <mrpt/obs/CSensoryFrame.h>
#include <mrpt/poses/CPose2D.h>
#include <mrpt/poses/CPose3D.h>
#include <mrpt/random/RandomGenerators.h>
#include <mrpt_vslam/multirobot/StereoGeometry.h>

#include <Eigen/Cholesky>
#include <array>
#include <cmath>
#include <string>
#include <vector>

namespace mrpt_vslam::test {

/** An odometry reading of the true increment `delta`: delta plus Gaussian noise of MRPT's
 *  motion model `model` (the covariance CActionRobotMovement2D gives it). */
inline mrpt::poses::CPose2D noisyOdometry(
    const mrpt::poses::CPose2D& delta,
    const mrpt::obs::CActionRobotMovement2D::TMotionModelOptions& model,
    mrpt::random::CRandomGenerator& rng)
{
    mrpt::obs::CActionRobotMovement2D probe;
    probe.computeFromOdometry(delta, model);
    mrpt::math::CMatrixDouble33 cov;
    mrpt::poses::CPose2D mean;
    probe.poseChange->getCovarianceAndMean(cov, mean);
    const Eigen::Matrix3d L = cov.asEigen().llt().matrixL();
    const Eigen::Vector3d e =
        L * Eigen::Vector3d(rng.drawGaussian1D_normalized(), rng.drawGaussian1D_normalized(),
                            rng.drawGaussian1D_normalized());
    return {mean.x() + e[0], mean.y() + e[1], mean.phi() + e[2]};
}

/** A synthetic world for the multi-robot filter's tests and benchmarks: landmarks with random
 *  unit descriptors on the walls of a room, K robots driving circles in it with a forward
 *  stereo head, noisy odometry (MRPT's Gaussian model), and measurements produced as the
 *  front-end does: project to (r, c, d), add pixel noise, triangulate (Eq. 12), R_t from
 *  StereoGeometry with the paper's σ, descriptor plus noise. Deterministic for a seed. */
class SyntheticTeamWorld {
  public:
    struct TParams {
        size_t robots = 2;
        size_t landmarks = 600;
        double half_x = 8.5, half_y = 4.0;  ///< room [m]
        double circle_radius = 2.2;         ///< [m] robots' paths
        double step_length = 0.2;           ///< [m] per step
        double pixel_noise = 0.3;           ///< [px] true noise on r, c and d
        double descriptor_noise = 0.03;     ///< per component, before re-normalisation
        double max_depth = 5.0;             ///< [m]
        double odometry_noise = 0.06;       ///< a1 = a4 of MRPT's Gaussian model
        uint32_t seed = 1;
    };

    explicit SyntheticTeamWorld(const TParams& p)
        : params(p),
          geometry(280, 280, 160, 120, 0.12),
          camera_on_robot(0.1, 0, 0.5, -M_PI / 2, 0, -M_PI / 2)  // z forward along robot x
    {
        rng.randomize(p.seed);
        for (size_t i = 0; i < p.landmarks; i++) {
            // on one of the four walls, 0.2-2.3 m high
            const int wall = static_cast<int>(rng.drawUniform(0, 4)) % 4;
            const double u = rng.drawUniform(-1, 1), z = rng.drawUniform(0.2, 2.3);
            Eigen::Vector3d pt;
            if (wall == 0)
                pt = {u * p.half_x, p.half_y, z};
            else if (wall == 1)
                pt = {u * p.half_x, -p.half_y, z};
            else if (wall == 2)
                pt = {p.half_x, u * p.half_y, z};
            else
                pt = {-p.half_x, u * p.half_y, z};
            points.push_back(pt);
            descriptors.push_back(randomUnitDescriptor());
        }
        for (size_t k = 0; k < p.robots; k++) {
            // circles centred along x, R1 around (2.2, 0) starting at the origin heading +y...
            const double cx = (k == 0 ? 0.0 : (k == 1 ? -4.0 : 4.0)) + p.circle_radius;
            centres.push_back({cx, 0});
            truth.push_back({cx - p.circle_radius, 0, M_PI / 2});
            odometry.push_back(truth.back());
        }
        model.modelSelection = mrpt::obs::CActionRobotMovement2D::mmGaussian;
        model.gaussianModel.a1 = p.odometry_noise;
        model.gaussianModel.a2 = 0.005;
        model.gaussianModel.a3 = 0.005;
        model.gaussianModel.a4 = p.odometry_noise;
        model.gaussianModel.minStdXY = 0.005;
        model.gaussianModel.minStdPHI = 0.5 * M_PI / 180;
    }

    /// The world point whose descriptor is nearest to `d` (identifies a landmark).
    size_t pointOfDescriptor(const std::array<float, 64>& d) const
    {
        size_t best = 0;
        double best_e = 1e9;
        for (size_t i = 0; i < descriptors.size(); i++) {
            double e = 0;
            for (size_t j = 0; j < 64; j++) e += std::pow(d[j] - descriptors[i][j], 2);
            if (e < best_e) best_e = e, best = i;
        }
        return best;
    }

    /// Start poses (ground truth at step 0).
    std::vector<mrpt::math::TPose2D> startPoses() const
    {
        std::vector<mrpt::math::TPose2D> s;
        for (size_t k = 0; k < params.robots; k++)
            s.push_back({centres[k][0] - params.circle_radius, 0, M_PI / 2});
        return s;
    }

    /// Moves every robot one step; fills the odometry actions (robot order) and measurements.
    void step(mrpt::obs::CActionCollection& actions, mrpt::obs::CSensoryFrame& frame)
    {
        actions.clear();
        frame.clear();
        time += 1.0;
        const auto stamp = mrpt::Clock::fromDouble(time);
        for (size_t k = 0; k < params.robots; k++) {
            // counter-clockwise circle: constant increment (step, 0, step / radius)
            const mrpt::poses::CPose2D delta(params.step_length, 0,
                                             params.step_length / params.circle_radius);
            const auto before = mrpt::poses::CPose2D(truth[k]);
            truth[k] = (before + delta).asTPose();
            const mrpt::poses::CPose2D noisy = noisyOdometry(delta, model, rng);
            mrpt::obs::CActionRobotMovement2D act;
            act.timestamp = stamp;
            act.computeFromOdometry(noisy, model);
            actions.insert(act);
            odometry[k] = (mrpt::poses::CPose2D(odometry[k]) + noisy).asTPose();
            frame.insert(observe(k, stamp));
        }
    }

    mrpt::obs::CObservationVisualLandmarks::Ptr observe(size_t k, mrpt::Clock::time_point stamp)
    {
        auto obs = mrpt::obs::CObservationVisualLandmarks::Create();
        obs->sensorLabel = "R" + std::to_string(k + 1) + "_LANDMARKS";
        obs->timestamp = stamp;
        obs->refCameraPose = camera_on_robot;
        const mrpt::poses::CPose3D cam =
            mrpt::poses::CPose3D(mrpt::poses::CPose2D(truth[k])) + camera_on_robot;
        const auto paper_noise = multirobot::TStereoPixelNoise::paper();
        for (size_t i = 0; i < points.size(); i++) {
            const auto pc = cam.inverseComposePoint(
                mrpt::math::TPoint3D(points[i].x(), points[i].y(), points[i].z()));
            if (pc.z < 0.5 || pc.z > params.max_depth) continue;
            auto px = geometry.project(pc);
            if (px.col < 0 || px.col >= 320 || px.row < 0 || px.row >= 240 || px.disparity < 1)
                continue;
            px.row += params.pixel_noise * rng.drawGaussian1D_normalized();
            px.col += params.pixel_noise * rng.drawGaussian1D_normalized();
            px.disparity += params.pixel_noise * rng.drawGaussian1D_normalized();
            if (px.disparity < 0.5) continue;
            mrpt::maps::CLandmark lm;
            lm.ID = static_cast<int64_t>(i);
            lm.pose_mean = geometry.triangulate(px);
            const auto R = geometry.covariance(px, paper_noise);
            lm.pose_cov_11 = static_cast<float>(R(0, 0));
            lm.pose_cov_12 = static_cast<float>(R(0, 1));
            lm.pose_cov_13 = static_cast<float>(R(0, 2));
            lm.pose_cov_22 = static_cast<float>(R(1, 1));
            lm.pose_cov_23 = static_cast<float>(R(1, 2));
            lm.pose_cov_33 = static_cast<float>(R(2, 2));
            mrpt::vision::CFeature f;
            f.x2[0] = f.x2[1] = f.y2[0] = f.y2[1] = 0;  // left uninitialized by MRPT
            std::vector<float> d(descriptors[i].begin(), descriptors[i].end());
            double norm = 0;
            for (auto& v : d) {
                v += static_cast<float>(params.descriptor_noise * rng.drawGaussian1D_normalized());
                norm += v * v;
            }
            for (auto& v : d) v = static_cast<float>(v / std::sqrt(norm));
            f.descriptors.SURF = d;
            lm.features.push_back(f);
            obs->landmarks.landmarks.push_back(lm);
        }
        return obs;
    }

    TParams params;
    multirobot::StereoGeometry geometry;
    mrpt::poses::CPose3D camera_on_robot;
    mrpt::obs::CActionRobotMovement2D::TMotionModelOptions model;
    mrpt::random::CRandomGenerator rng;
    std::vector<Eigen::Vector3d> points;
    std::vector<std::array<float, 64>> descriptors;
    std::vector<std::array<double, 2>> centres;
    std::vector<mrpt::math::TPose2D> truth, odometry;
    double time = 1000;

  private:
    std::array<float, 64> randomUnitDescriptor()
    {
        std::array<float, 64> d;
        double norm = 0;
        for (auto& v : d) {
            v = static_cast<float>(rng.drawGaussian1D_normalized());
            norm += v * v;
        }
        for (auto& v : d) v = static_cast<float>(v / std::sqrt(norm));
        return d;
    }
};

/// MRPT's particle filter as Gil et al. (2010) run it: standard proposal, systematic resampling
/// when N_eff < 0.5 M (Alg. 1 line 13).
inline mrpt::bayes::CParticleFilter standardFilter()
{
    mrpt::bayes::CParticleFilter pf;
    pf.m_options.PF_algorithm = mrpt::bayes::CParticleFilter::pfStandardProposal;
    pf.m_options.resamplingMethod = mrpt::bayes::CParticleFilter::prSystematic;
    pf.m_options.BETA = 0.5;
    pf.setVerbosityLevel(mrpt::system::LVL_ERROR);
    return pf;
}

/// Distance between the positions of two poses [m].
inline double positionError(const mrpt::math::TPose2D& a, const mrpt::math::TPose2D& b)
{
    return std::hypot(a.x - b.x, a.y - b.y);
}

}  // namespace mrpt_vslam::test
