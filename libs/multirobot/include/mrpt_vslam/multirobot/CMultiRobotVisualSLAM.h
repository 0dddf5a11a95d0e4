#pragma once

#include <mrpt/bayes/CParticleFilter.h>
#include <mrpt/bayes/CParticleFilterCapable.h>
#include <mrpt/bayes/CParticleFilterData.h>
#include <mrpt/config/CLoadableOptions.h>
#include <mrpt/obs/CActionRobotMovement2D.h>
#include <mrpt/random/RandomGenerators.h>
#include <mrpt_vslam/core/OdometryGaussian.h>
#include <mrpt_vslam/core/ParallelFor.h>
#include <mrpt_vslam/core/ParticleFilterDataImpl.h>
#include <mrpt_vslam/multirobot/TeamParticle.h>

#include <functional>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace mrpt_vslam::multirobot {

/** The Rao-Blackwellized particle filter of Gil et al. (2010, Alg. 1; doc/multirobot.md)
 *  over the joint paths of K robots and one shared map of 3D visual landmarks, on MRPT's
 *  particle-filter framework: drive it with `mrpt::bayes::CParticleFilter::executeOn()`;
 *  resampling happens there when N_eff < BETA (Alg. 1 line 13). `pfStandardProposal` is the
 *  paper's filter (below); `pfOptimalProposal` (ours) replaces steps 1 and 3 of a robot with
 *  measurements by a FastSLAM 2.0 proposal: a Gaussian in its pose from the odometry prior and
 *  sequential EKF updates with the associated landmarks, the pose drawn from it, the weight
 *  p(z | x_{t-1}, u, map) (the product of the marginals of its measurements), then the
 *  landmark updates from the drawn pose.
 *
 *  Input of one step: an action collection with one `CActionRobotMovement2D` per robot, in the
 *  order of options.robots, and a sensory frame with each robot's `<ROBOT>_LANDMARKS`
 *  (`CObservationVisualLandmarks`) or `<ROBOT>_RB` (`CObservationBearingRange`: planar
 *  range-bearing without descriptors, associated by the gate alone); a robot may have none.
 *  With options.robot_reading_ids, `<ROBOT>_ROBOTS` readings of the other robots of the team
 *  (ours: cooperative localization, as in MRCLAM) weigh each particle by how well they fit
 *  its poses of both robots; the seen robot is known, so there is no association and no gate.
 *  With `pfOptimalProposal` they also update the proposal of the reading robot. Robot by robot
 *  (lines 7-9):
 *   1. sample each particle's pose of that robot from the odometry's Gaussian (Sec. 3.1);
 *   2. keep its B nearest measurements (Sec. 6.2) and, for each one, search the shared pool
 *      for candidates once (E ≤ E0 near the point, radius widened by the particles' spread);
 *   3. particle by particle (its landmarks stay in the cache), fuse the measurements one
 *      after the other (CVisualLandmarksMap::fuse(): D0 gate, min E, EKF or new landmark; with
 *      the map's joint_association, associated all at once first by associateJointly()) and
 *      multiply its weight by ω (Eq. 13) or p0; the weights of the K robots multiply (line 11).
 *      The candidates are searched before the frame is fused, so two points of one frame never
 *      become one landmark. A robot with several sensors (observations in the frame) fuses
 *      them one after the other, the first in the proposal, so that the points of two
 *      sensors may become one landmark, and a sensor's points take distinct landmarks;
 *   4. with `resample_per_robot` (ours), resample when N_eff < BETA before the next robot's
 *      motion is sampled. The robots' motions are independent, so this is the same posterior
 *      processed one robot at a time; it keeps the particles from having to be good for all
 *      K robots at once, which the joint product over a 3K-dimensional proposal rarely is.
 *  The best particle is the one with the largest Σ_t log ω_t (Eq. 14). Each step of a
 *  particle's path keeps the step's correspondences (FastSLAM's c_t: the landmark each measurement
 *  went to, with its track_id), for the evaluation of the associations. */
