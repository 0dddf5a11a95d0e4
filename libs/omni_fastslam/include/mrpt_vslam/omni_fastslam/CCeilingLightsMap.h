#pragma once

#include <mrpt/config/CLoadableOptions.h>
#include <mrpt/maps/CMetricMap.h>
#include <mrpt/maps/TMetricMapTypesRegistry.h>
#include <mrpt/math/TPose2D.h>
#include <mrpt/obs/obs_frwds.h>
#include <mrpt/poses/CPose3D.h>
#include <mrpt_vslam/omni_fastslam/BearingMeasurementModel.h>
#include <mrpt_vslam/omni_fastslam/LightMapElements.h>
#include <mrpt_vslam/omni_fastslam/RayCrossPoint.h>

#include <Eigen/Core>
#include <optional>
#include <vector>

namespace mrpt_vslam::omni_fastslam {

/** One particle's map of ceiling lights for omnidirectional FastSLAM 2.0
 *  (Gamallo, Mucientes & Regueiro, "A FastSLAM-based Algorithm for Omnidirectional Cameras",
 *  2013; doc/omni-fastslam.md).
 *
 *  Holds the landmarks B_j (3D Gaussian, counter i_j, type I/II) and the candidate landmarks C_j
 *  (their measurements with the robot poses, counter, cross-points). One insertion with a known
 *  robot pose (insertMeasurements(), or insertObservation() of a `CObservationBearingRange`):
 *  1. measurements (φ, θ) and their covariance Q from the observation;
 *  2. level-1 association to landmarks: N_z × (N + N_z) cost matrix −log φ_{l,j}, extra columns
 *     −log P_new, Hungarian method (or greedy ML)                         (Sec. III-C, Alg. 2)
 *  3. EKF update of the associated landmarks, counters +1 seen / −1 unseen in perceptual range,
 *     particle log-weight                                                   (Alg. 4 lines 1-27)
 *  4. level-2 association of the rest to the candidates (same construction) (Sec. III-C)
 *  5. updateCandidateLandmarks(): add measurements, new candidates, −I_not on misses, cross-points,
 *     promotion to landmark                                           (Alg. 4 line 28, III-F(1))
 *  6. updateLandmarksType(): type II → I, deletion of landmarks with i_j < 0 (line 29, III-F(2)).
 *
 *  Usage: create it from an `.ini` through `CMultiMetricMap` (`ceilingLightsMap_count = 1`, see
 *  doc/omni-fastslam.md), or directly and set the options; insert observations with known poses;
 *  read landmarks(); saveMetricMapRepresentationToFile() writes `<prefix>.txt` (map.txt format).
 *  The FastSLAM 2.0 filter calls the steps (associate(), updateLandmarks(), updateCandidates(),
 *  updateLandmarksType()) itself, with the pose it sampled and its own likelihood matrices.
 */
class CCeilingLightsMap : public mrpt::maps::CMetricMap {
    DEFINE_SERIALIZABLE(CCeilingLightsMap, mrpt_vslam::omni_fastslam)

  public:
    /** Camera description ("<prefix>_creationOpts" section). Shared by insertion and likelihood. */
    struct TSensorOptions : public mrpt::config::CLoadableOptions {
        /// `spherical` (φ, θ of an upward camera, 3D landmarks) or `planar` (azimuth only,
        /// landmarks in the robot's plane; doc/omni-fastslam.md §12).
        TMeasurementModelKind measurement_model = TMeasurementModelKind::Spherical;
        /// Camera pose on the robot, when set (ini: `sensor_in_robot = [x y z yaw pitch roll]`,
        /// m, deg); unset (the default): each observation's own `sensorLocationOnRobot`, as
        /// MRPT's maps take it.
        std::optional<mrpt::poses::CPose3D> sensor_in_robot;
        /// Default σ of φ / θ [rad] (ini: `sigma_phi_deg`, `sigma_theta_deg`), used when the
        /// observation has neither per-measurement covariances nor sensor_std_yaw/pitch > 0.
        double sigma_phi = 1.0 * M_PI / 180;
        double sigma_theta = 1.0 * M_PI / 180;
        /// Perceptual range: maximum θ [rad] (ini: `max_theta_deg`).
        double max_theta = 80.0 * M_PI / 180;
        /// Perceptual range: maximum horizontal camera-landmark distance [m] (0 = unlimited).
        double max_horizontal_distance = 0;
        /// Perceptual range: maximum |φ| [rad] (ini: `max_abs_azimuth_deg`), half the horizontal
        /// field of view of a forward camera; π = all around. Unset (the default): half the
        /// observation's own `fieldOfView_yaw` (sensorLimitsInUse()).
        std::optional<double> max_abs_azimuth;

