#pragma once

#include <mrpt/math/TPoint2D.h>
#include <mrpt/math/TPose2D.h>

#include <map>
#include <string>
#include <vector>

namespace mrpt_vslam::mrclam {

/// One speed command of `RobotN_Odometry.dat`; it holds from `t` until the next command.
struct TSpeedCommand {
    double t = 0;  ///< [s] Unix time
    double v = 0;  ///< [m/s] forward speed
    double w = 0;  ///< [rad/s] turn rate
};

/// One barcode reading of `RobotN_Measurement.dat`.
struct TBarcodeReading {
    double t = 0;        ///< [s] Unix time
    int barcode = 0;     ///< barcode number read (not the subject)
    double range = 0;    ///< [m]
    double bearing = 0;  ///< [rad], counter-clockwise from the robot's heading
};

/// One Vicon pose of `RobotN_Groundtruth.dat`.
struct TViconPose {
    double t = 0;  ///< [s] Unix time
    mrpt::math::TPose2D pose;
};

/// The three files of one robot, each in time order.
struct TMrclamRobot {
    int number = 0;  ///< 1..5, also its subject number
    std::vector<TSpeedCommand> commands;
    std::vector<TBarcodeReading> readings;
    std::vector<TViconPose> ground_truth;
};

/** One dataset of the UTIAS Multi-Robot Cooperative Localization and Mapping collection (Leung
 *  et al., IJRR 2011): per robot its speed commands, barcode readings and Vicon poses, the
 *  landmark positions and the barcode of every subject (robots 1-5, landmarks 6-20).
 *
 *  The files are whitespace-separated text with `#` header lines. Every problem throws
 *  std::runtime_error naming the file (and the line for a malformed one): a missing folder or
 *  file, a wrong column count, a non-number, a time going back, a repeated subject or barcode. */
struct TMrclamDataset {
    static constexpr int kRobots = 5;        ///< subjects 1..5 are robots
    static constexpr int kLastSubject = 20;  ///< subjects 6..20 are landmarks

    std::vector<TMrclamRobot> robots;               ///< the robots asked for, in that order
    std::map<int, int> subject_of_barcode;          ///< Barcodes.dat
    std::map<int, mrpt::math::TPoint2D> landmarks;  ///< subject -> [m] Vicon position

    /// Reads `dir`'s Barcodes.dat, Landmark_Groundtruth.dat and the files of `robot_numbers`.
    static TMrclamDataset load(const std::string& dir, const std::vector<int>& robot_numbers);

    /// The first timestamp of any file of the loaded robots [s].
    double firstTime() const;
};

}  // namespace mrpt_vslam::mrclam