class CMultiRobotVisualSLAM
    : public mrpt::bayes::CParticleFilterData<TTeamParticle,
                                              mrpt::bayes::particle_storage_mode::POINTER>,
      public core::ParticleFilterDataImpl<
          CMultiRobotVisualSLAM,
          mrpt::bayes::CParticleFilterData<
              TTeamParticle, mrpt::bayes::particle_storage_mode::POINTER>::CParticleList> {
  public:
    struct TOptions : public mrpt::config::CLoadableOptions {
        /// Robot names, the prefix of their sensor labels (ini: `robots = R1 R2`). One name: a
        /// single-robot rawlog, whose observations are found by class (see sensor_label).
        std::vector<std::string> robots{"R1", "R2"};
        /// One robot only: the sensor label of its landmark observations (range-bearing,
        /// visual landmarks or, in the app, stereo images); empty: every observation of those
        /// classes, whatever its label. Several robots: must be empty, their labels are
        /// `<ROBOT>` + the suffixes below.
        std::string sensor_label;
        /// Suffix of the landmark observations' labels: `<ROBOT>` + this.
        std::string landmarks_suffix = "_LANDMARKS";
        /// Suffix of the range-bearing observations' labels (`CObservationBearingRange`).
        std::string range_bearing_suffix = "_RB";
        /// Noise of range-bearing measurements (ini: range_bearing_std_range,
        /// range_bearing_std_bearing_deg, range_bearing_std_pitch_deg: absent = the
        /// observation's own sensor_std_*; range_bearing_std_height).
        TRangeBearingNoise range_bearing_noise;
        /// Suffix of the labels of range-bearing readings of other robots of the team
        /// (`CObservationBearingRange`, landmarkID = the seen robot's id below).
        std::string robot_readings_suffix = "_ROBOTS";
        /// The landmarkID that names each robot of `robots` in those readings, in the same order
        /// (ini: `robot_reading_ids = 1 2 3`); empty: readings of robots are not used.
        std::vector<int> robot_reading_ids;
        /// Noise of those readings (ini: robot_reading_std_range, robot_reading_std_bearing_deg,
        /// robot_reading_std_height).
        TRangeBearingNoise robot_reading_noise;
        /// B: measurements integrated per robot and step (paper: 8 online, 20 offline).
        unsigned int max_observations_per_robot = 8;
        /// Which B of a robot's measurements are kept when it has more (ini:
        /// `observation_selection = nearest | random`; the paper does not say): the nearest, the
        /// most precise for a stereo pair, or a uniform random subset.
        enum class TSelection { Nearest, Random } observation_selection = TSelection::Nearest;
        /// Added to the odometry covariance so the proposal never degenerates (ini:
        /// min_motion_std_xy [m], min_motion_std_phi_deg).
        core::TMotionNoiseFloor motion_noise_floor{0.002, 0.1 * M_PI / 180};
        /// Spread of the initial poses of every robot but the first, whose start defines the
        /// map frame (Sec. 6.1: "the initial position ... is known approximately").
        double initial_std_xy = 0.05;               ///< [m]
        double initial_std_phi = 1.0 * M_PI / 180;  ///< [rad] (ini: initial_std_phi_deg)
        /// Resample (if N_eff < BETA) after each robot's measurements too (ours; paper: once
        /// per step). Pays off with 3 robots (doc/multirobot.md).
        bool resample_per_robot = false;
        /** The sensor label of robot k's observations for a label suffix: `<ROBOT>` + suffix
         *  for a team, sensor_label for one robot ("": any label). */
        std::string inputLabel(size_t k, const std::string& suffix) const
        {
            return robots.size() == 1 ? sensor_label : robots[k] + suffix;
        }
        void loadFromConfigFile(const mrpt::config::CConfigFileBase& cfg,
                                const std::string& section) override;
        void saveToConfigFile(mrpt::config::CConfigFileBase& cfg,
                              const std::string& section) const override;
    } options;

    /// Counters of the last step (summed over particles where marked).
    struct TStepStats {
        size_t measurements = 0;         ///< integrated (after the B limit), all robots
        size_t candidates = 0;           ///< pool candidates, summed over measurements
        size_t created = 0;              ///< new landmarks, summed over particles
        size_t associated = 0;           ///< EKF updates, summed over particles
        size_t robot_readings = 0;       ///< readings of team robots used, all robots
        size_t non_positive_ranges = 0;  ///< range-bearing readings left out (range ≤ 0)
    } lastStepStats;

    /// A reading of another robot of the team: its index and where robot k saw it.
    struct TRobotReading {
        size_t robot;
        TLandmarkMeasurement m;
    };
    /** Told of what the filter takes in (TeamPathSmoother records the run with it): of
     *  reset(), and once per robot and step of its inputs, before its motion is sampled. */
    struct TStepObserver {
        virtual ~TStepObserver() = default;
        /// reset(): the start poses; the particles' poses of every robot but the first are
        /// drawn around them with σ initial_std_xy [m], initial_std_phi [rad].
        virtual void onReset(const std::vector<mrpt::math::TPose2D>& start_poses,
                             double initial_std_xy, double initial_std_phi) = 0;
        /** Robot `robot` in step `step` (1 for the first, the index of the step in the path;
         *  robots in the order of options.robots): its odometry Gaussian, its B measurements
         *  and its readings of other robots of the team. */
        virtual void onRobotStep(size_t step, size_t robot, const core::TOdometryGaussian& motion,
                                 const std::vector<TLandmarkMeasurement>& z,
                                 const std::vector<TRobotReading>& readings) = 0;
    };

    /** \param map_template options every particle's map starts with (must be empty)
     *  \param particle_count M \param seed of the filter's own random generator */
    CMultiRobotVisualSLAM(const CVisualLandmarksMap& map_template, size_t particle_count,
                          uint32_t seed);

    /** All particles at the start poses (one per robot), the first robot's exactly, the others
     *  drawn around theirs with options.initial_std_*; equal weights; empty maps. */
    void reset(const std::vector<mrpt::math::TPose2D>& start_poses, double timestamp);

    size_t robotCount() const { return options.robots.size(); }
    /// One robot's path in a particle, oldest first: (timestamp, pose).
    static std::vector<std::pair<double, mrpt::math::TPose2D>> pathOf(const TTeamParticle& p,
                                                                      size_t robot);
    /// `observer` (nullptr: none) is told of every reset() and step from now on; it must
    /// outlive its use by the filter.
    void setStepObserver(TStepObserver* observer) { m_observer = observer; }

    /** Resampling (core::ParticleFilterDataImpl), then, once as many landmarks were created
     *  since the last time as the pool's search then kept, the landmarks of the particles
     *  that died taken out of the pool's search (LandmarkDescriptorPool::forgetAllBut()):
     *  they can match no particle, and spurious ones pile up by the thousand on long runs. */
    void performSubstitution(const std::vector<size_t>& indx) override;

  protected:
    void prediction_and_update_pfStandardProposal(
        const mrpt::obs::CActionCollection* action, const mrpt::obs::CSensoryFrame* observation,
        const mrpt::bayes::CParticleFilter::TParticleFilterOptions& pf_options) override;
    void prediction_and_update_pfOptimalProposal(
        const mrpt::obs::CActionCollection* action, const mrpt::obs::CSensoryFrame* observation,
        const mrpt::bayes::CParticleFilter::TParticleFilterOptions& pf_options) override;

  private:
    core::TOdometryGaussian motionOf(size_t k,
                                     const mrpt::obs::CActionRobotMovement2D& odometry) const;
    /// Robot k's B measurements in the frame (`<ROBOT>_LANDMARKS` or `<ROBOT>_RB`), selected as
    /// `observation_selection` says (random: drawn from the filter's generator), each with the
    /// index of its observation in the frame as its sensor.
    std::vector<TLandmarkMeasurement> measurementsOf(size_t k,
                                                     const mrpt::obs::CSensoryFrame& frame);
    /// Robot k's readings of the other robots of the team (`<ROBOT>_ROBOTS`); others dropped.
    std::vector<TRobotReading> robotReadingsOf(size_t k, const mrpt::obs::CSensoryFrame& frame);
    /// pfStandardProposal: multiplies each particle's weight by its robot readings' likelihood.
    void weighRobotReadings(size_t k, const std::vector<TRobotReading>& readings);
    std::vector<mrpt::math::TPose2D> posesOf(size_t k) const;
    /** core::parallelFor() over the particles for a body that reads or writes their poses
     *  and little else: the poses of the particle kParticlesAhead on in this thread's run are
     *  requested before body(i) runs (the particles' data lie scattered in memory, and such a
     *  loop is bound by the misses on them). */
    void forEachParticle(const std::function<void(size_t)>& body,
                         const std::function<void()>& first = {}) const;
    /// How many particles on in its run a loop over the particles requests a particle's data
    /// (forEachParticle(), the path step of runStep()): enough for the misses to overlap
    static constexpr size_t kParticlesAhead = 4;
    /// One step: every robot moves and measures (lines 7-9); `optimal` selects the proposal.
    void runStep(const mrpt::obs::CActionCollection* action,
                 const mrpt::obs::CSensoryFrame* observation,
                 const mrpt::bayes::CParticleFilter::TParticleFilterOptions& pf_options,
                 bool optimal);
    /// Sec. 3.1 for robot k: sample its pose in every particle from the motion model.
    void sampleMotion(size_t k, const core::TOdometryGaussian& motion);
    /// N(0, I₃) per particle for a robot's move: drawn ahead (drawNoiseAhead()) or now.
    const std::vector<Eigen::Vector3d>& particleNoise();
    /** The next move's particle noise drawn from the generator now, by the calling thread
     *  while the others update the particles (core::parallelFor()'s `first`): the same draws
     *  in the same order, off the serial path. Not with `observation_selection = random`,
     *  which draws from the generator between two moves. */
    void drawNoiseAhead();
    /** The pool's candidates for each measurement, searched once for all particles around
     *  the mean of `poses`, widened by their spread plus extra_xy [m] and extra_phi [rad]. */
    std::vector<TMeasurementCandidates> searchCandidates(
        const std::vector<mrpt::math::TPose2D>& poses, double extra_xy, double extra_phi,
        const std::vector<TLandmarkMeasurement>& z);
    /// Steps 2-3 for robot k with its measurements of one sensor, after sampleMotion() or
    /// proposeAndFuse() (`rule` as CVisualLandmarksMap::fuseFrame() takes it).
    void fuseMeasurements(size_t k, const std::vector<TLandmarkMeasurement>& z,
                          CVisualLandmarksMap::TFrameAssociation rule);
    /// pfOptimalProposal for robot k: Gaussian proposal from the motion and the measurements,
    /// weight p(z | x_{t-1}, u, map), then the landmark updates from the sampled pose.
    void proposeAndFuse(size_t k, const core::TOdometryGaussian& motion,
                        const std::vector<TLandmarkMeasurement>& z,
                        const std::vector<TRobotReading>& readings);
    /** Alg. 1 lines 33-36 for robot k after its particles fused the rest of z:
     *  `created[i * n + j]` says measurement j starts a landmark in particle i. The pool's ids
     *  are handed out in particle order (one thread, as a serial loop would), then the
     *  particles create the landmarks in parallel and give the id to the correspondence
     *  each left for it (the last n of the particle's). */
    void createLandmarks(size_t k, const std::vector<TLandmarkMeasurement>& z,
                         std::vector<TMeasurementCandidates>& candidates,
                         const std::vector<bool>& created);

    size_t m_steps = 0;                   ///< since reset()
    TStepObserver* m_observer = nullptr;  ///< setStepObserver()

    CVisualLandmarksMap m_template;  ///< empty; shares the particles' descriptor pool
    /// Pool size at the last performSubstitution() that pruned it, and ids it kept then
    size_t m_poolSizeAtPrune = 0, m_poolKeptAtPrune = 0;
    mrpt::random::CRandomGenerator m_rng;
    /// The move's normal draws, one per particle, and those of the next move if drawn ahead
    std::vector<Eigen::Vector3d> m_noise, m_noise_ahead;
    bool m_noise_ahead_drawn = false;
};

}  // namespace mrpt_vslam::multirobot