        void loadFromConfigFile(const mrpt::config::CConfigFileBase& cfg,
                                const std::string& section) override;
        void dumpToTextStream(std::ostream& out) const override;
    } sensorOptions;

    /** Association and initialization parameters ("<prefix>_insertOpts"); paper values. */
    struct TInsertionOptions : public mrpt::config::CLoadableOptions {
        /// `hungarian` (hierarchical, Sec. III-C) or `ml` (greedy maximum likelihood, Sec. IV-A).
        TAssociationMethod association_method = TAssociationMethod::Hungarian;
        unsigned int nz_min = 3;        ///< NZ_min: measurements for a candidate's promotion
        unsigned int ncross_valid = 5;  ///< NCROSS_valid: valid cross-points for promotion
        /// ANG_min [rad] (ini: `ang_min_deg`, paper "1.22 rad (7°)": we use 7°).
        double ang_min = 7.0 * M_PI / 180;
        double d_min = 8.0;  ///< D_min: XY distance for type I landmarks [m]
        /// Σ0 diagonal [m²]. The paper's diag(0.0025, 0.0025) (for a 3D landmark) is far below
        /// the triangulation error of a light from rays a few degrees apart; 0.5 is what the
        /// project measured best with the spherical model (doc/omni-fastslam.md, "Deviations").
        double sigma0_xx = 0.5, sigma0_yy = 0.5, sigma0_zz = 0.5;
        /// Squared Mahalanobis distance of P_new = (1/2π)|Q|^{-1/2} exp(−p_new_mahalanobis2/2).
        double p_new_mahalanobis2 = 64;
        /// Counter decrement of an unseen candidate: 0 = the paper's I_not (number of iterations
        /// in a row without a measurement), > 0 = this fixed amount.
        unsigned int candidate_miss_decrement = 0;
        /// Measurements kept per candidate (oldest dropped); bounds the O(n²) cross-points.
        unsigned int max_candidate_measurements = 20;
        /// Our addition (doc/omni-fastslam.md): after a promotion, fuse the candidate's
        /// measurements into the new landmark by EKF updates from the poses they were taken
        /// from. false = the paper (mean = best cross-point, covariance Σ0); true is what the
        /// project measured best.
        bool refine_initialization = true;
        /// The farthest the camera reads a light [m] (0 = no limit; planar: in its plane):
        /// cross-points farther along either ray are not valid, and a landmark farther is not
        /// associated with a measurement (isWithinReadingRange()). Unset (the default): the
        /// observation's own `maxSensorDistance` (sensorLimitsInUse()).
        std::optional<double> max_cross_point_range;
        /// The nearest the camera reads a light [m] (0 = no limit): as max_cross_point_range;
        /// planar: also the near end of the segment a candidate's last ray predicts; the
        /// smoothing (LightsPathSmoother) keeps lights beyond it. Unset (the default): the
        /// observation's own `minSensorDistance`.
        std::optional<double> min_cross_point_range;
        /// Counter increment i_j of a landmark or candidate per associated measurement (a new
        /// candidate starts at it); misses still cost 1 (landmarks) or the candidate decrement.
        /// Paper: 1. With a detection probability p < 1/2 inside the perceptual range the
        /// paper's counters drift down and delete real landmarks; k·p − (1 − p) > 0 keeps them.
        unsigned int hit_increment = 1;

        void loadFromConfigFile(const mrpt::config::CConfigFileBase& cfg,
                                const std::string& section) override;
        void dumpToTextStream(std::ostream& out) const override;
    } insertionOptions;

    /** Particle weighting ("<prefix>_likelihoodOpts"). */
    struct TLikelihoodOptions : public mrpt::config::CLoadableOptions {
        /// p_in: detection probability of a landmark inside the perceptual range; an unseen one
        /// contributes 1 − p_in (Alg. 4 line 21). In [0, 1).
        double p_in = 0.5;
        /// Whether type II landmarks weigh particles (the paper: no).
        bool use_type_ii_landmarks = false;

