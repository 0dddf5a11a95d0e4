#pragma once

#include <mrpt/math/CMatrixFixed.h>
#include <mrpt/math/TPoint3D.h>

#include <string>

namespace mrpt::obs {
class CObservationStereoImages;
}

namespace mrpt_vslam::multirobot {

/** A pixel of the left image with its disparity: row r, column c, disparity d (all in [px]);
 *  the point appears at (r, c − d − o) in the right image, o = c_x − c_x,right the offset of
 *  the two principal points' columns (StereoGeometry::disparityOffset(), 0 where they agree). */
struct TStereoPixel {
    double row = 0;
    double col = 0;
    double disparity = 0;
};

/** Standard deviations of the pixel measurements behind R_t (Gil et al. 2010, Sec. 3.2). The
 *  paper's σ_d = 1 px, σ_r = σ_c = 10 px are about 20 times too wide in σ for this project's
 *  front-end; the defaults are the values measured best on the office team (doc/multirobot.md). */
struct TStereoPixelNoise {
    double sigma_disparity = 0.5;  ///< σ_d [px]
    double sigma_row = 3.0;        ///< σ_r [px]
    double sigma_col = 3.0;        ///< σ_c [px]

    /// The paper's values: σ_d = 1 px, σ_r = σ_c = 10 px.
    static TStereoPixelNoise paper() { return {1.0, 10.0, 10.0}; }
};

/** The standard rectified stereo pair of Gil et al. (2010), Sec. 3.2, Eq. 12: two pin-hole
 *  cameras with parallel optical axes, the right one displaced by the baseline B along the left
 *  camera's x axis, same intrinsics (f_x, f_y, c_x, c_y) but for the right camera's c_x,right,
 *  which a rectification may shift (OpenCV's stereoRectify() without CALIB_ZERO_DISPARITY, as
 *  StereoRectifier and MRPT's `rawlog-edit --stereo-rectify` call it): the right image's
 *  columns are offset by o = c_x − c_x,right, taken off the columns' difference before Eq. 12.
 *
 *  Frame: MRPT's camera frame of the left camera, x right, y down, z forward. Eq. 12 writes
 *  Y = I(C_y − r)/d with Y pointing up; here Y = +B·(f_x/f_y)(r − c_y)/d points down, i.e.
 *  Y_here = −Y_Eq.12 (and f_x = f_y = f recovers the paper's X and Z exactly):
 *
 *    X = B (c − c_x) / d,   Y = B (f_x/f_y) (r − c_y) / d,   Z = f_x B / d      (Eq. 12)
 *
 *  The disparity is d = c − c_right > 0 (the paper writes the right pixel as (r, c + d), the
 *  same relation with the opposite sign convention for d).
 *
 *  Usage:
 *   1. `StereoGeometry g = StereoGeometry::fromObservation(stereo_obs);` (checks rectification)
 *   2. `auto p = g.triangulate({r, c, d}); auto R = g.covariance({r, c, d}, noise);`
 */
class StereoGeometry {
  public:
    /** \param fx, fy focal lengths [px]; \param cx, cy principal point [px];
     *  \param baseline B [m], distance between the optical centres;
     *  \param disparity_offset o = c_x − c_x,right [px] (0: both principal points agree).
     *  \throw std::invalid_argument if a value is not finite, or fx, fy or B is not positive. */
    StereoGeometry(double fx, double fy, double cx, double cy, double baseline,
                   double disparity_offset = 0);

    /** The geometry of a rectified stereo observation: intrinsics of `leftCamera`, baseline =
     *  x of `rightCameraPose`, offset = the difference of the two cameras' c_x.
     *  \throw std::invalid_argument (one line) if the pair is not rectified (whyNotRectified();
     *  StereoRectifier rectifies it) or its calibration cannot be read. */
    static StereoGeometry fromObservation(const mrpt::obs::CObservationStereoImages& obs);

    /** Why the calibration of `obs` is not that of a rectified pair (a distortion parameter of
     *  either camera non-zero, the two cameras' f_x, f_y or c_y apart, the right camera turned
     *  w.r.t. the left one or off its x axis), or empty if it is.
     *  \throw std::invalid_argument (one line) if a parameter is not finite, a focal length is
     *  not positive, a camera has the kannala_brandt (fisheye) model, or the right camera is not
     *  at +x of the left one. */
    static std::string whyNotRectified(const mrpt::obs::CObservationStereoImages& obs);

    /** Eq. 12: the 3D point [m] in the left camera frame (x right, y down, z forward).
     *  \throw std::invalid_argument unless the disparity is finite and positive. */
    mrpt::math::TPoint3D triangulate(const TStereoPixel& px) const;

    /** J = ∂(X, Y, Z)/∂(d, r, c) of Eq. 12 at `px` (columns in the order d, r, c):
     *
     *    [ −X/d        0             B/d ]
     *    [ −Y/d   B (f_x/f_y)/d       0  ]
     *    [ −Z/d        0              0  ]
     */
    mrpt::math::CMatrixDouble33 jacobian(const TStereoPixel& px) const;

    /** R_t = J R_sp Jᵀ with R_sp = diag(σ_d², σ_r², σ_c²) (Sec. 3.2) [m²]. */
    mrpt::math::CMatrixDouble33 covariance(const TStereoPixel& px,
                                           const TStereoPixelNoise& noise) const;

    /** Inverse of triangulate(): (r, c, d) of a point in the left camera frame.
     *  \throw std::invalid_argument unless the point is finite with z > 0. */
    TStereoPixel project(const mrpt::math::TPoint3D& point) const;

    double fx() const { return m_fx; }
    double fy() const { return m_fy; }
    double cx() const { return m_cx; }
    double cy() const { return m_cy; }
    double baseline() const { return m_baseline; }
    /// o = c_x − c_x,right [px]: a column difference c − c_right is the disparity d plus o.
    double disparityOffset() const { return m_disparity_offset; }

  private:
    double m_fx, m_fy, m_cx, m_cy, m_baseline, m_disparity_offset;
};

}  // namespace mrpt_vslam::multirobot
