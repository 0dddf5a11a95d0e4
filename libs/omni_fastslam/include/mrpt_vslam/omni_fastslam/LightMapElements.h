#pragma once

#include <mrpt/math/TPose2D.h>
#include <mrpt/typemeta/TEnumType.h>

#include <Eigen/Core>
#include <cstdint>
#include <vector>

namespace mrpt_vslam::omni_fastslam {

/** One bearing-only measurement z = (φ, θ) with its noise covariance Q (Gamallo et al. 2013,
 *  Sec. III-A). */
struct TBearingMeasurement {
    Eigen::Vector2d z = Eigen::Vector2d::Zero();             ///< (φ, θ) [rad]
    Eigen::Matrix2d Q = Eigen::Matrix2d::Identity() * 3e-4;  ///< covariance of (φ, θ) [rad²]
    /// The landmark's number when the data set gives it (`landmarkID`), else −1. Kept for
    /// evaluation only (counting wrong associations); the filter never reads it.
    int64_t hidden_id = -1;
};

/** Measurement model of the map (ini `measurement_model`):
 *  - `spherical`: an upward camera, z = (φ, θ), 3D landmarks (doc/omni-fastslam.md §2);
 *  - `planar`: azimuth only, z = φ, landmarks are points of the robot's plane (z = 0)
 *    (doc/omni-fastslam.md §12). */
enum class TMeasurementModelKind : uint8_t { Spherical = 0, Planar = 1 };

/** Landmark types of Sec. III-F(2): type II landmarks were initialized from far away and are
 *  neither used for the pose proposal (Alg. 3) nor for the particle weight (Alg. 4). */
enum class TLandmarkType : uint8_t { TypeI = 1, TypeII = 2 };

/** Data-association method: the paper's hierarchical Hungarian method or the greedy maximum
 *  likelihood (ML) method it is compared with (Sec. IV-A). */
enum class TAssociationMethod : uint8_t { Hungarian = 0, ML = 1 };

/** A map landmark B_j: a 3D Gaussian plus the detection counter i_j (Gamallo et al.
 *  2013, Sec. III). */
struct TLightLandmark {
    int64_t id = -1;
    Eigen::Vector3d mean = Eigen::Vector3d::Zero();  ///< μ_j [m]
    Eigen::Matrix3d cov = Eigen::Matrix3d::Zero();   ///< Σ_j [m²]
    int counter = 0;                                 ///< i_j: +1 seen, −1 unseen in range
    TLandmarkType type = TLandmarkType::TypeI;
    /// Measurements in a row taken from robot poses within D_min (XY) of the mean
    /// (used by updateLandmarksType() to promote type II to type I).
    int consecutive_close = 0;
};

/** One measurement of a candidate C_j with the robot pose it was taken from. */
struct TCandidateObservation {
    TBearingMeasurement measurement;
    mrpt::math::TPose2D robot_in_map;  ///< robot pose when the measurement was taken
    uint64_t step = 0;                 ///< insertion step of the map at that time
};

/** A cross-point of two of a candidate's measurements and its validity (Sec. III-F(1)). */
struct TCandidateCrossPoint {
    Eigen::Vector3d point = Eigen::Vector3d::Zero();  ///< [m]
    uint64_t step_first = 0;   ///< `step` of the older measurement of the pair
    uint64_t step_second = 0;  ///< `step` of the newer measurement of the pair
    double angle = 0;          ///< angle between the two rays [rad] (test a: > ANG_min)
    double gap = 0;            ///< common-perpendicular length [m]
    bool in_front = false;     ///< in front of both cameras and above them (test b)
    /// Σ over the candidate's measurements of log p(z_i | cross-point, x_i): its "probability".
    double sum_log_prob = 0;
    /// Σ over the candidate's measurements of the squared Mahalanobis distance (test c).
    double sum_mahalanobis2 = 0;
    bool valid = false;  ///< tests a, b and c all pass
};

/** A candidate landmark C_j: the measurements associated with it so far (Sec. III-F(1)). */
struct TCandidateLight {
    int64_t id = -1;
    std::vector<TCandidateObservation> observations;  ///< oldest first
    std::vector<TCandidateCrossPoint> cross_points;
    int counter = 0;             ///< i_j: +1 per measurement, −I_not per miss
    int consecutive_misses = 0;  ///< I_not of the paper: iterations in a row without measurement
    uint32_t nz = 0;             ///< NZ_j: measurements associated along time (incl. dropped)
    /// Planar model: depths [m] along the last measurement's ray where the light agrees with
    /// all kept measurements (doc/omni-fastslam.md §12).
    double depth_min = 0, depth_max = 0;
};

/** Result of the hierarchical data association (Sec. III-C). */
struct TLightAssociation {
    /// Level 1: landmark index (into landmarks()) of each measurement, or −1.
    std::vector<int> landmark_of_measurement;
    /// Level 2, only for measurements with landmark −1: candidate index (into candidates()),
    /// or −1 for "start a new candidate".
    std::vector<int> candidate_of_measurement;
};

}  // namespace mrpt_vslam::omni_fastslam

MRPT_ENUM_TYPE_BEGIN(mrpt_vslam::omni_fastslam::TAssociationMethod)
MRPT_FILL_ENUM_CUSTOM_NAME(mrpt_vslam::omni_fastslam::TAssociationMethod::Hungarian, "hungarian");
MRPT_FILL_ENUM_CUSTOM_NAME(mrpt_vslam::omni_fastslam::TAssociationMethod::ML, "ml");
MRPT_ENUM_TYPE_END()

MRPT_ENUM_TYPE_BEGIN(mrpt_vslam::omni_fastslam::TMeasurementModelKind)
MRPT_FILL_ENUM_CUSTOM_NAME(mrpt_vslam::omni_fastslam::TMeasurementModelKind::Spherical,
                           "spherical");
MRPT_FILL_ENUM_CUSTOM_NAME(mrpt_vslam::omni_fastslam::TMeasurementModelKind::Planar, "planar");
MRPT_ENUM_TYPE_END()