        void loadFromConfigFile(const mrpt::config::CConfigFileBase& cfg,
                                const std::string& section) override;
        void dumpToTextStream(std::ostream& out) const override;
    } likelihoodOptions;

    /** 3D rendering ("<prefix>_renderOpts"). */
    struct TRenderOptions : public mrpt::config::CLoadableOptions {
        bool draw_candidates = true;       ///< candidates as faint points at their best cross-point
        double ellipsoid_quantiles = 3.0;  ///< covariance ellipsoids at this many σ

        void loadFromConfigFile(const mrpt::config::CConfigFileBase& cfg,
                                const std::string& section) override;
        void dumpToTextStream(std::ostream& out) const override;
    } renderOptions;

    CCeilingLightsMap() = default;

    /// @name Map contents
    /// @{
    const std::vector<TLightLandmark>& landmarks() const { return m_landmarks; }
    const std::vector<TCandidateLight>& candidates() const { return m_candidates; }
    /// Iterations closed so far (each updateCandidates() closes one).
    uint64_t step() const { return m_step; }
    /// Adds a landmark (e.g. a known map), returns its id. \param cov [m²]
    int64_t addLandmark(const Eigen::Vector3d& mean, const Eigen::Matrix3d& cov,
                        TLandmarkType type = TLandmarkType::TypeI, int counter = 1);
    /// The measurement model with the camera pose in use (sensorPoseInUse()).
    BearingMeasurementModel measurementModel() const;
    /** The camera pose of the measurements being processed: sensorOptions.sensor_in_robot
     *  when set, else that of the last observation given to measurementsFromObservation(). */
    const mrpt::poses::CPose3D& sensorPoseInUse() const { return m_sensor_in_robot; }
    /// The camera's field of view and reading range.
    struct TSensorLimits {
        double max_abs_azimuth = M_PI;  ///< [rad] half the horizontal field of view
        double min_range = 0;           ///< [m] nearest reading (0: no limit)
        double max_range = 0;           ///< [m] farthest reading (0: no limit)
    };
    /** The limits in use: each option's value when set, else that of the last observation
     *  given to measurementsFromObservation() (fieldOfView_yaw / 2, minSensorDistance,
     *  maxSensorDistance; before any, all around and no range limit). */
    TSensorLimits sensorLimitsInUse() const;
    /// @}

    /// @name Measurements
    /// @{
    /** (φ, θ) and Q of each entry of an `OMNICAM_BEARINGS` observation (φ = yaw, θ = π/2 +
     *  pitch); Q from the per-measurement covariances, else sensor_std_yaw/pitch, else the
     *  sensorOptions defaults. \throw std::runtime_error naming the sensor label and landmark
     *  for a non-finite bearing or pitch (ranges are not used, any value is fine), a non-finite
     *  or negative covariance or sensor_std_*: never silently wrong input. */
    std::vector<TBearingMeasurement> measurementsFromObservation(
        const mrpt::obs::CObservationBearingRange& obs) const;
    /// log P_new = −log 2π − ½ log|Q| − p_new_mahalanobis2 / 2 (Sec. IV); planar: the same
    /// on φ alone, −½ log(2π Q_φφ) − p_new_mahalanobis2 / 2.
    double logPNew(const TBearingMeasurement& m) const;
    /// log N(ν; 0, S) of an innovation of this map's measurements: logGaussian() for the
    /// spherical model, the 1D density of ν_φ with variance S_φφ for the planar one.
    double measurementLogLikelihood(const Eigen::Vector2d& innovation,
                                    const Eigen::Matrix2d& S) const;
    /** Whether a predicted measurement can have been observed: θ ≤ max_theta + margin
     *  (spherical) and |φ| ≤ the max_abs_azimuth in use + margin. \param margin [rad] */
    bool couldBeObserved(const Eigen::Vector2d& z_predicted, double margin = 0) const;
    /** Whether the camera reads a light at `point_in_camera` [m] (planar: in its plane):
     *  within the reading range in use (sensorLimitsInUse(); a limit of 0: none). */
    bool isWithinReadingRange(const Eigen::Vector3d& point_in_camera) const;
    /// log N(ν; 0, S) of a 2D innovation.
    static double logGaussian(const Eigen::Vector2d& innovation, const Eigen::Matrix2d& S);
    /// Whether a point is inside the perceptual range of the camera at robot_in_map.
    bool isInPerceptualRange(const Eigen::Vector3d& point_in_map,
                             const mrpt::math::TPose2D& robot_in_map) const;
    /// The same with the model at the robot's pose (`at` = measurementModel().atPose()).
    bool isInPerceptualRange(const Eigen::Vector3d& point_in_map,
                             const BearingMeasurementModel::AtPose& at) const;
    /// @}

