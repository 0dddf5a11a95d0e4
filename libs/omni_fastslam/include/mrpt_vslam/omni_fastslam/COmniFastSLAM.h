#pragma once

#include <mrpt/bayes/CParticleFilter.h>
#include <mrpt/bayes/CParticleFilterCapable.h>
#include <mrpt/bayes/CParticleFilterData.h>
#include <mrpt/config/CLoadableOptions.h>
#include <mrpt/math/TPose2D.h>
#include <mrpt/random/RandomGenerators.h>
#include <mrpt_vslam/core/KLDSampling.h>
#include <mrpt_vslam/core/OdometryGaussian.h>
#include <mrpt_vslam/core/ParallelFor.h>
#include <mrpt_vslam/core/ParticleFilterDataImpl.h>
#include <mrpt_vslam/core/ParticlePath.h>
#include <mrpt_vslam/omni_fastslam/CCeilingLightsMap.h>

#include <map>
#include <memory>
#include <string>
#include <vector>

namespace mrpt_vslam::omni_fastslam {

/** One step of a particle's history: its pose and the step's correspondences c_t (Sec. III-C
 *  level 1): for each measurement associated to a landmark of the particle's map, the
 *  landmark's id and the measurement's hidden_id (−1 where the data gives none). */
struct TOmniFastSLAMStep {
    mrpt::math::TPose2D robot_in_map;
    struct TCorrespondence {
        int64_t landmark_id, hidden_id;
        uint32_t measurement;  ///< index of the measurement in the step's frame
    };
    std::vector<TCorrespondence> correspondences{};
};
using TOmniFastSLAMPath = core::ParticlePath<TOmniFastSLAMStep>;

/** Evaluation only, when the data set gives landmark numbers (TBearingMeasurement::hidden_id):
 *  the numbers of the measurements associated (level 1) to each landmark of a map. A landmark
 *  stands for its most frequent number; every other association to it is wrong. */
struct TAssociationTally {
    /// map landmark id → hidden id → measurements
    std::map<int64_t, std::map<int64_t, uint32_t>> counts;
    /// Level-1 associations of measurements with a hidden id.
    size_t labelled() const;
    /// Associations whose hidden id is not the most frequent one of their landmark.
    size_t wrong() const;
};

/** One FastSLAM particle: the robot pose, its path and its own map of ceiling lights. */
struct TOmniFastSLAMParticle {
    mrpt::math::TPose2D robot_in_map;
    TOmniFastSLAMPath path;
    CCeilingLightsMap map;
    /// Σ of the log-weight increments since the start, kept through resampling: the best
    /// particle is the one with the largest value.
    double accumulated_log_w = 0;
};

/** FastSLAM 2.0 for an omnidirectional camera and ceiling lights (Gamallo, Mucientes &
 *  Regueiro 2013; doc/omni-fastslam.md), on MRPT's particle-filter framework: drive it
 *  with `mrpt::bayes::CParticleFilter::executeOn()`; `pfOptimalProposal` runs the FastSLAM 2.0
 *  proposal below, `pfStandardProposal` samples the motion model only (FastSLAM 1.0).
 *
 *  One step, for every particle k (pfOptimalProposal):
 *   1. predicted pose x̂_t = x_{t-1} ⊕ Δ and its covariance R_t from the odometry action;
 *   2. Alg. 2: per landmark j and measurement l, the proposal Σ_{x,j,l}, μ_{x,j,l} and the
 *      association likelihood φ_{l,j} = N(z_l; h(μ_j, μ_{x,j,l}), Q_{j,l});
 *   3. Sec. III-C level 1: Hungarian assignment of measurements to landmarks (or ML);
 *   4. Alg. 3: fuse the associated type-I landmarks in order of increasing covariance (ties:
 *      lower φ) into N(μ_xt, Σ_xt) and sample x_t from it; sample the motion model when none;
 *   5. Alg. 4: EKF updates of the landmarks and the weight; Sec. III-C level 2 and
 *      updateCandidateLandmarks(); updateLandmarksType().
 *  Resampling (low variance = `prSystematic`) is done by CParticleFilter when ESS < BETA; with
 *  its `adaptiveSampleSize` set, by KLD-sampling here instead (kld), at the start of the step
 *  after the one whose ESS fell below BETA, to the number of particles the spread asks for.
 */
class COmniFastSLAM
    : public mrpt::bayes::CParticleFilterData<TOmniFastSLAMParticle,
                                              mrpt::bayes::particle_storage_mode::POINTER>,
      public core::ParticleFilterDataImpl<
          COmniFastSLAM,
          mrpt::bayes::CParticleFilterData<
              TOmniFastSLAMParticle, mrpt::bayes::particle_storage_mode::POINTER>::CParticleList> {
  public:
    struct TOptions : public mrpt::config::CLoadableOptions {
        /// Label of the bearings observation in each sensory frame.
        std::string bearings_label = "OMNICAM_BEARINGS";
        /// Added to the odometry covariance (ini: min_motion_std_xy [m],
        /// min_motion_std_phi_deg).
        core::TMotionNoiseFloor motion_noise_floor{0.005, 0.25 * M_PI / 180};
        /// Landmarks whose predicted θ exceeds the perceptual range by more than this are
        /// skipped in Alg. 2 (they cannot have produced a measurement).
        double prediction_margin = 5.0 * M_PI / 180;  ///< [rad] (ini: prediction_margin_deg)
        /// A frame with more bearings is refused (the association's cost grows with their
        /// cube; a ceiling camera sees tens of lights).
        unsigned int max_bearings_per_frame = 200;

        void loadFromConfigFile(const mrpt::config::CConfigFileBase& cfg,
                                const std::string& section) override;
        void saveToConfigFile(mrpt::config::CConfigFileBase& cfg,
                              const std::string& section) const override;
    } options;

    /// KLD-sampling (Fox 2003) when CParticleFilter's adaptiveSampleSize is set (ini section
    /// KLD_options, MRPT's keys).
    core::TKLDParams kld;

    /// Per-step counters of the last executed step (all particles).
    struct TStepStats {
        size_t measurements = 0;
        size_t associated_to_landmarks = 0;  ///< summed over particles
        size_t motion_only_samples = 0;      ///< particles that sampled the motion model
    } lastStepStats;

    /** \param map_template options (and possibly a prior map) every particle starts with
     *  \param particle_count M \param seed of the filter's own random generator */
    COmniFastSLAM(const CCeilingLightsMap& map_template, size_t particle_count, uint32_t seed);

    /// All particles at `robot_in_map`, equal weights, maps = the template.
    void reset(const mrpt::math::TPose2D& robot_in_map, double timestamp);

    /** What a run is made of, step by step (for smoothing after the run, LightsPathSmoother):
     *  told on reset() and at each step, before the particles are updated. */
    struct TStepObserver {
        virtual ~TStepObserver() = default;
        virtual void onReset(const mrpt::math::TPose2D& robot_in_map, double timestamp) = 0;
        /// The step's odometry Gaussian and measurements; path step k follows the k-th call.
        virtual void onStep(const core::TOdometryGaussian& motion,
                            const std::vector<TBearingMeasurement>& z) = 0;
    };
    /// Tells `observer` (nullptr: none) of every reset and step; it must outlive the filter's use.
    void setStepObserver(TStepObserver* observer) { m_observer = observer; }

    /// A particle's path, oldest first: (timestamp, pose).
    static std::vector<std::pair<double, mrpt::math::TPose2D>> pathOf(
        const TOmniFastSLAMParticle& p);
    /// The level-1 associations along a particle's path, by landmark and hidden id.
    static TAssociationTally associationsOf(const TOmniFastSLAMParticle& p);

  protected:
    void prediction_and_update_pfStandardProposal(
        const mrpt::obs::CActionCollection* action, const mrpt::obs::CSensoryFrame* observation,
        const mrpt::bayes::CParticleFilter::TParticleFilterOptions& pf_options) override;
    void prediction_and_update_pfOptimalProposal(
        const mrpt::obs::CActionCollection* action, const mrpt::obs::CSensoryFrame* observation,
        const mrpt::bayes::CParticleFilter::TParticleFilterOptions& pf_options) override;

  private:
    std::vector<TBearingMeasurement> measurementsFromFrame(const mrpt::obs::CSensoryFrame* sf,
                                                           const CCeilingLightsMap& map,
                                                           double& timestamp) const;
    /// A sample of the motion model from `from`, with `noise` ~ N(0, I₃) drawn before.
    static mrpt::math::TPose2D sampleMotion(const mrpt::math::TPose2D& from,
                                            const core::TOdometryGaussian& motion,
                                            const Eigen::Vector3d& noise);
    /// Steps 2-4 for one particle, with R_t of step 1 and `noise` ~ N(0, I₃) drawn before:
    /// returns the sampled pose and the level-1 association.
    mrpt::math::TPose2D sampleFastSLAM2Proposal(const TOmniFastSLAMParticle& p,
                                                const std::vector<TBearingMeasurement>& z,
                                                const core::TOdometryGaussian& motion,
                                                const Eigen::Matrix3d& R,
                                                const Eigen::Vector3d& noise,
                                                std::vector<int>& landmark_of_measurement) const;
    /// Step 5 and the path bookkeeping, shared by both proposals: returns the log-weight.
    double updateParticle(TOmniFastSLAMParticle& p, const mrpt::math::TPose2D& x_t,
                          double timestamp, const std::vector<TBearingMeasurement>& z,
                          const std::vector<int>& landmark_of_measurement,
                          const Eigen::Matrix3d& R_t);
    void runStep(const mrpt::obs::CActionCollection* action, const mrpt::obs::CSensoryFrame* sf,
                 bool fastslam2, const mrpt::bayes::CParticleFilter::TParticleFilterOptions& pf);

    mrpt::random::CRandomGenerator m_rng;
    std::vector<Eigen::Vector3d> m_noise;  ///< the step's normal draws, one per particle
    TStepObserver* m_observer = nullptr;
};

}  // namespace mrpt_vslam::omni_fastslam
