#pragma once

#include <mrpt/config/CLoadableOptions.h>
#include <mrpt/math/CMatrixFixed.h>
#include <mrpt/math/TPoint3D.h>
#include <mrpt/obs/CObservationStereoImages.h>
#include <mrpt/obs/CObservationVisualLandmarks.h>
#include <mrpt_vslam/core/USurfDescriptor.h>
#include <mrpt_vslam/multirobot/StereoGeometry.h>
#include <mrpt_vslam/multirobot/StereoMatcher.h>
#include <mrpt_vslam/multirobot/StereoRectifier.h>

#include <cstddef>
#include <cstdint>
#include <limits>
#include <string>
#include <vector>

namespace mrpt_vslam::multirobot {

/** The stereo front-end of one robot (Gil et al. 2010, Sec. 4, 6.1 and 6.2): turns rectified
 *  stereo pairs into 3D visual landmark observations o_t = (z_t, d_t) with their covariance
 *  R_t, keeping only points tracked over several consecutive frames. A pair whose calibration
 *  is not rectified is rectified first (StereoRectifier). Per frame:
 *
 *   1. Harris corners on the left image (OpenCV's goodFeaturesToTrack with the Harris
 *      measure: quality relative to the strongest corner, 3 × 3 non-maximum suppression, a
 *      minimum distance between corners), only where the descriptor window and the
 *      correlation patch fit in the image.
 *   2. Stereo correspondence along the same row of the right image (StereoMatcher: NCC,
 *      uniqueness, parabolic sub-pixel disparity, optional left-right check); points whose
 *      depth lies outside [min_depth, max_depth] are dropped.
 *   3. The 64-D U-SURF descriptor d_t of each left point at the fixed scale `usurf_scale`
 *      (core::USurfDescriptor; points on flat patches get none and are dropped).
 *   4. z_t = (X, Y, Z) in the left camera frame (Eq. 12) and R_t = J R_sp Jᵀ (Sec. 3.2),
 *      StereoGeometry.
 *   5. Tracking against the previous frame of the same robot: each point takes the previous
 *      point within `track_search_radius` pixels whose descriptor is nearest, if it passes
 *      the ratio test and `track_max_descriptor_distance`; when several points take the same
 *      previous point the nearest descriptor keeps it. A matched point continues that track
 *      (same id, length + 1); any other starts a new track (new id, length 1). A track that
 *      misses a frame ends.
 *   6. "Only the observations found in 3 consecutive robot poses are integrated in the filter"
 *      (Sec. 6.2): points whose track length is at least `min_track_length` are emitted, at
 *      most `max_landmarks_per_frame` of them (0: all), longest tracks first, then the nearest
 *      (smallest Z), then the oldest track id. The paper's limit of B = 8 observations per
 *      filter iteration (Sec. 6.2) is a filter setting, not this one.
 *
 *  Output: a CObservationVisualLandmarks with the input's timestamp, label `<ROBOT>_LANDMARKS`
 *  (landmarksLabel()), refCameraPose = the left camera's pose on the robot, and one CLandmark
 *  per emitted point: pose_mean = z_t [m] in the camera frame (x right, y down, z forward),
 *  pose_cov_11..33 = R_t [m²], ID = track id, seenTimesCount = track length,
 *  timestampLastSeen = the frame's timestamp, and one CFeature (type featHarris) with
 *  keypoint.pt = the left pixel (x = column, y = row), keypoint.ID = track id and
 *  descriptors.SURF = the 64 U-SURF floats.
 *
 *  Usage: one instance per robot (it keeps that robot's tracks);
 *  `auto lm = frontEnd.process(stereo_obs);` for each of its frames, in time order.
 */
class StereoFrontEnd {
  public:
    /** Section `[StereoFrontEnd]` of the configuration. */
    struct TOptions : public mrpt::config::CLoadableOptions {
        /// @name Step 1: Harris corners (the paper gives no values)
        /// @{
        int max_corners = 300;            ///< most corners kept, strongest first
        double harris_quality = 0.01;     ///< minimum response relative to the strongest
        double min_corner_distance = 10;  ///< [px] minimum distance between two corners
        int harris_block_size = 5;        ///< [px] side of the structure-tensor window
        double harris_k = 0.04;           ///< Harris & Stephens' k
        /// @}
        /// @name Step 2: stereo correspondence and depth range
        /// @{
        StereoMatcher::TOptions matching;  ///< its keys are in the same section
        double min_depth = 0.3;            ///< [m] nearer points are dropped
        double max_depth = 10.0;           ///< [m] farther points are dropped
        /// @}
        /// @name Step 3: descriptor
        /// @{
        double usurf_scale = 2.0;  ///< [px] U-SURF scale s (window 20 s wide)
        /// @}
        /// @name Step 4: R_t (defaults and the paper's values: TStereoPixelNoise)
        /// @{
        TStereoPixelNoise pixel_noise;  ///< keys sigma_disparity, sigma_row, sigma_col
        /// @}
        /// @name Steps 5-6: tracking and emission
        /// @{
        double track_search_radius = 80;             ///< [px] image motion between frames
        double track_ratio = 0.8;                    ///< descriptor ratio test, in (0, 1]
        double track_max_descriptor_distance = 0.5;  ///< Euclidean, unit-length descriptors
        int min_track_length = 3;                    ///< frames (paper: 3 consecutive poses)
        int max_landmarks_per_frame = 0;             ///< 0 = no limit (step 6)
        /// @}