    /// @name Data association (Sec. III-C)
    /// @{
    /** log φ_{l,j} (Alg. 2 line 11) of every measurement l and landmark j at a fixed pose:
     *  N(z_l; h(μ_j, x), Q_l + H_m Σ_j H_m^T). −inf where the prediction is undefined. */
    Eigen::MatrixXd landmarkLogLikelihoods(const std::vector<TBearingMeasurement>& z,
                                           const mrpt::math::TPose2D& robot_in_map) const;
    /** log p(z_l | x, C_j) of every measurement and candidate (doc/omni-fastslam.md "Candidate
     *  likelihood"): from the candidate's best valid cross-point if it has one, else from the
     *  point of its last measurement ray closest to the ray of z_l. */
    Eigen::MatrixXd candidateLogLikelihoods(const std::vector<TBearingMeasurement>& z,
                                            const mrpt::math::TPose2D& robot_in_map) const;
    /** One level of the association: row l of log_lik holds the log-likelihoods of measurement
     *  l, log_p_new(l) its log P_new. Hungarian: minimum-cost assignment of the N_z × (N + N_z)
     *  matrix of −log values. ML: measurement by measurement, in order, the most likely column not
     *  yet taken. Returns the column of each row, −1 for "new". */
    static std::vector<int> solveAssociation(const Eigen::MatrixXd& log_lik,
                                             const Eigen::VectorXd& log_p_new,
                                             TAssociationMethod method);
    /** Level 2 only: the candidate of each measurement that level 1 left without a landmark
     *  (landmark_of_measurement[l] < 0), −1 for "new candidate" and for measurements with a
     *  landmark. */
    std::vector<int> associateCandidates(const std::vector<TBearingMeasurement>& z,
                                         const mrpt::math::TPose2D& robot_in_map,
                                         const std::vector<int>& landmark_of_measurement) const;
    /// Both levels at a known pose, with insertionOptions.association_method.
    TLightAssociation associate(const std::vector<TBearingMeasurement>& z,
                                const mrpt::math::TPose2D& robot_in_map) const;
    /// @}

    /// @name Map update (Alg. 4)
    /// @{
    /** EKF update of the landmarks associated to a measurement and their counters (Alg. 4
     *  lines 1-27). Returns the particle log-weight Σ log ŵ: log N(ν; 0, H_x R H_x^T + Q̃) per
     *  associated landmark, log(1 − p_in) per unseen landmark in range (type I only unless
     *  use_type_ii_landmarks).
     *  \param robot_pose_cov R_t, covariance of (x, y, yaw) [m², m·rad, rad²] (0 for known poses)
     */
    double updateLandmarks(const std::vector<TBearingMeasurement>& z,
                           const mrpt::math::TPose2D& robot_in_map,
                           const std::vector<int>& landmark_of_measurement,
                           const Eigen::Matrix3d& robot_pose_cov = Eigen::Matrix3d::Zero());
    /** updateCandidateLandmarks() (Alg. 4 line 28): measurements with landmark −1 go to their
     *  candidate (or start a new one), unseen candidates lose I_not and go at ≤ 0, candidates
     *  meeting the initialization conditions become landmarks. Closes the iteration (step()+1). */
    void updateCandidates(const std::vector<TBearingMeasurement>& z,
                          const mrpt::math::TPose2D& robot_in_map, const TLightAssociation& assoc);
    /// updateLandmarksType() (Alg. 4 line 29): type II → I, deletion of landmarks with i_j < 0.
    void updateLandmarksType();
    /// Steps 2-6 of the class description at a known pose. Returns updateLandmarks()'s log-weight.
    double insertMeasurements(const std::vector<TBearingMeasurement>& z,
                              const mrpt::math::TPose2D& robot_in_map);
    /// @}

