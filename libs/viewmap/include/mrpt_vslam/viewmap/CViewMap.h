#pragma once

#include <mrpt/config/CLoadableOptions.h>
#include <mrpt/maps/CMetricMap.h>
#include <mrpt/maps/TMetricMapTypesRegistry.h>
#include <mrpt/math/TPose2D.h>
#include <mrpt_vslam/viewmap/View.h>

#include <Eigen/Core>
#include <cstddef>
#include <optional>
#include <string>
#include <vector>

namespace mrpt_vslam::viewmap {

/** The map of view-based omnidirectional EKF SLAM (Valiente et al., "Information-based view
 *  initialization in visual SLAM with a single omnidirectional camera", RAS 2015;
 *  doc/view-slam.md §1): a set of views, each the planar pose where an omnidirectional
 *  image was taken plus that image's feature points.
 *
 *  The view poses are estimated by ViewMapEKF; this class is the MRPT-facing container the SLAM
 *  copies them into (addView(), setViewEstimate()), so the map can be serialized (final_map.gz),
 *  drawn (SceneViewer3D) and written to map.txt like any other CMetricMap. It does not build
 *  itself from observations.
 *
 *  Usage: create it directly, or from an `.ini` through `CMultiMetricMap` (`viewMap_count = 1`,
 *  render options in `<prefix>_renderOpts`); addView() at each new view, setViewEstimate() after
 *  each EKF step; saveMetricMapRepresentationToFile() writes `<prefix>.txt` (map.txt format) and
 *  `<prefix>_views.txt`. */
class CViewMap : public mrpt::maps::CMetricMap {
    DEFINE_SERIALIZABLE(CViewMap, mrpt_vslam::viewmap)

  public:
    /** 3D rendering ("<prefix>_renderOpts"). */
    struct TRenderOptions : public mrpt::config::CLoadableOptions {
        bool draw_ellipses = true;       ///< x-y covariance ellipse of each view
        double ellipse_quantiles = 3.0;  ///< ellipses at this many σ (> 0)
        double view_size = 0.3;          ///< [m] length of the mark of a view (> 0)
        bool draw_ids = false;           ///< a text label with the id of each view

        /// \throw std::invalid_argument naming the section and key of an invalid value.
        void loadFromConfigFile(const mrpt::config::CConfigFileBase& cfg,
                                const std::string& section) override;
        void dumpToTextStream(std::ostream& out) const override;
    } renderOptions;

    CViewMap() = default;

    /// @name Contents
    /// @{
    /** Appends a view, setting its id to its index, and returns that index. The covariance is
     *  stored exactly symmetric (its upper triangle mirrored).
     *  \throw std::invalid_argument for a non-finite pose, a covariance that is not finite and
     *         symmetric, or feature arrays of different lengths. */
    size_t addView(TView view);
    const std::vector<TView>& views() const { return m_views; }
    /// \throw std::out_of_range naming the index and the size.
    const TView& view(size_t i) const;
    /** The EKF's estimate of view i (ViewMapEKF::viewPose(), viewCovariance()), stored
     *  as addView() stores it; a relative asymmetry up to 1e-12 (rounding) is accepted.
     *  \throw std::invalid_argument for a bad index, a non-finite pose, or a covariance that is
     *         not finite and symmetric. */
    void setViewEstimate(size_t i, const mrpt::math::TPose2D& pose,
                         const Eigen::Matrix3d& covariance);
    size_t size() const { return m_views.size(); }
    /// @}

    /// @name CMetricMap interface
    /// @{
    bool isEmpty() const override;
    /** `<prefix>.txt`: `# id x y yaw cxx cxy cxyaw cyy cyyaw cyawyaw` (core::LandmarkFile view
     *  layout, yaw in radians); `<prefix>_views.txt`: `# id timestamp features image_file`
     *  (`-` for a view without image file).
     *  \throw std::runtime_error naming a file that cannot be written. */
    void saveMetricMapRepresentationToFile(const std::string& filNamePrefix) const override;
    /** Per view a triangle in the XY plane pointing along yaw, renderOptions.view_size long
     *  (all views in one CSetOfTriangles), its x-y covariance ellipse (skipped when that 2 × 2
     *  block is not positive definite) and optionally its id. */
    void getVisualizationInto(mrpt::opengl::CSetOfObjects& o) const override;
    std::string asString() const override;
    /// 0: not defined for view maps.
    float compute3DMatchingRatio(const mrpt::maps::CMetricMap* otherMap,
                                 const mrpt::poses::CPose3D& otherMapPose,
                                 const mrpt::maps::TMatchingRatioParams& params) const override;
    /// @}

    MAP_DEFINITION_START(CViewMap)
    mrpt_vslam::viewmap::CViewMap::TRenderOptions renderOpts;
    MAP_DEFINITION_END(CViewMap)

  protected:
    void internal_clear() override;
    /** Returns false: views are added by the SLAM (addView()), not from observations. */
    bool internal_insertObservation(
        const mrpt::obs::CObservation& obs,
        const std::optional<const mrpt::poses::CPose3D>& robotPose = std::nullopt) override;
    /// 0 (log-likelihood): a view map does not weigh observations.
    double internal_computeObservationLikelihood(
        const mrpt::obs::CObservation& obs, const mrpt::poses::CPose3D& takenFrom) const override;
    /// false for every observation.
    bool internal_canComputeObservationLikelihood(
        const mrpt::obs::CObservation& obs) const override;

  private:
    std::vector<TView> m_views;

    /** Throws std::invalid_argument, prefixed with `what`, for a non-finite pose, a covariance
     *  that is not finite and symmetric, or feature arrays of different lengths. */
    static void checkView(const TView& v, const std::string& what);
};

}  // namespace mrpt_vslam::viewmap