        /** Reads every key of `section` listed above, keeping the defaults of missing ones,
         *  and validates them. \throw std::invalid_argument with one line naming the section
         *  and key: `[StereoFrontEnd] max_depth must be finite and > min_depth`. */
        void loadFromConfigFile(const mrpt::config::CConfigFileBase& cfg,
                                const std::string& section) override;
        void saveToConfigFile(mrpt::config::CConfigFileBase& cfg,
                              const std::string& section) const override;
        /** \throw std::invalid_argument naming `section` and the first invalid key. */
        void validate(const std::string& section) const;
    };

    /** A point of the current frame that passed steps 1-4, with its track (step 5). */
    struct TPoint {
        TStereoPixel pixel;               ///< left row, column and disparity [px]
        mrpt::math::TPoint3D point;       ///< z_t [m], left camera frame
        mrpt::math::CMatrixDouble33 cov;  ///< R_t [m²]
        core::USurfDescriptor::TDescriptor descriptor;
        double ncc = 0;  ///< stereo correlation score
        int64_t track_id = 0;
        uint32_t track_length = 1;  ///< consecutive frames, this one included
    };

    /** Counts of one frame (lastFrameStats()), or of several added with +=. */
    struct TFrameStats {
        size_t frames = 0;     ///< stereo pairs counted (1 for lastFrameStats())
        size_t rectified = 0;  ///< of those, rectified here from their calibration
        size_t corners = 0;    ///< step 1
        size_t matched = 0;    ///< matched in the right image at a positive disparity (step 2)
        double nearest_match = std::numeric_limits<double>::infinity();  ///< [m] depth
        double farthest_match = 0;  ///< [m] depth of the farthest matched corner
        size_t stereo = 0;          ///< passed step 2 (matched, depth in range)
        size_t points = 0;          ///< passed step 3 (with descriptor): points()
        size_t tracked = 0;         ///< continued a track of the previous frame
        size_t eligible = 0;        ///< track length >= min_track_length
        size_t emitted = 0;         ///< in the output (eligible, capped)
        /// why the (first) pair was rectified here (StereoRectifier), empty if none was
        std::string rectified_because;

        /** Adds the counts of `frame` and widens the depth range; keeps the first reason. */
        TFrameStats& operator+=(const TFrameStats& frame);
    };

    /** Empty if `frames` (the counts of one or more frames) emitted a landmark. Else one line
     *  for an error message: the step at which the last of the points were lost, what it had,
     *  and the keys of `options` (`[StereoFrontEnd]`) that govern it. */
    static std::string whyNoLandmarks(const TFrameStats& frames, const TOptions& options);

    /** \throw std::invalid_argument if the options are invalid. */
    explicit StereoFrontEnd(const TOptions& options);

    /** Runs steps 1-6 on one frame of this robot.
     *  \throw std::invalid_argument with a one-line reason if the images are missing, empty,
     *  not 8-bit, of another size than the calibration's, or the calibration or camera pose
     *  cannot be read (StereoGeometry::whyNotRectified(); then the tracks are left as they
     *  were). */
    mrpt::obs::CObservationVisualLandmarks::Ptr process(
        const mrpt::obs::CObservationStereoImages& obs);

    /** Every point of the last frame (steps 1-5), in detection order. */
    const std::vector<TPoint>& points() const { return m_points; }
    const TFrameStats& lastFrameStats() const { return m_stats; }
    const TOptions& options() const { return m_options; }
    /** Forgets all tracks (the next frame starts new ones; ids keep increasing). */
    void reset();

    /** `<ROBOT>_STEREO` → `<ROBOT>_LANDMARKS`; any other label gets `_LANDMARKS` appended. */
    static std::string landmarksLabel(const std::string& stereo_label);

  private:
    std::vector<TPoint> detect(const mrpt::obs::CObservationStereoImages& obs,
                               const StereoGeometry& geometry);
    void track(std::vector<TPoint>& current);
    std::vector<size_t> selectEmitted();

    TOptions m_options;
    StereoRectifier m_rectifier;
    std::vector<TPoint> m_points;  ///< the last frame's points: the previous frame for track()
    int64_t m_next_track_id = 0;
    TFrameStats m_stats;
};

}  // namespace mrpt_vslam::multirobot