    /// @name CMetricMap interface
    /// @{
    bool isEmpty() const override;
    /// Writes `<prefix>.txt`: `# id x y z cxx cxy cxz cyy cyz czz`, one line per landmark.
    void saveMetricMapRepresentationToFile(const std::string& filNamePrefix) const override;
    void getVisualizationInto(mrpt::opengl::CSetOfObjects& o) const override;
    std::string asString() const override;
    float compute3DMatchingRatio(const mrpt::maps::CMetricMap* otherMap,
                                 const mrpt::poses::CPose3D& otherMapPose,
                                 const mrpt::maps::TMatchingRatioParams& params) const override;
    /// @}

    MAP_DEFINITION_START(CCeilingLightsMap)
    mrpt_vslam::omni_fastslam::CCeilingLightsMap::TSensorOptions sensorOpts;
    mrpt_vslam::omni_fastslam::CCeilingLightsMap::TInsertionOptions insertionOpts;
    mrpt_vslam::omni_fastslam::CCeilingLightsMap::TLikelihoodOptions likelihoodOpts;
    mrpt_vslam::omni_fastslam::CCeilingLightsMap::TRenderOptions renderOpts;
    MAP_DEFINITION_END(CCeilingLightsMap)

  protected:
    void internal_clear() override;
    bool internal_insertObservation(
        const mrpt::obs::CObservation& obs,
        const std::optional<const mrpt::poses::CPose3D>& robotPose = std::nullopt) override;
    double internal_computeObservationLikelihood(
        const mrpt::obs::CObservation& obs, const mrpt::poses::CPose3D& takenFrom) const override;
    bool internal_canComputeObservationLikelihood(
        const mrpt::obs::CObservation& obs) const override;

  private:
    /// See sensorPoseInUse(); set by each observation turned into measurements.
    mutable mrpt::poses::CPose3D m_sensor_in_robot;
    /// The limits the last observation states (see sensorLimitsInUse()).
    mutable TSensorLimits m_observed_limits;
    /// The limits in use with `observed` as the observation's: each option's value when set.
    TSensorLimits limitsInUse(const TSensorLimits& observed) const;
    std::vector<TLightLandmark> m_landmarks;
    std::vector<TCandidateLight> m_candidates;
    uint64_t m_step = 0;
    int64_t m_next_landmark_id = 0;
    int64_t m_next_candidate_id = 0;

    bool usesForWeight(const TLightLandmark& lm) const;
    void addCandidateObservation(TCandidateLight& cand, const TCandidateObservation& obs) const;
    void refreshCrossPointValidity(TCandidateLight& cand) const;
    /** Planar candidate likelihood: innovation of z against the segment [s_lo, s_hi] [m] of a
     *  candidate's last ray (origin, unit dir); x is the crossing of that ray with the ray of
     *  z. */
    static Eigen::Vector2d segmentInnovation(const BearingMeasurementModel& model,
                                             const Eigen::Vector3d& origin,
                                             const Eigen::Vector3d& dir, double s_lo, double s_hi,
                                             const TRayCrossPoint& x, const Eigen::Vector2d& z,
                                             const mrpt::math::TPose2D& robot_in_map);
    /** Planar: the depths along the candidate's last ray, between min_ and
     *  max_cross_point_range, where every earlier measurement is within the P_new gate. When
     *  there is none, the candidate keeps only its newest measurement. */
    void updateDepthInterval(TCandidateLight& cand) const;
    /// Limits of the cross-point tests (a), (b) from the options and the measurement model.
    TCrossPointLimits crossPointLimits() const;
    bool tryPromote(const TCandidateLight& cand);
    /** Alg. 4 lines 4-9 for one landmark and measurement at a pose. Returns false (and changes
     *  nothing) where the prediction is undefined; else the innovation, its covariance Q̃ and
     *  H_x at the prior mean. */
    bool ekfUpdate(TLightLandmark& lm, const TBearingMeasurement& m,
                   const BearingMeasurementModel::AtPose& at, Eigen::Vector2d& innovation,
                   Eigen::Matrix2d& S, BearingMeasurementModel::Matrix23& H_x) const;
};

}  // namespace mrpt_vslam::omni_fastslam
