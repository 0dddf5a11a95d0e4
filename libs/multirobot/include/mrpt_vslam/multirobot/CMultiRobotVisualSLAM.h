#pragma once

#include <mrpt/bayes/CParticleFilter.h>
#include <mrpt/bayes/CParticleFilterCapable.h>
#include <mrpt/bayes/CParticleFilterData.h>
#include <mrpt/config/CLoadableOptions.h>
#include <mrpt/obs/CActionRobotMovement2D.h>
#include <mrpt/random/RandomGenerators.h>
#include <mrpt_vslam/core/ParticleFilterDataImpl.h>
#include <mrpt_vslam/multirobot/TeamParticle.h>

#include <string>
#include <utility>
#include <vector>

namespace mrpt_vslam::multirobot {

/** The Rao-Blackwellized particle filter of Gil et al. (paper 003, Alg. 1; doc/multirobot.md)
 *  over the joint paths of K robots and one shared map of 3D visual landmarks, on MRPT's
 *  particle-filter framework: drive it with `mrpt::bayes::CParticleFilter::executeOn()` and
 *  `pfStandardProposal`; resampling happens there when N_eff < BETA (Alg. 1 line 13).
 *
 *  Input of one step: an action collection with one `CActionRobotMovement2D` per robot, in the
 *  order of options.robots, and a sensory frame with each robot's `<ROBOT>_LANDMARKS`
 *  (`CObservationVisualLandmarks`; a robot may have none). Robot by robot (lines 7-9):
 *   1. sample each particle's pose of that robot from the odometry's Gaussian (Sec. 3.1);
 *   2. keep its B nearest measurements (Sec. 6.2) and, for each one, search the shared pool
 *      for candidates once (E ≤ E0 near the point, radius widened by the particles' spread);
 *   3. particle by particle (its landmarks stay in the cache), fuse the measurements one
 *      after the other (CVisualLandmarksMap::fuse(): D0 gate, min E, EKF or new landmark) and
 *      multiply its weight by ω (Eq. 13) or p0; the weights of the K robots multiply (line 11).
 *      The candidates are searched before the frame is fused, so two points of one frame never
 *      become one landmark;
 *   4. with `resample_per_robot` (ours), resample when N_eff < BETA before the next robot's
 *      motion is sampled. The robots' motions are independent, so this is the same posterior
 *      processed one robot at a time; it keeps the particles from having to be good for all
 *      K robots at once, which the joint product over a 3K-dimensional proposal rarely is.
 *  The best particle is the one with the largest Σ_t log ω_t (Eq. 14). */
class CMultiRobotVisualSLAM
    : public mrpt::bayes::CParticleFilterData<TTeamParticle,
                                              mrpt::bayes::particle_storage_mode::POINTER>,
      public core::ParticleFilterDataImpl<
          CMultiRobotVisualSLAM,
          mrpt::bayes::CParticleFilterData<
              TTeamParticle, mrpt::bayes::particle_storage_mode::POINTER>::CParticleList> {
public:
    struct TOptions : public mrpt::config::CLoadableOptions {
        /// Robot names, the prefix of their sensor labels (ini: `robots = R1 R2`).
        std::vector<std::string> robots{"R1", "R2"};
        /// Suffix of the landmark observations' labels: `<ROBOT>` + this.
        std::string landmarks_suffix = "_LANDMARKS";
        /// B: measurements integrated per robot and step (paper: 8 online, 20 offline).
        unsigned int max_observations_per_robot = 8;
        /// Added to the odometry covariance (std) so the proposal never degenerates.
        double min_motion_std_xy = 0.002;               ///< [m]
        double min_motion_std_phi = 0.1 * M_PI / 180;   ///< [rad] (ini: min_motion_std_phi_deg)
        /// Spread of the initial poses of every robot but the first, whose start defines the
        /// map frame (Sec. 6.1: "the initial position ... is known approximately").
        double initial_std_xy = 0.05;                   ///< [m]
        double initial_std_phi = 1.0 * M_PI / 180;      ///< [rad] (ini: initial_std_phi_deg)
        /// Resample (if N_eff < BETA) after each robot's measurements too (ours; paper: once
        /// per step). Pays off with 3 robots (doc/multirobot.md).
        bool resample_per_robot = false;

        void loadFromConfigFile(const mrpt::config::CConfigFileBase& cfg,
                                const std::string& section) override;
        void saveToConfigFile(mrpt::config::CConfigFileBase& cfg,
                              const std::string& section) const override;
    } options;

    /// Counters of the last step (summed over particles where marked).
    struct TStepStats {
        size_t measurements = 0;          ///< integrated (after the B limit), all robots
        size_t candidates = 0;            ///< pool candidates, summed over measurements
        size_t created = 0;               ///< new landmarks, summed over particles
        size_t associated = 0;            ///< EKF updates, summed over particles
    } lastStepStats;

    /** \param map_template options every particle's map starts with (must be empty)
     *  \param particle_count M \param seed of the filter's own random generator */
    CMultiRobotVisualSLAM(const CVisualLandmarksMap& map_template, size_t particle_count,
                          uint32_t seed);

    /** All particles at the start poses (one per robot), the first robot's exactly, the others
     *  drawn around theirs with options.initial_std_*; equal weights; empty maps. */
    void reset(const std::vector<mrpt::math::TPose2D>& start_poses, double timestamp);

    size_t robotCount() const { return options.robots.size(); }
    /// The particle with the largest accumulated log-weight (Eq. 14).
    const TTeamParticle& bestParticle() const;
    /// One robot's path in a particle, oldest first: (timestamp, pose).
    static std::vector<std::pair<double, mrpt::math::TPose2D>> pathOf(const TTeamParticle& p,
                                                                       size_t robot);

protected:
    void prediction_and_update_pfStandardProposal(
        const mrpt::obs::CActionCollection* action, const mrpt::obs::CSensoryFrame* observation,
        const mrpt::bayes::CParticleFilter::TParticleFilterOptions& pf_options) override;

private:
    /// Sec. 3.1 for robot k: sample its pose in every particle; returns the step timestamp.
    void sampleMotion(size_t k, const mrpt::obs::CActionRobotMovement2D& odometry);
    /// Steps 2-3 for robot k with its measurements.
    void fuseMeasurements(size_t k, const std::vector<TLandmarkMeasurement>& z);

    CVisualLandmarksMap m_template;  ///< empty; shares the particles' descriptor pool
    mrpt::random::CRandomGenerator m_rng;
};

}  // namespace mrpt_vslam::multirobot
